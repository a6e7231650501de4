"""The bench's step test on the node (``step_test.enabled``, ``~/hold_actuator``): one actuator
held at a small thrust for a bounded time, every other one set FAILED. Each sample then
allocates the wrench the held thrust gives along the actuator's current direction, so that the
actuator alone meets it through the same limits, faults, rate limits and dead band as any
sample's. When the hold ends the faults in force before it come back.

Plain logic on the allocator, so that it is tested without a node; the runtime keeps the hold
in force and ends it (its duration, a stale input, a fault service, a parameter change,
deactivation). A hold is refused while the input is stale, since the next sample would end it."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..allocation.allocator import Allocator
from ..effectiveness.faults import Fault, FaultMode
from ..vehicle.node_settings import NodeSettings


@dataclass
class Hold:
    """One actuator held (``index``) at ``thrust`` [N] until ``end`` [ns of the node clock]; the
    faults and failed redundancy groups in force before it."""

    index: int
    thrust: float
    end: int
    faults: dict[str, Fault]
    groups: tuple[str, ...] = ()

    @classmethod
    def start(cls, allocator: Allocator, actuator: str, thrust: float, end: int) -> Hold:
        """Hold ``actuator`` (checked by :func:`refusal`): every other actuator FAILED from now."""
        names = allocator.names
        saved = allocator.faults
        for name in names:
            if name != actuator:
                allocator.set_fault(name, FaultMode.FAILED)
        return cls(names.index(actuator), float(thrust), end, saved, allocator.group_faults)

    def wrench(self, allocator: Allocator) -> np.ndarray:
        """The wrench (FRD) the held thrust gives along the held actuator's current direction."""
        return allocator.configuration_matrix()[:, self.index] * self.thrust

    def release(self, allocator: Allocator) -> None:
        """Put back the faults and failed groups in force before the hold."""
        allocator.clear_faults()
        for name, fault in self.faults.items():
            allocator.set_fault(name, fault.mode, efficiency=fault.efficiency, angle=fault.angle)
        for group in self.groups:
            allocator.set_group_fault(group)


def refusal(allocator: Allocator, settings: NodeSettings, actuator: str, thrust: float, duration: float,
            active: bool, stale: bool = False) -> str | None:
    """Why ``actuator`` cannot be held at ``thrust`` [N] for ``duration`` [s], or None: unless
    step_test.enabled, beyond step_test.thrust_share of the actuator's largest thrust or
    step_test.duration_max, for a control surface, while the runtime is not ``active``, while
    the wrench input is ``stale`` (the watchdog would end the hold at the next sample), and for
    an actuator acting on no controlled DOF."""
    if not settings.step_test_enabled:
        return "step_test.enabled is false (enable it on the bench only)"
    names = allocator.names
    if actuator not in names:
        return f"unknown actuator '{actuator}'; actuators: {', '.join(names)}"
    index = names.index(actuator)
    config = allocator.vehicle.actuators[index]
    if config.is_surface:
        return f"{actuator} is a control surface: it has no thrust of its own to hold"
    largest = max(config.thrust_max, -config.thrust_min)
    limit = settings.step_test_thrust_share * largest
    if not (math.isfinite(thrust) and abs(thrust) <= limit):
        return (f"thrust {thrust:g} N of {actuator}: at most {limit:g} N in magnitude "
                f"(step_test.thrust_share {settings.step_test_thrust_share:g} of {largest:g} N)")
    if not (math.isfinite(duration) and 0.0 < duration <= settings.step_test_duration_max):
        return f"duration {duration:g} s: more than 0 and at most step_test.duration_max " \
               f"{settings.step_test_duration_max:g} s"
    if not active:
        return "not active: no samples to hold an actuator in"
    if stale:
        return (f"wrench_command is stale (no valid wrench for {settings.wrench_timeout:g} s): send wrenches (zero) "
                "on it before and during the hold, which the watchdog ends as soon as it is stale")
    column = allocator.configuration_matrix()[list(allocator.vehicle.dof_indices), index]
    if not np.any(column):
        return f"{actuator} acts on none of the controlled DOFs ({', '.join(allocator.dofs)})"
    return None
