"""``~/get_capability``: the largest scale along a wrench direction that the actuators give
under the faults, battery voltage, speed and available power in force now
(:class:`~allocator_pkg.capability.envelope.Capability`, built once per configuration)."""

from __future__ import annotations

import threading

import numpy as np

from ..allocation.allocator import Allocator
from ..capability.envelope import Capability
from ..vehicle.frames import wrench_between
from .power_report import available_text


class CapabilityQuery:
    """The capability analysis of the allocator's configuration, kept until it changes."""

    def __init__(self) -> None:
        self._capability: Capability | None = None

    def answer(self, allocator: Allocator, lock: threading.Lock, frame: str,
               direction: np.ndarray) -> tuple[bool, str, float, np.ndarray]:
        """(success, message, scale, wrench) for ``direction``, a wrench in the node's ``frame``;
        the wrench there in the node's frame too. What is in force is read under ``lock``; the
        programme runs outside it."""
        if not np.all(np.isfinite(direction)):
            return False, f"the direction must be finite, got {direction.tolist()}", 0.0, np.zeros(6)
        body = wrench_between(direction, frame)
        with lock:
            if self._capability is None or self._capability.vehicle is not allocator.vehicle:
                try:
                    self._capability = Capability(allocator.vehicle, allocator.method, allocator.speed)
                except ValueError as error:
                    return False, str(error), 0.0, np.zeros(6)
            faults, speed, voltage = allocator.faults, allocator.speed, allocator.voltage
            power = None if allocator.power_limit is None else (allocator.power, allocator.power_limit)
            capability = self._capability
        if not np.any(body[list(capability.vehicle.dof_indices)]):
            return False, (f"the direction has no component in the controlled DOFs "
                           f"({', '.join(capability.vehicle.dofs)})"), 0.0, np.zeros(6)
        scale, wrench = capability.reach(body, faults, speed, voltage, power)
        where = f", {voltage:g} V" if voltage is not None else ""
        where += f", available power {available_text(power[0])}" if power is not None else ""
        return True, (f"steady state with {len(faults)} faults, speed {speed:g} m/s{where}, method "
                      f"{capability.method}"), scale, wrench_between(wrench, frame)
