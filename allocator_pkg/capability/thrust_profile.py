"""A thrust limit that depends on the thrust direction, and its force region as convex pieces.

A :class:`ThrustProfile` scales a thruster's thrust limit T by a factor beta(theta) in [0, 1]
of the thrust direction theta [rad, body frame]. It is given by corners (theta_k, beta_k) in
increasing angle over less than one turn, taken cyclically: between two corners both at 1 the
boundary of the forces the thruster can give is the circle of radius T; between any other two
it is the straight chord from T beta_k (cos theta_k, sin theta_k) to the next corner's point
(a loss linear in Cartesian coordinates, as Figure 3-6 of DNV-ST-0111 draws it; a loss given
another way is drawn by chords between corners close together).

Within an allowed arc of directions the region {r (cos theta, sin theta): 0 <= r <= T beta(theta)}
is star-shaped, not convex: a notch turns toward the origin at a reflex corner.
:meth:`ThrustProfile.pieces` cuts the arc at every reflex corner and into cones at most pi wide;
each piece is then convex, the intersection of its cone, the disc of radius T and the
half-planes of the chords it meets (a chord's line supports the convex piece it bounds), so a
linear programme over each piece and the best over the combinations of pieces gives the exact
reach of the profile.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

TWO_PI = 2.0 * math.pi
_TOLERANCE = 1e-12

HalfPlane = tuple[float, float, float]
"""(n_x, n_y, c): the force f of a thruster of limit T keeps n . f <= c T."""
ForcePiece = tuple[float, float, float, bool, tuple[HalfPlane, ...]]
"""(start, end, radius, line, half-planes): a convex piece of a thruster's forces, the cone
[start, end] (a ray when start == end; ``line``: both ways along it) within the radius and the
half-planes (their offsets per unit of radius)."""


class ForceProfile(Protocol):
    """What the capability analysis asks of a direction-dependent thrust limit."""

    def factor(self, angle: float) -> float:
        """The share of the thrust limit along ``angle`` [rad]."""

    def available(self, angle: float, low: float, high: float) -> float:
        """The thrust a thruster of range [low, high] can give along ``angle`` [rad]."""

    def force_pieces(self, arcs: Sequence[tuple[float, float]], low: float, high: float) -> list[ForcePiece]:
        """Convex pieces of the forces of a thruster of range [low, high] turning over ``arcs``."""


@dataclass(frozen=True)
class ThrustProfile:
    """Thrust limit factor over the thrust direction: ``corners`` (angle [rad], factor in [0, 1]),
    increasing, spanning less than 2 pi, taken cyclically (no corners: 1 everywhere)."""

    corners: tuple[tuple[float, float], ...]

    def __post_init__(self) -> None:
        angles = [angle for angle, _ in self.corners]
        if any(b <= a for a, b in itertools.pairwise(angles)) or (angles and angles[-1] - angles[0] >= TWO_PI):
            raise ValueError("profile corners: increasing angles spanning less than 2 pi")
        if any(not 0.0 <= factor <= 1.0 for _, factor in self.corners):
            raise ValueError("profile corners: factors in [0, 1]")
        if len(self.corners) == 1:
            raise ValueError("profile corners: none, or at least two")
        factors = [factor for _, factor in self.corners]
        if any(a == b == 0.0 for a, b in zip(factors, factors[1:] + factors[:1])):
            raise ValueError("profile corners: no two neighbours at 0")

    def factor(self, angle: float) -> float:
        """beta at the thrust direction ``angle`` [rad]: where the ray meets the boundary, over T."""
        for start, end, normal, offset in self._segments():
            if _inside(angle, start, end):
                if normal is None:
                    return 1.0
                along = normal[0] * math.cos(angle) + normal[1] * math.sin(angle)
                return offset / along if along > _TOLERANCE else 1.0
        return 1.0

    def available(self, angle: float, low: float, high: float) -> float:
        """``high`` times :meth:`factor`: the limit along ``angle`` pushing ahead."""
        return high * self.factor(angle)

    def chords(self) -> list[tuple[float, float, HalfPlane]]:
        """(start, end, half-plane) of every straight piece of the boundary."""
        return [(start, end, (*normal, offset)) for start, end, normal, offset in self._segments()
                if normal is not None]

    def reflex(self) -> list[float]:
        """The angles of the corners where the boundary turns toward the origin (only a corner
        inside the circle can: both its segments are chords)."""
        points = self._points()
        count = len(points)
        angles = []
        for k in range(count):
            if self.corners[k][1] == 1.0:
                continue
            (xa, ya), (xb, yb), (xc, yc) = (points[(k + j) % count][1] for j in (-1, 0, 1))
            if (xb - xa) * (yc - yb) - (yb - ya) * (xc - xb) < -_TOLERANCE:
                angles.append(points[k][0])
        return angles

    def pieces(self, start: float, end: float) -> list[tuple[float, float, tuple[HalfPlane, ...]]]:
        """Convex pieces (start, end, half-planes) of the forces along the arc [start, end] [rad]
        (at most one turn): cut at the reflex corners inside it and into cones at most pi wide;
        each with the half-planes of the chords that meet it."""
        cuts = sorted({_shift(angle, start) for angle in self.reflex()} - {start})
        cuts = [angle for angle in cuts if angle < end - _TOLERANCE]
        if cuts and end - start >= TWO_PI - _TOLERANCE:            # a whole turn: begin at a cut
            start, end, cuts = cuts[0], cuts[0] + TWO_PI, cuts[1:]
        bounds = [start, *cuts, end]
        chords = self.chords()
        pieces = []
        for low, high in itertools.pairwise(bounds):
            parts = max(1, math.ceil((high - low) / math.pi - 1e-9))
            width = (high - low) / parts
            for k in range(parts):
                a, b = low + k * width, low + (k + 1) * width
                planes = tuple(plane for c_start, c_end, plane in chords if _overlaps(a, b, c_start, c_end))
                pieces.append((a, b, planes))
        return pieces

    def force_pieces(self, arcs: Sequence[tuple[float, float]], low: float, high: float) -> list[ForcePiece]:
        """The convex :meth:`pieces` of each allowed arc at the radius ``high``, and when the
        thruster reverses (low < 0) of each arc turned by pi at the radius -low."""
        turned = [(start, end, high) for start, end in arcs]
        if low < 0.0:
            turned += [(start + math.pi, end + math.pi, -low) for start, end in arcs]
        return [(a, b, radius, False, planes)
                for start, end, radius in turned for a, b, planes in self.pieces(start, end)]

    def _points(self) -> list[tuple[float, tuple[float, float]]]:
        return [(angle, (factor * math.cos(angle), factor * math.sin(angle))) for angle, factor in self.corners]

    def _segments(self) -> list[tuple[float, float, tuple[float, float] | None, float]]:
        """(start, end, outward normal or None for the circle, offset) per boundary segment: the
        chord keeps n . f <= offset per unit of T."""
        points = self._points()
        segments = []
        for k, (angle, (xa, ya)) in enumerate(points):
            following = k + 1 if k + 1 < len(points) else 0
            end, (xb, yb) = points[following]
            end = end if following else end + TWO_PI
            if self.corners[k][1] == 1.0 and self.corners[following][1] == 1.0:
                segments.append((angle, end, None, 1.0))
                continue
            normal = (yb - ya, xa - xb)
            size = math.hypot(*normal)
            normal = (normal[0] / size, normal[1] / size)
            segments.append((angle, end, normal, normal[0] * xa + normal[1] * ya))
        return segments


def _shift(angle: float, start: float) -> float:
    """``angle`` plus a multiple of 2 pi, in [start, start + 2 pi)."""
    return start + (angle - start) % TWO_PI


def _inside(angle: float, start: float, end: float) -> bool:
    return _shift(angle, start) <= end + _TOLERANCE


def _overlaps(a: float, b: float, start: float, end: float) -> bool:
    """Whether the arcs [a, b] and [start, end] share more than a point (cyclically)."""
    shifted = _shift(start, a)
    for offset in (shifted - TWO_PI, shifted):
        if offset < b - _TOLERANCE and offset + (end - start) > a + _TOLERANCE:
            return True
    return False
