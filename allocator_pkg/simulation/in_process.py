"""The allocator library in the closed loop, in this process, without a node or ROS: a
:class:`~allocator_pkg.simulation.closed_loop.Link` that does per sample what
``allocator_node`` does between the wrench it receives and the commands it publishes, so that
a run gives the same trace and metrics as with the node in the loop
(``allocator_pkg.ros.sim_loop``), thousands of times faster to repeat.

What the node does, and so what this does, by the node's own rules
(:mod:`allocator_pkg.allocation.sample_rules`):

- configuration: the vehicle file's node section with ``trigger: input``, the scenario's
  ``method`` and ``parameters`` over it, parsed and checked as a whole (``parse_parameters``;
  a scenario's vehicle file holds its own geometry, as :mod:`.scenario` requires), and the
  allocator built on it;
- supply voltage (``battery_state``, a float32 field): with thrust tables at several voltages,
  each step's voltage, rounded to float32, sets the thrust limits; one the allocator refuses
  leaves the last (``set_supply_voltage``);
- speed (``odometry``): with control surfaces, each step's surge speed;
- the wrench: taken in the node's ``frame`` (FLU turned to FRD), allocated; the unallocated
  wrench given back in that frame (``wrench_between``);
- before the first wrench, the watchdog's zero thrust (``Watchdog``, ``Allocator.stop``),
  angles held;
- a fault: ``set_fault`` with the efficiency (DEGRADED) or angle (STUCK) and 0 otherwise, as
  ``~/set_actuator_fault`` carries it (``fault_request``); ``set_group_fault`` as
  ``~/set_group_fault``; ``clear_faults``;
- available power (``power_available``): each step's reported values, ``set_available_power``;
  the status's power per source (``Allocator.power.draw``, the figures of ``reading``);
- with redundancy groups, the consequence analysis at its rate on the sim clock
  (:mod:`.consequence_watch`, ``consequence_period``) and its alarm in the answer;
- a parameter: refused when read-only or not declared; else checked with the node's declared
  values and the change over them, and the running allocator reconfigured
  (``check_reconfigure``, ``reconfigure``), as the node's parameter callbacks do
  (``ros/node_base.py``).
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from ..allocation.allocator import Allocator
from ..allocation.result import AllocationResult
from ..allocation.sample_rules import Watchdog, fault_request, set_available_power, set_fault, set_supply_voltage
from ..configuration.declared import declared, declared_keys, typed_value
from ..configuration.parameters import parse_parameters
from ..configuration.params_file import read_parameters
from ..configuration.schema import key_for
from ..effectiveness.faults import FaultMode
from ..vehicle.config import ConfigError
from ..vehicle.frames import wrench_between
from ..vehicle.node_settings import INPUT, NODE_NAME
from .closed_loop import Answer
from .consequence_watch import ConsequenceWatch
from .live_text import wrapped
from .plant import Pose
from .run_setup import SimulationError
from .scenario import Scenario

STOPS = 3
"""Zero-thrust samples before the first wrench, as the node's link waits for three in a row."""


def node_parameters(scenario: Scenario) -> dict[str, Any]:
    """The parameters the node of ``scenario`` starts with: its vehicle file's section, then
    ``trigger``, ``method`` and the scenario's ``parameters`` (``allocator_pkg.ros.sim_loop``'s
    command line)."""
    return {**read_parameters(scenario.vehicle, NODE_NAME), "trigger": INPUT, "method": scenario.method,
            **scenario.parameters}


class InProcessLink:
    """The allocator of ``scenario``'s node, stepped in this process."""

    def __init__(self, scenario: Scenario) -> None:
        given = node_parameters(scenario)
        try:
            vehicle, self.settings = parse_parameters(given)
            self.allocator = Allocator(vehicle)
        except ConfigError as error:
            raise SimulationError(f"{scenario.vehicle}: {error}") from error
        self.parameters = declared(given, vehicle)
        self.declared_names = {name for name, _ in declared_keys(vehicle)} | set(given)
        self.follows_battery = vehicle.voltage_range is not None
        self.follows_speed = vehicle.has_surfaces
        self.rejected_voltages = 0
        self._last: AllocationResult | None = None
        self.watch = ConsequenceWatch(self.allocator) if vehicle.redundancy_groups else None
        self.watchdog = Watchdog(self.settings.wrench_timeout)

    # -- the samples ----------------------------------------------------------------------

    def begin(self, t_ns: int, period_ns: int, supply: float | None, wrench: np.ndarray) -> tuple[int, Answer]:
        """The node's zero thrust while no wrench has come (its watchdog on), at ``supply``,
        then the first sample of ``wrench`` at the step after."""
        if self.watchdog.check(t_ns, None)[0]:                  # no wrench yet: stale unless disabled
            for _ in range(STOPS):
                t_ns += period_ns
                self._supply(supply)
                self._tick(t_ns)
                self.allocator.stop()
        t_ns += period_ns
        self._supply(supply)
        return t_ns, self._allocate(wrench, t_ns)

    def step(self, t_ns: int, pose: Pose, supply: float | None, wrench: np.ndarray, setpoint_position,
             setpoint_heading: float, record: bool = True, power: dict[str, float] | None = None) -> Answer:
        """One sample: the battery's voltage, the available power reported, the odometry's
        surge speed, then ``wrench``."""
        self._supply(supply)
        if power:
            set_available_power(self.allocator, list(power), list(power.values()))
        if self.follows_speed:
            speed = float(pose.velocity[0])
            if math.isfinite(speed):
                self.allocator.set_speed(speed)
        return self._allocate(wrench, t_ns)

    def _tick(self, t_ns: int) -> None:
        if self.watch is not None:
            self.watch.tick(t_ns, self.settings)

    def _supply(self, volts: float | None) -> None:
        """``battery_state``'s voltage (float32) to the allocator, when it follows one."""
        if volts is None or not self.follows_battery:
            return
        try:
            set_supply_voltage(self.allocator, volts)
        except ValueError:
            self.rejected_voltages += 1

    def _allocate(self, wrench: np.ndarray, t_ns: int) -> Answer:
        frame = self.settings.frame
        allocator = self.allocator
        self.watchdog.check(t_ns, t_ns)
        self._tick(t_ns)
        result = self._last = allocator.allocate(wrench_between(wrench, frame))
        if self.watch is not None:
            self.watch.observe(result.requested, t_ns, self.settings)
        voltage = allocator.voltage
        limit = allocator.power_limit
        drawn = None if limit is None else allocator.power.draw(result.thrust, limit)
        return Answer(result.thrust.copy(), result.azimuth.copy(), bool(result.saturated), float(result.power),
                      math.nan if voltage is None else float(voltage), wrench_between(result.unallocated, frame),
                      source_power=drawn,
                      consequence_alarm=self.watch is not None and self.watch.alarm)

    def live_line(self) -> str:
        """Every actuator's thrust [N] and angle [deg], then the solver's figures, in lines of at
        most :data:`~.live_text.WIDTH` characters."""
        result = self._last
        if result is None:
            return ""
        parts = [f"{name} {thrust:9.1f} N" + (f" @{math.degrees(angle):6.1f}" if angle != 0.0 else "")
                 for name, thrust, angle in zip(self.allocator.names, result.thrust, result.azimuth)]
        figures = [f"sat {'YES' if result.saturated else 'no '} {result.iterations:5d} it {result.status}"]
        return "\n".join(wrapped(parts) + wrapped(figures, "|| "))

    # -- faults and parameters ------------------------------------------------------------

    def set_fault(self, actuator: str, mode: str, value: float) -> str:
        fault = FaultMode[mode.upper()]
        try:
            return set_fault(self.allocator, actuator, fault, *fault_request(fault, value))
        except ValueError as error:
            raise SimulationError(f"set_actuator_fault refused: {error}") from error

    def set_group_fault(self, group: str) -> str:
        try:
            self.allocator.set_group_fault(group)
        except ValueError as error:
            raise SimulationError(f"set_group_fault refused: {error}") from error
        return f"redundancy group {group} failed from the next sample"

    def set_bus_tie(self, name: str, closed: bool) -> str:
        try:
            return self.allocator.set_bus_tie(name, closed)
        except ValueError as error:
            raise SimulationError(f"set_bus_tie refused: {error}") from error

    def clear_faults(self) -> str:
        had = sorted(self.allocator.faults)
        self.allocator.clear_faults()
        return f"cleared faults of {', '.join(had)}" if had else "no faults were set"

    def set_parameter(self, name: str, value: Any) -> str:
        """One parameter changed as the node changes it, from the next sample; SimulationError
        when the node would refuse it (nothing changes then)."""
        key = key_for(name)
        if name not in self.declared_names:
            raise SimulationError(f"parameter {name} refused: it is not declared")
        if key is not None and key.read_only:
            raise SimulationError(f"parameter {name} refused: it is read-only")
        candidate = {**self.parameters, name: typed_value(name, value)}
        try:
            vehicle, settings = parse_parameters(candidate)
            self.allocator.check_reconfigure(vehicle)
        except ValueError as error:
            raise SimulationError(f"parameter {name} refused: {error}") from error
        self.allocator.reconfigure(vehicle)
        self.settings, self.parameters = settings, candidate
        self.watchdog.timeout = settings.wrench_timeout
        return f"{name} = {value}"


@contextlib.contextmanager
def in_process_link(scenario: Scenario, out: Path) -> Iterator[InProcessLink]:
    """The in-process link of ``scenario`` (a :data:`~.closed_loop.Connect`; it writes nothing into ``out``)."""
    yield InProcessLink(scenario)
