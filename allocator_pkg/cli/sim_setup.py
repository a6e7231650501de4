"""What a closed-loop run of ``allocator-sim`` is made of, without ROS: a scenario's plant,
set-point and supply voltage, the node's command line, and the run's result and error."""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

from ..ros.process import node_command
from ..simulation.environment import Environment
from ..simulation.plant import Plant
from ..simulation.rov import Rov
from ..simulation.scenario import Scenario
from ..simulation.thrusters import Thrusters
from ..simulation.trace import Trace
from ..simulation.vessel import Vessel, VesselParameters
from ..vehicle.config import Vehicle


class SimulationError(RuntimeError):
    pass


@dataclass
class RunResult:
    metrics: dict[str, float]
    trace: Trace
    vehicle: Vehicle
    fault_intervals: list[tuple[float, float]]


def build_plant(scenario: Scenario, vehicle: Vehicle) -> Plant:
    if scenario.model == "dp_vessel":
        hull = Vessel(VesselParameters(coefficients=scenario.particulars.coefficients))
    else:
        hull = Rov()
    thrusters = Thrusters(vehicle, scenario.thruster_time_constant, scenario.voltage)
    environment = Environment(scenario.environment, scenario.seed, scenario.particulars)
    return Plant(hull, thrusters, environment, np.array(scenario.initial_position),
                 np.array([0.0, 0.0, scenario.initial_heading]))


def setpoint_vector(scenario: Scenario, planar: bool) -> np.ndarray:
    n, e, d = scenario.setpoint_position
    if planar:
        return np.array([n, e, scenario.setpoint_heading])
    return np.array([n, e, d, 0.0, 0.0, scenario.setpoint_heading])


def scenario_command(scenario: Scenario, log_level: str = "warn") -> list[str]:
    """``allocator_node`` on the scenario's vehicle, on sim time, allocating each wrench on
    arrival with the scenario's method and parameters."""
    parameters = ["use_sim_time:=true", "trigger:=input", f"method:={scenario.method}"]
    parameters += [f"{name}:={json.dumps(value) if not isinstance(value, str) else value}"
                   for name, value in scenario.parameters.items()]
    return node_command(scenario.vehicle, "--log-level", log_level, parameters=parameters)


class Voltage:
    """The supply voltage at a sim time: the scenario's, then each ramp linearly to its end value."""

    def __init__(self, scenario: Scenario):
        self.start = scenario.voltage
        self.ramps = [e for e in scenario.events if e.kind == "battery_ramp"]

    def at(self, t: float) -> float | None:
        voltage = self.start
        for ramp in self.ramps:
            if voltage is None or t < ramp.time:
                continue
            share = 1.0 if ramp.duration == 0.0 else min(1.0, (t - ramp.time) / ramp.duration)
            voltage = voltage + share * (float(ramp.value) - voltage)
        return voltage
