"""The node's rules for each sample, without ROS: what ``allocator_node``
(:mod:`allocator_pkg.ros.runtime` and its inputs) and the in-process simulation
(:mod:`allocator_pkg.simulation.in_process`) both do between what reaches the node and the
allocator, so that the two give the same samples.

- the wrench input's watchdog (:class:`Watchdog`): stale when no valid wrench came for
  ``wrench_timeout`` seconds (0 disables it), or none has come yet; a stale sample commands
  zero thrust (``Allocator.stop``), angles held;
- the frame: a wrench comes in the node's ``frame`` and is allocated in FRD, the unallocated
  wrench goes back in that frame (:func:`~allocator_pkg.vehicle.frames.wrench_between`);
- the supply voltage (:func:`set_supply_voltage`): ``BatteryState.voltage`` is a float32 field,
  so the allocator gets the voltage rounded to float32; one it refuses leaves the last;
- a fault (:func:`fault_request`, :func:`set_fault`): ``~/set_actuator_fault`` carries the
  efficiency of DEGRADED and the angle of STUCK, 0 otherwise, from the next sample;
- the available power (:func:`set_available_power`): the sources a message names with their
  values [kW], refused whole when the two lists differ in length;
- the consequence analysis (:func:`consequence_period`): at every multiple of 1 / rate of the
  clock; rate 0 turns it off, and its alarm with it.

Everything here works on nanosecond stamps of the node's clock (simulated time works alike)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..effectiveness.faults import FaultMode
from .allocator import Allocator

NS = 1_000_000_000
"""Nanoseconds per second."""


class Watchdog:
    """Input is stale when no valid wrench came for ``timeout`` seconds (0 disables), or none
    has come yet. :meth:`check` returns the state and, on a change only, a log line and its
    severity (``info`` or ``warn``)."""

    def __init__(self, timeout: float):
        self.timeout = timeout
        self.stale = False

    def is_stale(self, now_ns: int, last_ns: int | None) -> bool:
        """Whether the input, last valid at ``last_ns`` (None: never), is stale at ``now_ns``;
        no state changes."""
        return self.timeout > 0.0 and (last_ns is None or now_ns - last_ns > round(self.timeout * 1e9))

    def check(self, now_ns: int, last_ns: int | None) -> tuple[bool, tuple[str, str] | None]:
        stale = self.is_stale(now_ns, last_ns)
        if stale == self.stale:
            return stale, None
        self.stale = stale
        if stale and last_ns is None:
            return stale, ("info", "waiting for wrench_command: commanding zero thrust")
        if stale:
            return stale, ("warn", f"no valid wrench for {self.timeout:g} s: commanding zero thrust")
        return stale, ("info", "wrench input resumed")


def set_supply_voltage(allocator: Allocator, volts: float) -> None:
    """``battery_state``'s voltage [V] to ``allocator``, as the float32 the message carries;
    ValueError (nothing changes) for one the allocator refuses (NaN, outside its tables)."""
    allocator.set_voltage(float(np.float32(volts)))


def fault_request(mode: FaultMode, value: float) -> tuple[float, float]:
    """(efficiency, angle) that ``~/set_actuator_fault`` carries for ``mode`` with ``value``: the
    efficiency of DEGRADED, the angle [rad] of STUCK, 0 for the other field and other modes."""
    return (value if mode == FaultMode.DEGRADED else 0.0, value if mode == FaultMode.STUCK else 0.0)


def set_fault(allocator: Allocator, actuator: str, mode: FaultMode, efficiency: float, angle: float) -> str:
    """One actuator's fault from the next sample (``Allocator.set_fault``: ValueError, nothing
    changed, when it refuses); what the node answers."""
    allocator.set_fault(actuator, mode, efficiency=efficiency, angle=angle)
    return f"{actuator}: {mode.name} from the next sample"


def set_available_power(allocator: Allocator, sources: Sequence[str], values: Sequence[float]) -> None:
    """The available power [kW] of the ``sources`` named, from the next sample; ValueError
    (nothing changed) when the lists differ in length or the allocator refuses a value."""
    if len(sources) != len(values):
        raise ValueError(f"{len(sources)} sources but {len(values)} values")
    allocator.set_available_power(dict(zip(sources, values)))


def consequence_period(rate: float) -> int | None:
    """[ns] between two consequence analyses at ``rate`` [Hz] (``consequence.rate``); None when
    the analysis is off (rate 0)."""
    return round(NS / rate) if rate > 0.0 else None
