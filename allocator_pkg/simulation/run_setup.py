"""What a closed-loop run is made of, whichever allocator answers it: a scenario's plant,
set-point and supply voltage, the warm-up's length, and the run's result and error."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..vehicle.config import Vehicle
from .electric_plant import PlantRecord
from .environment import Environment
from .plant import Plant
from .rov import Rov
from .scenario import Scenario
from .thrusters import Thrusters
from .trace import Trace
from .vessel import Vessel, VesselParameters

WARM_UP_MARGIN = 5.0
"""[s] of equilibrium wrench beyond what the rate limits need (a method's own dynamics, as
the dynamic law's, settle in it)."""


class SimulationError(RuntimeError):
    pass


@dataclass
class RunResult:
    metrics: dict[str, float]
    trace: Trace
    vehicle: Vehicle
    fault_intervals: list[tuple[float, float]]
    report: dict
    """What metrics.json holds (``simulation.report.run_report``)."""
    plant: PlantRecord | None = None
    """The simulated electric power plant's record, with a scenario's ``power_plant``."""


def build_plant(scenario: Scenario, vehicle: Vehicle) -> Plant:
    if scenario.model == "dp_vessel":
        hull = Vessel(VesselParameters(coefficients=scenario.particulars.coefficients))
    else:
        hull = Rov()
    thrusters = Thrusters(vehicle, scenario.thruster_time_constant, scenario.voltage, trip=scenario.fault_trip,
                          losses=scenario.thrust_losses)
    environment = Environment(scenario.environment, scenario.seed, scenario.particulars, scenario.duration,
                              scenario.setpoint_heading)
    return Plant(hull, thrusters, environment, np.array(scenario.initial_position),
                 np.array([0.0, 0.0, scenario.initial_heading]))


def setpoint_vector(position, heading: float, planar: bool) -> np.ndarray:
    """The controller's set-point: [north, east, heading] or [north, east, down, 0, 0, heading]."""
    n, e, d = position
    if planar:
        return np.array([n, e, heading])
    return np.array([n, e, d, 0.0, 0.0, heading])


def warm_up_steps(vehicle: Vehicle, period: float) -> int:
    """How many steps of the equilibrium wrench bring the node's commands to it from zero
    thrust, a fixed number for a vehicle: the time the slowest thrust takes across its whole
    range at its rate limit or the slowest azimuth half a turn, whichever is longer, plus
    WARM_UP_MARGIN."""
    longest = 0.0
    for actuator in vehicle.actuators:
        if actuator.thrust_rate_max > 0.0:
            longest = max(longest, (actuator.thrust_max - actuator.thrust_min) / actuator.thrust_rate_max)
        if actuator.rotatable and actuator.rotation.rate_max > 0.0:
            longest = max(longest, math.pi / actuator.rotation.rate_max)
    return math.ceil((longest + WARM_UP_MARGIN) / period)


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


class WeatherScale:
    """The scale of the environment at a sim time (:class:`~.environment.Environment`'s
    ``scale``): 1, then each weather ramp linearly to its end value."""

    def __init__(self, scenario: Scenario):
        self.ramps = [e for e in scenario.events if e.kind == "weather_ramp"]

    def at(self, t: float) -> float:
        scale = 1.0
        for ramp in self.ramps:
            if t < ramp.time:
                continue
            share = 1.0 if ramp.duration == 0.0 else min(1.0, (t - ramp.time) / ramp.duration)
            scale = scale + share * (float(ramp.value) - scale)
        return scale
