"""Power per source as linear rows (docs/power.md, "Power rows"; docs/theory.md): the chords of
r^(3/2) and the values a power-aware method writes into its problem.

Actuator i draws p_i = P_i |f_i|^(3/2) (1.44). On [0, F_i] the convex g(f) = f^(3/2) lies
below its piecewise-linear interpolant h through the breakpoints f_k = F_i (k/K)^2, and h is
the maximum of the chord lines l_k(f) = g(f_k) + s_k (f - f_k), s_k the slope between f_k
and f_(k+1). So an epigraph variable q_i with

    q_i >= P_i l_k(|f_i|),  k = 0 ... K-1                                  (chord rows)

is at least P_i h(|f_i|) >= p_i, the safe side: no row can let the draw pass the available
power, and with K = BREAKPOINTS the interpolant is at most CHORD_ERROR above the curve where
the thrust matters (measured, docs/power.md). |f_i| enters linearly: a scalar thruster takes
both signs (q_i >= P_fwd l_k(f_i) and q_i >= P_rev l_k(-f_i)); a rotatable thruster a
magnitude rho_i over the N-gon inscribed in the circle of radius rho_i (apothem
rho_i cos(pi/N), a vertex along the direction it pushes), so |f_i| <= rho_i, and the chord
rows on rho_i. Each source row j is

    sum_i w_ij q_i <= A_j                                                    (source rows)

with w_ij the share of actuator i's power that row j gives. :class:`PowerRows` holds the
values of one set of available powers and feeds; :class:`PowerPattern` the structure (which
(i, j) can ever be non-zero), fixed per configuration. The allocator's
:meth:`~allocator_pkg.allocation.power_budget.PowerBudget.rows` writes them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np

from ..vehicle.config import Vehicle

BREAKPOINTS = 24
"""Chords of r^(3/2) per thruster: the allocator reaches >= 0.99 of the exact power-limited
optimum with them (test/methods/test_power_block.py against SLSQP)."""
SPACING = 2.0
"""Breakpoints at F (k/K)^SPACING: denser near zero, where a chord's relative error is largest."""
POWER_SIDES = 32
"""Faces of the polygon inscribed in a rotatable thruster's magnitude circle."""


def breakpoints(count: int = BREAKPOINTS) -> np.ndarray:
    """The K + 1 breakpoints, fractions of the thrust range: (k/K)^SPACING, k = 0 ... K."""
    if count < 1:
        raise ValueError(f"the chords of r^(3/2) need at least one segment, got {count}")
    return (np.arange(count + 1) / count) ** SPACING


@cache
def chord_lines(count: int = BREAKPOINTS) -> tuple[np.ndarray, np.ndarray]:
    """(slope s_k, intercept c_k) of the K chord lines of g(r) = r^(3/2) on r in [0, 1]:
    l_k(r) = c_k + s_k r; their maximum is the interpolant through :func:`breakpoints`, >= g
    on [0, 1] (g convex). Computed once per ``count``; the arrays are read-only."""
    r = breakpoints(count)
    g = r ** 1.5
    slope = np.diff(g) / np.diff(r)
    intercept = g[:-1] - slope * r[:-1]
    slope.flags.writeable = intercept.flags.writeable = False
    return slope, intercept


def interpolant(fraction: np.ndarray, count: int = BREAKPOINTS) -> np.ndarray:
    """max_k l_k(r) at ``fraction`` r in [0, 1]: the power the chord rows see, per unit of
    P F^(3/2)."""
    slope, intercept = chord_lines(count)
    return np.max(intercept[:, None] + slope[:, None] * np.atleast_1d(np.asarray(fraction, dtype=float)), axis=0)


def polygon(sides: int = POWER_SIDES) -> tuple[np.ndarray, float]:
    """(normals (N x 2), apothem per unit radius) of the N-gon inscribed in the unit circle with
    a vertex at angle 0: n . f <= rho cos(pi/N) for every face keeps |f| <= rho."""
    angles = (np.arange(sides) + 0.5) * 2.0 * math.pi / sides
    return np.column_stack((np.cos(angles), np.sin(angles))), math.cos(math.pi / sides)


def feed_shares(vehicle: Vehicle) -> np.ndarray:
    """(actuators x sources) the configured share s_ij of actuator i's power from source j."""
    sources = [s.name for s in vehicle.power_sources]
    shares = np.zeros((len(vehicle.actuators), len(sources)))
    for i, actuator in enumerate(vehicle.actuators):
        for feed, share in zip(actuator.feeds, actuator.feed_shares or (1.0,) * len(actuator.feeds)):
            shares[i, sources.index(feed)] = share
    return shares


def tied_reach(sources: tuple[str, ...], ties: tuple[tuple[str, str], ...], shares: np.ndarray) -> np.ndarray:
    """(sources x actuators) every (row, actuator) pair that some state of the bus ties
    ``ties`` (pairs of source names) makes non-zero: row j carries actuator i when a path of
    ties from j to one of i's feeds passes only sources at or after j (closing just those ties
    makes a bus that j heads, its first source in ``sources`` order, and that feeds i)."""
    index = {name: j for j, name in enumerate(sources)}
    links = [(index[a], index[b]) for a, b in ties]
    reach = np.zeros((len(sources), shares.shape[0]), dtype=bool)
    for j in range(len(sources)):
        bus, grown = {j}, True
        while grown:
            joined = {b for a, b in links if a in bus and b > j} | {a for a, b in links if b in bus and a > j}
            grown = not joined <= bus
            bus |= joined
        reach[j] = (shares[:, sorted(bus)] > 0.0).any(axis=1)
    return reach


@dataclass(frozen=True)
class PowerPattern:
    """The structure of the power rows: ``pattern`` (actuators x rows), every (i, j) whose
    weight can ever be non-zero for this configuration. The powered actuators are those with a
    non-zero entry; the structure changes only with the configuration."""

    pattern: np.ndarray

    @classmethod
    def of(cls, vehicle: Vehicle) -> PowerPattern | None:
        """The configuration's pattern: the feeds, pooled by every state of the bus ties
        (:func:`tied_reach`), so that a tie's change is values only (None without power
        sources)."""
        if not vehicle.power_sources:
            return None
        sources = tuple(s.name for s in vehicle.power_sources)
        ties = tuple(tuple(t.sources) for t in vehicle.bus_ties)
        return cls(tied_reach(sources, ties, feed_shares(vehicle)).T)

    @property
    def powered(self) -> np.ndarray:
        """Indices of the actuators with an entry in some row."""
        return np.flatnonzero(self.pattern.any(axis=1))

    def same(self, other: PowerPattern | None) -> bool:
        """Whether ``other`` is a pattern with the same entries (None: no pattern): the rows'
        structure holds and a change is values only."""
        return other is not None and np.array_equal(self.pattern, other.pattern)


@dataclass(frozen=True)
class PowerRows:
    """The values of the power rows (module docstring) at one set of available powers, feeds,
    coefficients and bus-tie states:

    - ``weights`` (actuators x rows): w_ij, the share of actuator i's power row j carries;
      non-zero only where ``pattern.pattern`` is;
    - ``available`` (rows): A_j [W] (inf: the row bounds nothing);
    - ``forward``/``reverse`` (actuators): P_i [W/N^1.5] of a positive and a negative thrust;
    - ``rated`` (actuators): the range F_i [N] the chords cover (the largest magnitude the
      actuator's configured range allows).

    A change of any value is values only for a method's problem; a new ``pattern`` is a new
    structure."""

    pattern: PowerPattern
    weights: np.ndarray
    available: np.ndarray
    forward: np.ndarray
    reverse: np.ndarray
    rated: np.ndarray

    def short(self) -> np.ndarray:
        """Per row, whether its consumers could together draw more than A_j, each at its full
        range (sum_i w_ij P_i F_i^(3/2), which the chord rows see exactly): only such a row can
        bind, the others are left out of the solve (values only)."""
        return np.max(np.column_stack((self.forward, self.reverse)), axis=1) * self.rated ** 1.5 @ self.weights \
            > self.available

    def seen(self, thrust: np.ndarray, count: int = BREAKPOINTS) -> np.ndarray:
        """The draw [W] of each row the chord rows see at ``thrust`` (>= the exact sum_i w_ij p_i)."""
        coefficient = np.where(thrust >= 0.0, self.forward, self.reverse)
        scale = np.where(self.rated > 0.0, self.rated, 1.0)
        fraction = np.clip(np.abs(thrust) / scale, 0.0, 1.0)
        return (coefficient * scale ** 1.5 * interpolant(fraction, count)) @ self.weights
