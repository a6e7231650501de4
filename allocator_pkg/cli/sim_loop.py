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
from ..simulation.report import run_report
from ..simulation.scenario import Event, Scenario
from ..simulation.trace import Trace
from ..simulation.windows import fault_intervals
from .echo import format_sample
from .sim_link import NodeLink
from .sim_setup import (
    RunResult,
    SimulationError,
    Voltage,
    build_plant,
    scenario_command,
    setpoint_vector,
    warm_up_steps,
)

START_NS = 100_000_000_000
"""Sim time [ns] before the first warm-up step; the run starts after the warm-up."""


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
        self.schedule = scenario.schedule()
        self.voltage = Voltage(scenario)
        self.trace = Trace(names=list(self.vehicle.names), period=self.period, horizontal=scenario.horizontal)
        self.faults = fault_intervals(scenario.events, scenario.duration)

    def run(self, live: float = 0.0) -> RunResult:
        """The whole run; outputs into ``out``; with ``live`` > 0 a line of the live table every
        ``live`` simulated seconds."""
        node_log = self.out / "node.log"
        with child_process(scenario_command(self.scenario), output=node_log, dies_with_parent=True) as process, \
                contextlib.closing(NodeLink(self.out, node_log)) as link:
            link.wait_for_node(lambda: process.poll() is None)
            start_ns = self._warm_up(link)
            wall_start = time.monotonic()
            self._steps(link, start_ns, live)
            wall = time.monotonic() - wall_start
        report = run_report(self.scenario, self.trace, self.vehicle,
                            self.scenario.duration / wall if wall > 0 else math.inf)
        (self.out / "metrics.json").write_text(json.dumps(report, indent=2) + "\n")
        return RunResult(report["metrics"], self.trace, self.vehicle, self.faults, report)

    def _wrench(self, setpoint: np.ndarray) -> np.ndarray:
        """The controller's request for this step, in the six DOFs."""
        wrench = np.zeros(6)
        wrench[self.dofs] = self.controller.wrench(self.plant.eta, self.plant.nu, setpoint)
        return wrench

    def _warm_up(self, link: NodeLink) -> int:
        """Before t = 0: bring the node into step with the clock (no allocation), then hold the
        controller's first request, the equilibrium wrench (its integral holds the mean load),
        for the vehicle's fixed number of warm-up steps (``warm_up_steps``), so that the node's
        allocator settles there; the simulated thrusters start at its last commands. The
        node allocates the same requests in every run. The sim time [ns] of t = 0."""
        supply = self.voltage.at(0.0)
        position, heading = self.schedule.at(0.0)
        wrench = self._wrench(setpoint_vector(position, heading, self.plant.planar))
        t_ns = link.synchronise(START_NS, self.period_ns, supply)
        t_ns, commands = link.first_sample(t_ns, self.period_ns, wrench, supply)
        pose = self.plant.pose()
        steps = warm_up_steps(self.vehicle, self.period)
        for _ in range(steps - 1):
            t_ns += self.period_ns
            _, commands = link.step(t_ns, pose, supply, wrench, position, heading, record=False)
        self.plant.thrusters.start_at(np.array(commands.thrust), np.array(commands.azimuth))
        self.log(f"sim: warm-up: {steps} steps of the equilibrium request; thrusters start at "
                 + ", ".join(f"{name} {f:.4g} N" for name, f in zip(self.vehicle.names, commands.thrust)))
        return t_ns + self.period_ns

    def _steps(self, link: NodeLink, start_ns: int, live: float) -> None:
        """Every step of the scenario: its events, the supply voltage and the set-point, the
        controller's wrench against the node's answer, the trace, the live line, then the
        vehicle one period on."""
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
            position, heading = self.schedule.at(t)
            setpoint = setpoint_vector(position, heading, self.plant.planar)
            wrench = self._wrench(setpoint)
            status, commands = link.step(start_ns + k * self.period_ns, pose, supply, wrench, position, heading)
            thrust, azimuth = np.array(commands.thrust), np.array(commands.azimuth)
            faulted = any(start <= t + 1e-9 < end for start, end in self.faults)
            self.trace.add(t, pose.position, pose.attitude, position, heading, thrust, azimuth, status.saturated,
                           status.power, faulted, status.voltage)
            if live > 0.0 and t - printed >= live - 1e-9:
                printed = t
                error = self.trace.position_errors()[-1]
                self.log(f"{t:6.1f} s  err {error:6.2f} m  " + format_sample(commands, status))
            self.controller.integrate(self.plant.eta, setpoint, self.period,
                                      wrench_to_array(status.unallocated)[self.dofs])
            self.plant.step(thrust, azimuth, self.period)

    def _apply(self, link: NodeLink, event: Event) -> None:
        """A timed event: a fault (on the node and on the simulated thruster), clearing the
        faults, or a node parameter (the set-point's events are in the schedule, the battery
        ramps in the voltage)."""
        services = link.services
        if event.kind == "fault":
            value = 0.0 if event.mode == "failed" else event.value
            if value is None:                           # stuck where it is
                value = float(self.plant.thrusters.angle[self.vehicle.names.index(event.actuator)])
            response = services.set_fault(event.actuator, event.mode, value)
            if not response.success:
                raise SimulationError(f"set_actuator_fault refused: {response.message}")
            self.plant.thrusters.set_fault(event.actuator, event.mode, value)
            self.log(f"sim: {event.time:7.1f} s  {response.message}")
        elif event.kind == "clear_faults":
            self.log(f"sim: {event.time:7.1f} s  {services.clear_faults().message}")
            self.plant.thrusters.clear_faults()
        elif event.kind == "parameter":
            result = services.set_parameters({event.name: event.value})
            if not result.successful:
                raise SimulationError(f"parameter {event.name} refused: {result.reason}")
            self.log(f"sim: {event.time:7.1f} s  {event.name} = {event.value}")
