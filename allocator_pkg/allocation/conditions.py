"""What the faults, surge speed and supply voltage in force decide, for every stage of a
sample: computed by the allocator when one of them changes (never per sample) and read by
the limits, method and actuation stages and the commit, so that no stage hands another what
it computed."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..effectiveness.actuators import drag_gain
from ..effectiveness.faults import FaultSet, lift_gains, static_ranges
from ..vehicle.config import Vehicle


@dataclass(frozen=True)
class Conditions:
    """The faults in force; ``low``/``high``, the signed static force range of every actuator
    (:func:`~allocator_pkg.effectiveness.faults.static_ranges`, before any rate limit);
    ``lift`` (1.48) and ``drag`` (1.57), each control surface's gains at the speed (0 for
    thrusters)."""

    faults: FaultSet
    low: np.ndarray
    high: np.ndarray
    lift: np.ndarray
    drag: np.ndarray

    @classmethod
    def of(cls, vehicle: Vehicle, faults: FaultSet, speed: float, voltage: float | None) -> Conditions:
        low, high = static_ranges(vehicle, faults, speed, voltage)
        drag = np.array([drag_gain(a.surface, vehicle.water_density, speed) if a.is_surface else 0.0
                         for a in vehicle.actuators])
        return cls(faults=faults, low=low, high=high, lift=lift_gains(vehicle, speed), drag=drag)
