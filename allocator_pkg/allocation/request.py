"""The request a sample allocates: the generalised force [X, Y, Z, K, M, N] checked."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np


def checked_request(tau: Sequence[float]) -> np.ndarray:
    """The request as a new array of six finite components; ValueError otherwise."""
    requested = np.array(tau, dtype=float)
    if requested.shape != (6,):
        requested = requested.reshape(-1)
        if requested.shape != (6,):
            raise ValueError(f"tau needs 6 components [X, Y, Z, K, M, N], got {requested.size}")
    if not all(map(math.isfinite, requested.tolist())):
        raise ValueError(f"tau must be finite, got {requested.tolist()}")
    return requested
