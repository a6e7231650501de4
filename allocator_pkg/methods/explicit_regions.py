"""The regions of the explicit method (survey 4.1) enumerated offline.

:func:`precompute` tries every active set of (1.35) with beta = 0 (each actuator free, at its
lower or at its upper bound: 3^r sets) and keeps those whose region has an interior: a linear
programme finds the largest ball of parameters p = [tau, f_min, f_max] (1.37), in units of
each DOF's authority and each actuator's force range, inside the region's checks and inside
the set of parameters the vehicle can meet:

- tau within TAU_RANGE times each controlled DOF's authority;
- f_min <= f_max, both within the actuator's static range (faults scale it, rate limits cut a
  window out of it), a control surface's at the given flow speed (its lift range grows as the
  square of the speed: regions that need a larger range are not listed), a thruster's at the
  nominal voltage (a region only a higher voltage reaches is found online).

The active sets and the law's fingerprint (T, W, Q, beta) are what a regions file holds
(``allocator-explicit precompute`` writes it,
:func:`allocator_pkg.methods.explicit_law.read_regions` reads it).
"""

from __future__ import annotations

import itertools
import time

import numpy as np

from ..effectiveness.faults import FaultSet, static_ranges
from ..effectiveness.model import Model
from ..solvers.linear_program import solve_linear_programme
from ..vehicle.config import Vehicle
from .explicit import ExplicitAllocation
from .explicit_law import Law

TAU_RANGE = 10.0
"""Requests up to this many times each DOF's authority (regions of larger ones are the same)."""

INTERIOR = 1e-12
"""A region counts when a ball of this radius (in units of authority and force range) fits.
Genuine regions include slivers 1e-8 to 1e-6 wide (where the slack trades against one
actuator's effort, Q >> W makes the transition that narrow); the checks' tolerances give
degenerate sets a width below 1e-14."""

MOST_ACTUATORS = 10
"""3^r candidate sets: 59049 for ten actuators, a few minutes."""


def candidates(r: int):
    """Every active set of box bounds: bits 2i (upper) and 2i + 1 (lower) of actuator i."""
    for states in itertools.product((0, 1, 2), repeat=r):
        yield sum(state << 2 * i for i, state in enumerate(states) if state)


def has_interior(law: Law, key: int, model: Model, low: np.ndarray, high: np.ndarray) -> bool:
    """Whether the region of ``key`` holds a ball of radius INTERIOR of parameters the vehicle
    can meet (see the module's docstring)."""
    region = law.region(key)
    if region is None:
        return False
    n, r = model.n, model.r
    scale = np.concatenate((model.dof_scale, model.force_scale, model.force_scale))
    checks = region.matrix[r:]
    rows = checks[:, :-1] * scale
    norms = np.linalg.norm(rows, axis=1)
    order = np.zeros((r, 2 * r + n + 1))                    # f_min,i - f_max,i + radius (|e| = sqrt 2) <= 0
    order[np.arange(r), n + np.arange(r)] = 1.0
    order[np.arange(r), n + r + np.arange(r)] = -1.0
    order[:, -1] = np.sqrt(2.0)
    a = np.vstack((np.hstack((rows, norms[:, None])), order))
    b = np.concatenate((-checks[:, -1], np.zeros(r)))
    force = [(lo / s, hi / s) for lo, hi, s in zip(low, high, model.force_scale)]
    bounds = [(-TAU_RANGE, TAU_RANGE)] * n + force + force + [(0.0, 1.0)]
    cost = np.zeros(a.shape[1])
    cost[-1] = -1.0
    result = solve_linear_programme(cost, bounds, a, b)
    return result.usable and float(result.x[-1]) > INTERIOR


def precompute(vehicle: Vehicle, speed: float) -> tuple[list[int], int, float, Law]:
    """(active sets with a region, candidates tried, seconds, the law's data) of ``vehicle``, with
    control surfaces' ranges at flow speed ``speed`` [m/s]."""
    problems = ExplicitAllocation.problems(vehicle)
    if problems:
        raise ValueError("; ".join(problems))
    if vehicle.weights.minimax > 0.0:
        raise ValueError("the enumeration covers beta = 0 (weights.minimax): with the minimax rows each actuator "
                         "has five states and degenerate sets; the online cache serves that case")
    if len(vehicle.actuators) > MOST_ACTUATORS:
        raise ValueError(f"{len(vehicle.actuators)} actuators: 3^r sets are too many to try beyond "
                         f"{MOST_ACTUATORS}; the online cache serves this vehicle")
    model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
    law = Law(model)
    low, high = static_ranges(vehicle, FaultSet(vehicle), speed)
    start = time.perf_counter()
    tried = 0
    keys = []
    for key in candidates(model.r):
        tried += 1
        if has_interior(law, key, model, low, high):
            keys.append(key)
    return keys, tried, time.perf_counter() - start, law
