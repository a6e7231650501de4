"""Forbidden zones of DNV-ST-0111 Level 1 [3.11.3]: no thruster may flush a working thruster.

Thruster i flushes thruster j when the angle between i's thrust direction and the vector from j
to i is less than arctan(0.1 + D / s), D the diameter of i and s the horizontal distance between
them: pushing away from j sends i's race onto j. This is not allowed closer than 15 D unless j
is a tunnel thruster (flushed tunnels are exempt). So each such pair gives i a forbidden sector
of that half-angle around the direction from j to i (the sector's edges allowed: "less than").

The zones are geometry only: computed among the thrusters that work in a failure case, a zone
lifts with the thruster it protects. Angles here are thrust angles in the body frame (FRD):
0 forward, pi/2 to starboard, the angle of a rotatable thruster; the sector of the standard's
Figure A-4 / Table A-6 mirrored (y to port there).

After the public transcription of [3.11.3] in the repository WilliamBoland1/Prosjektoppgave_Collab
(``dp_capability/models/Descriptions/forbidden_zones.md``); not verified by DNV.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from ..vehicle.angles import ANGLE_TOLERANCE

FLUSHING_DISTANCE = 15.0
"""In diameters of the flushing thruster."""


@dataclass(frozen=True)
class Unit:
    """A working thruster's horizontal position [m] (body frame), diameter [m] and whether it is
    a tunnel thruster."""

    name: str
    x: float
    y: float
    diameter: float
    tunnel: bool


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
    """arctan(0.1 + D / s) [rad]."""
    return math.atan(0.1 + diameter / distance)


def flushing_zones(units: Sequence[Unit]) -> list[Zone]:
    """Every zone among the working ``units``: each flushing thruster i and flushed j (not a
    tunnel) closer than 15 D_i."""
    zones = []
    for flushing in units:
        for flushed in units:
            if flushed is flushing or flushed.tunnel:
                continue
            dx, dy = flushing.x - flushed.x, flushing.y - flushed.y
            distance = math.hypot(dx, dy)
            if distance == 0.0:
                raise ValueError(f"{flushing.name} and {flushed.name} are at the same horizontal position")
            if distance < FLUSHING_DISTANCE * flushing.diameter:
                zones.append(Zone(flushing.name, flushed.name, math.atan2(dy, dx),
                                  half_angle(flushing.diameter, distance)))
    return zones
