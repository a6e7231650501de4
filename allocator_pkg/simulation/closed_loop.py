"""One closed-loop run: the simulated vehicle, its environment and station-keeping controller,
the scenario's events and the trace, stepped one period (1 / rate_hz) per answer of an
allocator behind a :class:`Link`, so that a run is deterministic for a seed and runs as fast
as the allocator answers.

Two links answer: the real ``allocator_node`` as a child process on ROS 2 sim time
(``allocator_pkg.ros.sim_link``), and the allocator library in this process, doing what the
node does per sample (:mod:`.in_process`). The loop, its warm-up, events, trace and
``metrics.json`` are the same for both."""

from __future__ import annotations

import contextlib
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from ..configuration.parameters import load_vehicle
from .control_system import DpControl
from .electric_plant import ElectricPlant
from .metrics import METRIC_UNITS
from .plant import PLANAR, Pose
from .plant_metrics import plant_report
from .power_plant import PowerPlant
from .run_report import report_json, run_report
from .run_setup import RunResult, Voltage, WeatherScale, build_plant, setpoint_vector, warm_up_steps
from .scenario import Event, Scenario
from .trace import Trace
from .windows import fault_intervals

START_NS = 100_000_000_000
"""Sim time [ns] before the first warm-up step; the run starts after the warm-up."""
BALANCE_ROUNDS = 3
"""Warm-up holds after the first that take up the thrust losses (:meth:`ClosedLoop._warm_up`)."""


@dataclass
class Answer:
    """What the loop takes from one sample of the allocator, as ``allocation_status`` and
    ``thruster_commands`` carry it: thrusts [N] and angles [rad] commanded, the saturation flag,
    the power estimate (1.44), the supply voltage the limits followed [V] (NaN without voltage
    tables), the unallocated wrench [X, Y, Z, K, M, N] in the node's ``frame``, the power drawn
    from each source [kW] (``source_power``; None without power sources) and the consequence
    alarm."""

    thrust: np.ndarray
    azimuth: np.ndarray
    saturated: bool
    power: float
    voltage: float
    unallocated: np.ndarray
    source_power: np.ndarray | None = None
    consequence_alarm: bool = False


class Link(Protocol):
    """The allocator of one run. ``begin`` brings it into step at sim time ``t_ns`` [ns]
    (nothing allocated) and has it allocate ``wrench`` at the next step: (that step's time,
    its answer). ``step`` is one sample at ``t_ns``: the supply voltage, the available power
    the power plant reports (``power``, kW by source) and the vehicle's ``pose`` first, then
    the controller's ``wrench`` (with ``record``, a link that records writes the step with the
    set-point in force). Faults, a redundancy group's loss, a bus tie and parameters apply from the next
    sample; a refused one raises ``SimulationError``. ``live_line`` is the latest sample in one
    line of text."""

    def begin(self, t_ns: int, period_ns: int, supply: float | None, wrench: np.ndarray) -> tuple[int, Answer]: ...

    def step(self, t_ns: int, pose: Pose, supply: float | None, wrench: np.ndarray, setpoint_position,
             setpoint_heading: float, record: bool = True, power: dict[str, float] | None = None) -> Answer: ...

    def set_fault(self, actuator: str, mode: str, value: float) -> str: ...

    def set_group_fault(self, group: str) -> str: ...

    def set_bus_tie(self, name: str, closed: bool) -> str: ...

    def clear_faults(self) -> str: ...

    def set_parameter(self, name: str, value: Any) -> str: ...

    def live_line(self) -> str: ...


Connect = Callable[[Scenario, Path], contextlib.AbstractContextManager[Link]]
"""A scenario's link, open while the context lasts (outputs such as a log into the folder)."""


class ClosedLoop:
    """The vehicle, its controller and the scenario's events, stepped in lock-step with the
    allocator ``connect`` gives."""

    def __init__(self, scenario: Scenario, out: Path, connect: Connect, log: Callable[[str], None] = print) -> None:
        self.scenario, self.out, self.connect, self.log = scenario, out, connect, log
        out.mkdir(parents=True, exist_ok=True)
        self.vehicle = load_vehicle(scenario.vehicle)
        self.period_ns = round(1e9 / self.vehicle.rate_hz)
        self.period = self.period_ns * 1e-9
        self.plant = build_plant(scenario, self.vehicle)
        self.dofs = PLANAR if self.plant.planar else list(range(6))
        self.control = DpControl(scenario.control, scenario.gains, self.plant, scenario.seed)
        self.control.settle()
        self.schedule = scenario.schedule()
        self.voltage = Voltage(scenario)
        self.weather = WeatherScale(scenario)
        self.electric = None if scenario.power_plant is None else ElectricPlant(scenario.power_plant, self.vehicle)
        self.power_plant = self.electric or PowerPlant(self.vehicle)
        self.trace = Trace(names=list(self.vehicle.names), period=self.period, horizontal=scenario.horizontal,
                           sources=list(self.power_plant.sources), position_limit=scenario.position_limit)
        self.faults = fault_intervals(scenario.events, scenario.duration)

    def run(self, live: float = 0.0) -> RunResult:
        """The whole run; ``metrics.json`` into ``out``; with ``live`` > 0 a line of the live
        table every ``live`` simulated seconds. The real-time factor counts the run after the
        warm-up."""
        with self.connect(self.scenario, self.out) as link:
            start_ns = self._warm_up(link)
            wall_start = time.monotonic()
            self._steps(link, start_ns, live)
            wall = time.monotonic() - wall_start
        report = run_report(self.scenario, self.trace, self.vehicle,
                            self.scenario.duration / wall if wall > 0 else math.inf)
        if self.electric is not None:
            report["power_plant"] = plant_report(self.electric.record, self.electric.sources, self.period)
            report["metrics"] |= report["power_plant"]["metrics"]
            report["units"] |= {name: METRIC_UNITS[name] for name in report["power_plant"]["metrics"]}
        (self.out / "metrics.json").write_text(report_json(report))
        return RunResult(report["metrics"], self.trace, self.vehicle, self.faults, report,
                         None if self.electric is None else self.electric.record)

    def _warm_up(self, link: Link) -> int:
        """Before t = 0: bring the allocator into step with the clock (no allocation), then hold
        the controller's first request, the equilibrium wrench (its integral holds the mean
        load), for the vehicle's fixed number of warm-up steps (``warm_up_steps``), so that the
        allocator settles there; the simulated thrusters start at its last commands. With thrust
        losses, :data:`BALANCE_ROUNDS` more such holds, each after the integral has taken up what
        the thrusters fall short of the equilibrium (the vessel starts on station in balance).
        The allocator allocates the same requests in every run. The sim time [ns] of t = 0."""
        supply = self.voltage.at(0.0)
        position, heading = self.schedule.at(0.0)
        setpoint = setpoint_vector(position, heading, self.plant.planar)
        wrench = self.control.wrench(setpoint)
        t_ns, answer = link.begin(START_NS, self.period_ns, supply, wrench)
        pose = self.plant.pose()
        steps = warm_up_steps(self.vehicle, self.period)
        thrusters = self.plant.thrusters
        for balance in range(1 + (BALANCE_ROUNDS if thrusters.losses is not None else 0)):
            if balance:
                self.control.balance(thrusters.wrench()[self.dofs])
                wrench = self.control.wrench(setpoint)
            for _ in range(steps - 1 if balance == 0 else steps):
                t_ns += self.period_ns
                answer = link.step(t_ns, pose, supply, wrench, position, heading, record=False)
            thrusters.start_at(answer.thrust.copy(), answer.azimuth.copy())
        if self.electric is not None:
            self.electric.start(thrusters.thrust, thrusters.efficiency)
        self.log(f"sim: warm-up: {steps} steps of the equilibrium request; thrusters start at "
                 + ", ".join(f"{name} {f:.4g} N" for name, f in zip(self.vehicle.names, answer.thrust)))
        return t_ns + self.period_ns

    def _steps(self, link: Link, start_ns: int, live: float) -> None:
        """Every step of the scenario: its events, the supply voltage and the set-point, the
        controller's wrench against the allocator's answer, the trace, the live line, then the
        vehicle one period on."""
        pending = list(self.scenario.events)
        printed = -math.inf
        plant, trace, dofs = self.plant, self.trace, self.dofs
        for k in range(round(self.scenario.duration / self.period)):
            t = k * self.period
            while pending and pending[0].time <= t + 1e-9:
                self._apply(link, pending.pop(0))
            supply = self.voltage.at(t)
            if supply is not None:
                plant.thrusters.set_voltage(supply)
            plant.environment.scale = self.weather.at(t)
            pose = plant.pose()
            position, heading = self.schedule.at(t)
            setpoint = setpoint_vector(position, heading, plant.planar)
            self.control.measure()
            wrench = self.control.wrench(setpoint)
            answer = link.step(start_ns + k * self.period_ns, pose, supply, wrench, position, heading,
                               power=dict(self.power_plant.reported))
            faulted = any(start <= t + 1e-9 < end for start, end in self.faults)
            trace.add(t, pose.position, pose.attitude, position, heading, answer.thrust, answer.azimuth,
                      answer.saturated, answer.power, faulted, answer.voltage)
            trace.add_power(answer.source_power, self.power_plant.available(), answer.consequence_alarm)
            if live > 0.0 and t - printed >= live - 1e-9:
                printed = t
                error = trace.position_errors()[-1]
                self.log(f"{t:6.1f} s  err {error:6.2f} m  " + link.live_line())
            self.control.advance(setpoint, self.period, answer.unallocated[dofs])
            if self.electric is not None:
                plant.thrusters.cap = self.electric.thrust_caps()
            plant.step(answer.thrust, answer.azimuth, self.period)
            if self.electric is not None:
                self._switchboards_lost(self.electric.advance(plant.thrusters.thrust, self.period,
                                                              plant.thrusters.efficiency))

    def _switchboards_lost(self, names: list[str]) -> None:
        """Log each switchboard whose bus went dead (its thrusters' drives stop with it)."""
        for name in names:
            self.log(f"sim: {self.electric.time:7.1f} s  power plant: switchboard {name} dead (blackout)")

    def _apply(self, link: Link, event: Event) -> None:
        """A timed event: a fault (on the allocator and on the simulated thruster), a redundancy
        group's loss (on the allocator, the simulated thrusters of the group and the power
        plant's sources), a bus tie opening or closing, clearing the faults, the available power
        of a source (the power plant reports it from this step) or an allocator parameter (the
        set-point's events are in the schedule, the battery ramps in the voltage, the weather
        ramps in the weather scale)."""
        thrusters = self.plant.thrusters
        if event.kind == "group_fault":
            message = link.set_group_fault(event.name)
            for actuator in self.power_plant.trip_group(event.name):
                thrusters.set_fault(actuator, "failed", 0.0)
        elif event.kind == "bus_tie":
            message = link.set_bus_tie(event.name, bool(event.value))
            if self.electric is not None:
                message += "; " + self.electric.set_bus_tie(event.name, bool(event.value))
        elif event.kind == "power":
            self.power_plant.set_available(event.name, float(event.value))
            message = f"power plant: {event.name} gives {float(event.value):g} kW"
        elif event.kind == "fault":
            value = 0.0 if event.mode == "failed" else event.value
            if value is None:                           # stuck where it is
                value = float(thrusters.angle[self.vehicle.names.index(event.actuator)])
            message = link.set_fault(event.actuator, event.mode, value)
            thrusters.set_fault(event.actuator, event.mode, value)
        elif event.kind == "clear_faults":
            message = link.clear_faults()
            thrusters.clear_faults()
            self.power_plant.restore()
        elif event.kind == "parameter":
            message = link.set_parameter(event.name, event.value)
        elif event.kind == "generator_trip":
            message = self.electric.lose_set(event.name)
        else:
            return
        self.log(f"sim: {event.time:7.1f} s  {message}")
