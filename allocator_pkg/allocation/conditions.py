"""What the faults, surge speed and supply voltage in force decide, for every stage of a
sample: computed by the allocator when one of them changes (never per sample) and read by
the limits, method and actuation stages and the commit, so that no stage hands another what
it computed. The flushing zones in force follow the thrusters that work
(:mod:`~allocator_pkg.effectiveness.zones`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..effectiveness.actuators import drag_gain
from ..effectiveness.faults import FaultSet, lift_gains, static_ranges
from ..effectiveness.flushing import DeadFlushing
from ..effectiveness.power_rows import PowerRows
from ..effectiveness.zones import has_zones, zones_in_force
from ..vehicle.config import RotationConfig, Vehicle


@dataclass(frozen=True)
class Conditions:
    """The faults in force; ``low``/``high``, the signed static force range of every actuator
    (:func:`~allocator_pkg.effectiveness.faults.static_ranges`, before any rate limit);
    ``lift`` (1.48) and ``drag`` (1.57), each control surface's gains at the speed (0 for
    thrusters); ``rotations``, each rotatable thruster's rotation with the flushing zones in force
    (None for other actuators); ``losses``, the [3.11.4] losses of a thruster pushing onto a dead
    one, by actuator index; ``power``, the power rows a method that solves with them takes
    (:mod:`~allocator_pkg.effectiveness.power_rows`; None: no sources, or a method without
    rows); ``power_bound``, with rows, the proportional power bounds [N] that keep every source
    within its power on their own, for the fallback when the method fails. A thruster works
    while its force range is not zero; a fixed thruster whose push a zone forbids has that side
    of its range closed."""

    faults: FaultSet
    low: np.ndarray
    high: np.ndarray
    lift: np.ndarray
    drag: np.ndarray
    rotations: tuple[RotationConfig | None, ...]
    losses: dict[int, tuple[DeadFlushing, ...]]
    power: PowerRows | None = None
    power_bound: np.ndarray | None = None

    @classmethod
    def of(cls, vehicle: Vehicle, faults: FaultSet, speed: float, voltage: float | None) -> Conditions:
        low, high = static_ranges(vehicle, faults, speed, voltage)
        drag = np.array([drag_gain(a.surface, vehicle.water_density, speed) if a.is_surface else 0.0
                         for a in vehicle.actuators])
        rotations = tuple(a.rotation for a in vehicle.actuators)
        losses: dict[int, tuple[DeadFlushing, ...]] = {}
        if has_zones(vehicle):
            zones = zones_in_force(vehicle, ((low != 0.0) | (high != 0.0)).tolist())
            rotations, losses = zones.rotations, zones.losses
            for i, (reverse, forward) in enumerate(zones.closed):
                low[i], high[i] = (0.0 if reverse else low[i]), (0.0 if forward else high[i])
        return cls(faults=faults, low=low, high=high, lift=lift_gains(vehicle, speed), drag=drag,
                   rotations=rotations, losses=losses)
