"""Angle constants and helpers shared by every module that reasons about azimuth angles."""

from __future__ import annotations

import math

TWO_PI = 2.0 * math.pi

ANGLE_TOLERANCE = 1e-9
"""[rad] Angles closer than this are the same angle (sector edges, feasible-sector ends)."""


def wrap(angle: float) -> float:
    """The same angle in (-pi, pi]."""
    wrapped = math.remainder(angle, TWO_PI)
    return math.pi if wrapped == -math.pi else wrapped
