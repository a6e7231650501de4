"""A rotatable thruster that pushes onto a dead thruster (DNV-ST-0111 [3.11.4]): the thrust it
may give there, and whether it should push there at all.

Along a direction theta within the loss sector the force is beta(theta) of the propeller's,
beta rising along a straight line (Figure 3-6, :class:`~allocator_pkg.effectiveness.flushing.DeadFlushing`)
from beta at the centre to 1 at the sector's edges. Each sample:

- :func:`cut` caps the thrust at the least beta over the angles the window allows, so that no
  angle the method picks gives more force than the thruster has there;
- :func:`closed` decides whether the sector is better left alone: when the force the thruster is
  wanted to give along a direction inside it (``wanted``, the unconstrained solution's) exceeds
  what beta leaves there, and the nearer edge gives more along that direction, or when the
  wanted direction lies outside the sector. A closed sector is a forbidden sector for the sample
  (the crossing rules apply); a thruster pushing inside one leaves it toward the wanted side by
  rate steps at the thrust the loss leaves (:func:`exit_limits`), rather than dropping its thrust
  as a forbidden sector would make it. The flat cap alone would keep it where it is: a method
  sees no gain in turning while the cap stays the same over its window.

A reversible thruster's sectors stay open (a forbidden sector would forbid its reverse thrust
too, whose race goes the other way): its thrust is cut only.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from ..effectiveness.flushing import DeadFlushing
from ..effectiveness.model import AzimuthLimits
from ..vehicle.angles import wrap
from ..vehicle.config import RotationConfig
from .azimuth import AzimuthState, thrust_window

HYSTERESIS = 0.1
"""A closed sector opens again only when the wanted force is this fraction below what the loss
leaves, so that a request near the threshold does not open and close it sample by sample."""


def cut(limits: AzimuthLimits, losses: Sequence[DeadFlushing], range_low: float,
        range_high: float) -> tuple[float, float]:
    """Cut a rotatable thruster's thrust this sample, in place, to what it gives pushing onto
    dead thrusters: its static range ``range_low``/``range_high`` times the least loss factor
    over the directions it may push along this sample (its angle window, turned by pi on the
    reverse side). A window already beyond the cut moves to it, as a fault's does. Returns the
    thrust window (thrust_low, thrust_high)."""
    if limits.magnitude_max == 0.0:
        return limits.thrust_low, limits.thrust_high
    factor = 1.0
    if limits.line or limits.sigma > 0:
        factor = min(loss.lowest(limits.low, limits.high) for loss in losses)
        limits.thrust_high = min(limits.thrust_high, factor * range_high)
        limits.thrust_low = min(limits.thrust_low, limits.thrust_high)
    if limits.line or limits.sigma < 0:
        factor = min(loss.lowest(limits.low + math.pi, limits.high + math.pi) for loss in losses)
        limits.thrust_low = max(limits.thrust_low, factor * range_low)
        limits.thrust_high = max(limits.thrust_high, limits.thrust_low)
    if not limits.line and math.isfinite(limits.physical_max):
        limits.physical_max *= factor
    return limits.thrust_low, limits.thrust_high


def closed(loss: DeadFlushing, wanted: tuple[float, float], radius: float, hold: float, was_closed: bool) -> bool:
    """Whether the loss sector is left alone this sample (see the module docstring): ``wanted``
    is the force the thruster is wanted to give, ``radius`` its largest thrust; a wanted force
    below ``hold`` leaves the sector as it was."""
    magnitude = math.hypot(wanted[0], wanted[1])
    if magnitude <= hold:
        return was_closed
    direction = math.atan2(wanted[1], wanted[0])
    delta = abs(math.remainder(direction - loss.centre, 2.0 * math.pi))
    if delta >= loss.half_angle:
        return True
    inside = loss.factor(direction) * radius
    edge = radius * math.cos(loss.half_angle - delta)
    if edge <= inside:
        return False
    return magnitude > (1.0 - HYSTERESIS) * inside if was_closed else magnitude > inside


def exit_limits(loss: DeadFlushing, rotation: RotationConfig, state: AzimuthState, wanted: tuple[float, float],
                angle_step: float, thrust_range: tuple[float, float], thrust_step: float) -> AzimuthLimits:
    """The limits of a thruster pushing inside a closed loss sector: a rate step toward the edge
    on the wanted direction's side (on its own side when the wanted direction is the centre),
    stopping at the edge and inside the feasible sector, with its thrust window (:func:`cut`
    then caps it along that angle)."""
    towards = math.remainder(math.atan2(wanted[1], wanted[0]) - loss.centre, 2.0 * math.pi)
    if towards == 0.0:
        towards = math.remainder(state.angle - loss.centre, 2.0 * math.pi)
    side = 1.0 if towards >= 0.0 else -1.0
    edge = loss.centre + side * loss.half_angle
    to_edge = side * math.remainder(edge - state.angle, 2.0 * math.pi)
    angle = state.angle + side * max(0.0, min(angle_step, to_edge))
    angle = wrap(angle) if rotation.continuous else min(max(angle, rotation.azimuth_min), rotation.azimuth_max)
    low, high = thrust_window(state.thrust, thrust_step, *thrust_range)
    return AzimuthLimits(angle, angle, 1, max(low, 0.0), max(high, 0.0))
