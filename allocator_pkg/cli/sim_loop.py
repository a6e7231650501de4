"""One closed-loop run of ``allocator-sim``: the real ``allocator_node`` as a child process,
unchanged, with ``use_sim_time`` and ``trigger: input``; here the simulated vehicle, its
environment and station-keeping controller, stepped one period (1 / rate_hz) per answer of the
node (``sim_link``), so that a run is deterministic for a seed and runs as fast as the node
answers."""

from __future__ import annotations

import contextlib
import json
import math
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..configuration.parameters import load_vehicle
from ..ros.conversions import wrench_to_array
from ..ros.process import child_process
from ..simulation.controller import StationKeeping
from ..simulation.plant import PLANAR
from ..simulation.scenario import Event, Scenario
from ..simulation.trace import Trace
from .echo import format_sample
from .sim_link import NodeLink
from .sim_setup import RunResult, SimulationError, Voltage, build_plant, scenario_command, setpoint_vector

START_NS = 100_000_000_000
"""Sim time [ns] of the first warm-up step; the run starts after the warm-up."""


class ClosedLoop:
    """The vehicle, its controller and the scenario's events, stepped in lock-step with the node."""

    def __init__(self, scenario: Scenario, out: Path, log: Callable[[str], None] = print) -> None:
        self.scenario, self.out, self.log = scenario, out, log
        out.mkdir(parents=True, exist_ok=True)
        self.vehicle = load_vehicle(scenario.vehicle)
        self.period_ns = round(1e9 / self.vehicle.rate_hz)
        self.period = self.period_ns * 1e-9
        self.plant = build_plant(scenario, self.vehicle)
        self.dofs = PLANAR if self.plant.planar else list(range(6))
        self.controller = StationKeeping(scenario.gains)
        self.controller.settle(self.plant.eta, self.plant.environment_force())
        self.setpoint = setpoint_vector(scenario, self.plant.planar)
        self.voltage = Voltage(scenario)
        self.trace = Trace(names=list(self.vehicle.names), period=self.period, horizontal=scenario.horizontal)
        self.faults: list[tuple[float, float]] = []
        self.fault_start: float | None = None

    def run(self, live: float = 0.0) -> RunResult:
        """The whole run; outputs into ``out``; with ``live`` > 0 a line of the live table every
        ``live`` simulated seconds."""
        node_log = self.out / "node.log"
        with child_process(scenario_command(self.scenario), output=node_log, dies_with_parent=True) as process, \
                contextlib.closing(NodeLink(self.scenario, self.out, node_log)) as link:
            link.wait_for_node(lambda: process.poll() is None)
            start_ns = link.warm_up(START_NS, self.period_ns, self.voltage.at(0.0))
            wall_start = time.monotonic()
            self._steps(link, start_ns, live)
            wall = time.monotonic() - wall_start
        if self.fault_start is not None:
            self.faults.append((self.fault_start, self.scenario.duration))
        metrics = self.trace.metrics(self.vehicle)
        metrics["realtime_factor"] = self.scenario.duration / wall if wall > 0 else math.inf
        (self.out / "metrics.json").write_text(json.dumps({"scenario": self.scenario.name,
                                                           "method": self.scenario.method,
                                                           "seed": self.scenario.seed,
                                                           "duration": self.scenario.duration,
                                                           "metrics": metrics}, indent=2) + "\n")
        return RunResult(metrics, self.trace, self.vehicle, self.faults)

    def _steps(self, link: NodeLink, start_ns: int, live: float) -> None:
        """Every step of the scenario: its events, the supply voltage, the controller's wrench
        against the node's answer, the trace, the live line, then the vehicle one period on."""
        pending = list(self.scenario.events)
        printed = -math.inf
        for k in range(round(self.scenario.duration / self.period)):
            t = k * self.period
            while pending and pending[0].time <= t + 1e-9:
                self._apply(link, pending.pop(0))
            supply = self.voltage.at(t)
            if supply is not None:
                self.plant.thrusters.set_voltage(supply)
            pose = self.plant.pose()
            wrench = np.zeros(6)
            wrench[self.dofs] = self.controller.wrench(self.plant.eta, self.plant.nu, self.setpoint)
            status, commands = link.step(start_ns + k * self.period_ns, pose, supply, wrench)
            thrust, azimuth = np.array(commands.thrust), np.array(commands.azimuth)
            self.trace.add(t, pose.position, pose.attitude, self.scenario.setpoint_position,
                           self.scenario.setpoint_heading, thrust, azimuth, status.saturated, status.power,
                           self.fault_start is not None, status.voltage)
            if live > 0.0 and t - printed >= live - 1e-9:
                printed = t
                error = self.trace.position_errors()[-1]
                self.log(f"{t:6.1f} s  err {error:6.2f} m  " + format_sample(commands, status))
            self.controller.integrate(self.plant.eta, self.setpoint, self.period,
                                      wrench_to_array(status.unallocated)[self.dofs])
            self.plant.step(thrust, azimuth, self.period)

    def _apply(self, link: NodeLink, event: Event) -> None:
        """A timed event: a fault (on the node and on the simulated thruster), clearing the
        faults, or a node parameter."""
        services = link.services
        if event.kind == "fault":
            value = 0.0 if event.mode == "failed" else event.value
            if value is None:                           # stuck where it is
                value = float(self.plant.thrusters.angle[self.vehicle.names.index(event.actuator)])
            response = services.set_fault(event.actuator, event.mode, value)
            if not response.success:
                raise SimulationError(f"set_actuator_fault refused: {response.message}")
            self.plant.thrusters.set_fault(event.actuator, event.mode, value)
            if self.fault_start is None:
                self.fault_start = event.time
            self.log(f"sim: {event.time:7.1f} s  {response.message}")
        elif event.kind == "clear_faults":
            self.log(f"sim: {event.time:7.1f} s  {services.clear_faults().message}")
            self.plant.thrusters.clear_faults()
            if self.fault_start is not None:
                self.faults.append((self.fault_start, event.time))
                self.fault_start = None
        elif event.kind == "parameter":
            result = services.set_parameters({event.name: event.value})
            if not result.successful:
                raise SimulationError(f"parameter {event.name} refused: {result.reason}")
            self.log(f"sim: {event.time:7.1f} s  {event.name} = {event.value}")
