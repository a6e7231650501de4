"""Flushing between thrusters, DNV-ST-0111 [3.11.3] and [3.11.4]: where a thruster's race hits
another thruster.

Thruster i flushes thruster j when the angle between i's thrust direction and the vector from j
to i is less than a half-angle: pushing away from j sends i's race onto j. Angles here are
thrust angles in the body frame (FRD): 0 forward, pi/2 to starboard, the angle of an azimuth
thruster.

- [3.11.3], a working thruster: i may not flush j closer than 15 D (D the diameter of i, s the
  horizontal distance), within arctan(0.1 + D / s) (:func:`flushing_zones`), unless j is a
  tunnel thruster. The sector's edges are allowed ("less than").
- [3.11.4], a dead thruster: i may flush it but loses thrust, closer than 8 D (open propeller)
  or 4 D (ducted), within arctan(0.6 D / s) (open) or arctan(0.35 D / s) (ducted); pointing
  straight at it the thrust is beta = 1 - 1 / (0.02 (s/D)^2 + 0.25 s/D + 1.2) of the nominal,
  and Figure 3-6 interpolates linearly in Cartesian coordinates out to 1 at the sector's edges
  (:func:`dead_flushing`, :class:`DeadFlushing`). A dead tunnel thruster may be flushed freely.

After the public transcription of [3.11.3] and [3.11.4] in the repository
WilliamBoland1/Prosjektoppgave_Collab (``dp_capability/models/Descriptions/forbidden_zones.md``
and ``dead_flushing.md``); not verified by DNV.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from ..vehicle.angles import ANGLE_TOLERANCE

FLUSHING_DISTANCE = 15.0
"""[3.11.3] In diameters of the flushing thruster."""

DEAD_FLUSHING_DISTANCE_OPEN = 8.0
"""[3.11.4] In diameters of an open flushing propeller."""

DEAD_FLUSHING_DISTANCE_DUCTED = 4.0
"""[3.11.4] In diameters of a ducted flushing propeller."""


@dataclass(frozen=True)
class Unit:
    """A thruster's horizontal position [m] (body frame), diameter [m], whether it is a tunnel
    thruster and whether its propeller is ducted."""

    name: str
    x: float
    y: float
    diameter: float
    tunnel: bool
    ducted: bool = False


@dataclass(frozen=True)
class Zone:
    """``thruster`` may not push within ``half_angle`` of ``centre`` [rad] (it would flush ``flushed``)."""

    thruster: str
    flushed: str
    centre: float
    half_angle: float

    @property
    def sector(self) -> tuple[float, float]:
        """(start, end) [rad], counter-clockwise in the body frame, start in (-pi, pi]."""
        start = math.remainder(self.centre - self.half_angle, 2.0 * math.pi)
        return start, start + 2.0 * self.half_angle

    def forbids(self, angle: float) -> bool:
        """Whether a thrust along ``angle`` [rad] is strictly inside the zone."""
        return abs(math.remainder(angle - self.centre, 2.0 * math.pi)) < self.half_angle - ANGLE_TOLERANCE


def half_angle(diameter: float, distance: float) -> float:
    """arctan(0.1 + D / s) [rad], [3.11.3]."""
    return math.atan(0.1 + diameter / distance)


def _offset(flushing: Unit, flushed: Unit) -> tuple[float, float, float]:
    """(dx, dy, s): the vector from ``flushed`` to ``flushing`` and its length."""
    dx, dy = flushing.x - flushed.x, flushing.y - flushed.y
    distance = math.hypot(dx, dy)
    if distance == 0.0:
        raise ValueError(f"{flushing.name} and {flushed.name} are at the same horizontal position")
    return dx, dy, distance


def flushing_zones(units: Sequence[Unit]) -> list[Zone]:
    """Every [3.11.3] zone among the working ``units``: each flushing thruster i and flushed j
    (not a tunnel) closer than 15 D_i."""
    zones = []
    for flushing in units:
        for flushed in units:
            if flushed is flushing or flushed.tunnel:
                continue
            dx, dy, distance = _offset(flushing, flushed)
            if distance < FLUSHING_DISTANCE * flushing.diameter:
                zones.append(Zone(flushing.name, flushed.name, math.atan2(dy, dx),
                                  half_angle(flushing.diameter, distance)))
    return zones


@dataclass(frozen=True)
class DeadFlushing:
    """[3.11.4]: ``thruster`` pushing within ``half_angle`` of ``centre`` [rad] flushes the dead
    ``flushed`` and gives ``factor`` of its thrust along ``centre``, rising linearly in Cartesian
    coordinates (Figure 3-6) to 1 at the sector's edges."""

    thruster: str
    flushed: str
    centre: float
    half_angle: float
    beta: float

    @property
    def sector(self) -> tuple[float, float]:
        """(start, end) [rad], counter-clockwise in the body frame, start in (-pi, pi]."""
        start = math.remainder(self.centre - self.half_angle, 2.0 * math.pi)
        return start, start + 2.0 * self.half_angle

    def inside(self, angle: float) -> bool:
        """Whether a thrust along ``angle`` [rad] is strictly inside the sector."""
        return abs(math.remainder(angle - self.centre, 2.0 * math.pi)) < self.half_angle - ANGLE_TOLERANCE

    def factor(self, angle: float) -> float:
        """beta_T,flushing dead along ``angle``: the radius, along that ray, of the straight line
        from beta (cos c, sin c) to (cos(c +- phi), sin(c +- phi)),
        beta sin(phi) / (sin(phi - |delta|) + beta sin|delta|); 1 outside the sector."""
        delta = abs(math.remainder(angle - self.centre, 2.0 * math.pi))
        if delta >= self.half_angle:
            return 1.0
        phi, beta = self.half_angle, self.beta
        return beta * math.sin(phi) / (math.sin(phi - delta) + beta * math.sin(delta))

    def lowest(self, low: float, high: float) -> float:
        """The least factor over the angles [low, high] [rad] (the whole circle when the arc is
        2 pi or wider): at the arc's ends, the centre, or the foot of the perpendicular from the
        origin to the notch's line, whichever of those the arc holds."""
        if not (math.isfinite(low) and math.isfinite(high)) or high - low >= 2.0 * math.pi:
            candidates = [self.centre, *self._feet()]
        else:
            candidates = [low, high] + [a for a in (self.centre, *self._feet())
                                        if (a - low) % (2.0 * math.pi) <= high - low]
        return min(self.factor(a) for a in candidates)

    def _feet(self) -> tuple[float, ...]:
        """The directions of least radius on each side's line, where the foot of the
        perpendicular from the origin lies between the centre and the edge."""
        phi, beta = self.half_angle, self.beta
        ax, bx, by = beta, math.cos(phi), math.sin(phi)
        ex, ey = bx - ax, by
        t = -(ax * ex) / (ex * ex + ey * ey)
        if not 0.0 < t < 1.0:
            return ()
        delta = math.atan2(t * ey, ax + t * ex)
        return (self.centre - delta, self.centre + delta)


def dead_flushing_factor(distance: float, diameter: float) -> float:
    """beta = 1 - 1 / (0.02 (s/D)^2 + 0.25 s/D + 1.2), [3.11.4], along the centre of the sector."""
    ratio = distance / diameter
    return 1.0 - 1.0 / (0.02 * ratio * ratio + 0.25 * ratio + 1.2)


def dead_flushing(flushing: Unit, dead: Unit) -> DeadFlushing | None:
    """The [3.11.4] loss of ``flushing`` pushing onto ``dead``, or None where it does not apply
    (a dead tunnel, or at or beyond 8 D open / 4 D ducted)."""
    if dead.tunnel:
        return None
    dx, dy, distance = _offset(flushing, dead)
    diameter = flushing.diameter
    reach = DEAD_FLUSHING_DISTANCE_DUCTED if flushing.ducted else DEAD_FLUSHING_DISTANCE_OPEN
    if distance >= reach * diameter:
        return None
    phi = math.atan((0.35 if flushing.ducted else 0.6) * diameter / distance)
    return DeadFlushing(flushing.name, dead.name, math.atan2(dy, dx), phi, dead_flushing_factor(distance, diameter))
