"""Angle sets of rotatable thrusters: feasible sector, forbidden sectors, rotation paths.

Angles of a thruster with free rotation (feasible sector of 2 pi) wrap to (-pi, pi];
angles of a thruster with a limited sector are plain numbers in [azimuth_min, azimuth_max].
A forbidden sector [start, end] is the arc counter-clockwise from start to end; thrust is
not allowed inside it, but the thruster may turn through it (at zero thrust).

Most functions here work in *offsets* from the current angle alpha0, on the real line, so
that "turn 30 degrees clockwise" is the interval [-0.52, 0].
"""

from __future__ import annotations

import math

from ..vehicle.angles import ANGLE_TOLERANCE, TWO_PI, wrap
from ..vehicle.config import RotationConfig

Interval = tuple[float, float]


def in_feasible_sector(rotation: RotationConfig, angle: float) -> bool:
    """Whether the thruster can be at this angle at all (the feasible sector)."""
    if rotation.continuous:
        return True
    return rotation.azimuth_min - ANGLE_TOLERANCE <= angle <= rotation.azimuth_max + ANGLE_TOLERANCE


def in_forbidden_sector(rotation: RotationConfig, angle: float) -> bool:
    """Whether the angle is strictly inside a forbidden sector (its edges are allowed)."""
    for start, end in rotation.forbidden_sectors:
        width = (end - start) % TWO_PI
        inside = (angle - start) % TWO_PI
        if ANGLE_TOLERANCE < inside < width - ANGLE_TOLERANCE:
            return True
    return False


def offset_domain(rotation: RotationConfig, alpha0: float) -> Interval:
    """Offsets the thruster can turn through from alpha0 (one turn either way if free)."""
    if rotation.continuous:
        return (-TWO_PI, TWO_PI)
    return (rotation.azimuth_min - alpha0, rotation.azimuth_max - alpha0)


def forbidden_offsets(rotation: RotationConfig, alpha0: float) -> list[Interval]:
    """Forbidden sectors as offset intervals from alpha0, over the offset domain."""
    low, high = offset_domain(rotation, alpha0)
    intervals = []
    for start, end in rotation.forbidden_sectors:
        width = (end - start) % TWO_PI
        first = wrap(start - alpha0)
        for shift in (-2.0 * TWO_PI, -TWO_PI, 0.0, TWO_PI):
            lo = first + shift
            if lo < high and lo + width > low:
                intervals.append((lo, lo + width))
    intervals.sort()
    return intervals


Surroundings = tuple[Interval, list[Interval], "Interval | None"]
"""(offset domain, forbidden offset intervals, allowed piece around the current angle)."""


def surroundings(rotation: RotationConfig, alpha0: float) -> Surroundings:
    """What a thruster at alpha0 is among: the offsets it can turn through, the forbidden
    intervals among them, and the allowed piece it is in (None inside a forbidden sector).
    Computed once per thruster and sample, and shared by everything that needs it."""
    domain = offset_domain(rotation, alpha0)
    if not rotation.forbidden_sectors:
        return domain, [], domain
    forbidden = forbidden_offsets(rotation, alpha0)
    return domain, forbidden, allowed_piece(domain, forbidden)


def allowed_piece(domain: Interval, forbidden: list[Interval], point: float = 0.0) -> Interval | None:
    """The largest interval of the domain around ``point`` that avoids the forbidden
    intervals' interiors; None when the point is strictly inside one of them."""
    low, high = domain
    for lo, hi in forbidden:
        if lo + ANGLE_TOLERANCE < point < hi - ANGLE_TOLERANCE:
            return None
        if hi <= point + ANGLE_TOLERANCE:
            low = max(low, hi)
        elif lo >= point - ANGLE_TOLERANCE:
            high = min(high, lo)
    return (low, high)


def target_offsets(rotation: RotationConfig, alpha0: float, target: float) -> list[float]:
    """Offsets that bring the thruster from alpha0 to ``target``: both ways round for free
    rotation, the representation inside the feasible sector otherwise (none if the
    sector does not contain the target)."""
    if rotation.continuous:
        ccw = (target - alpha0) % TWO_PI
        return [ccw, ccw - TWO_PI] if ccw > 0.0 else [0.0]
    low, high = offset_domain(rotation, alpha0)
    base = wrap(target - alpha0)
    return [base + k * TWO_PI for k in (-1, 0, 1)
            if low - ANGLE_TOLERANCE <= base + k * TWO_PI <= high + ANGLE_TOLERANCE]


def allowed_arcs(rotation: RotationConfig) -> list[Interval]:
    """Arcs of absolute angles at which the thruster may push: the feasible sector minus the
    forbidden sectors; for free rotation an arc may run across +-pi (its end above pi)."""
    low, high = (-math.pi, math.pi) if rotation.continuous else (rotation.azimuth_min, rotation.azimuth_max)
    cuts = []
    for start, end in rotation.forbidden_sectors:
        width = (end - start) % TWO_PI
        base = wrap(start)
        for shift in (-TWO_PI, 0.0, TWO_PI):
            if base + shift < high and base + shift + width > low:
                cuts.append((base + shift, base + shift + width))
    arcs = [(low, high)]
    for cut_low, cut_high in sorted(cuts):
        arcs = [piece for a, b in arcs
                for piece in ((a, min(b, cut_low)), (max(a, cut_high), b)) if piece[1] > piece[0]]
    if rotation.continuous and len(arcs) > 1 and arcs[0][0] == -math.pi and arcs[-1][1] == math.pi:
        arcs = [(arcs[-1][0], arcs[0][1] + TWO_PI), *arcs[1:-1]]        # join across +-pi
    return arcs


def can_push_along(rotation: RotationConfig, direction: float) -> bool:
    """Whether the thruster can push along ``direction`` [rad]: at that angle, or (if
    reversible) at the opposite one pushing backwards, inside the feasible sector and outside
    every forbidden sector."""
    candidates = [direction] + ([direction + math.pi] if rotation.reversible else [])
    for angle in candidates:
        for representation in (wrap(angle), wrap(angle) - TWO_PI, wrap(angle) + TWO_PI):
            if in_feasible_sector(rotation, representation) and not in_forbidden_sector(rotation, representation):
                return True
    return False
