"""Body frame conventions at the node's boundary: FRD inside, FRD or FLU outside.

The library works in FRD (x forward, y starboard, z down, as the survey and marine practice
do). A REP-103 ``base_link`` is FLU (x forward, y left, z up). The two differ by a half turn
about x: y and z change sign, for forces, moments and points alike, and the conversion is its
own inverse. Azimuth angles and per-actuator thrusts are not vectors of the body and are
never converted.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .node_settings import FLU

_VECTOR = np.array([1.0, -1.0, -1.0])
_WRENCH = np.concatenate((_VECTOR, _VECTOR))


def wrench_between(values: Sequence[float], frame: str) -> np.ndarray:
    """[X, Y, Z, K, M, N] from FRD to ``frame``, or from ``frame`` to FRD (the same map)."""
    values = np.asarray(values, dtype=float)
    return values * _WRENCH if frame == FLU else values.copy()


def vector_between(values: Sequence[float], frame: str) -> np.ndarray:
    """A point or direction [x, y, z] from FRD to ``frame``, or back (the same map)."""
    values = np.asarray(values, dtype=float)
    return values * _VECTOR if frame == FLU else values.copy()
