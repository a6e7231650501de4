"""An OSQP problem with a fixed sparsity pattern, in physical units outside, normalised inside.

Every entry that can ever be non-zero is stored explicitly (zeros included), so that new
values go in with ``OSQP.update(Ax=, Ax_idx=)`` and never need a new set-up.

Allocation problems mix newtons, newton-metres and weights six orders of magnitude apart
(Q >> W in (1.35)); OSQP's own equilibration handles that badly (thousands of iterations on
saturated samples). So the problem is scaled here, once per configuration, from physical
knowledge instead: each variable by its range (a force by its actuator's largest force, a
slack by the largest force its DOF can see), each row by its largest coefficient, and the
cost by its largest curvature. OSQP then runs without its own scaling, and its tolerances
read as fractions of those ranges.
"""

from __future__ import annotations

import math
import signal
from dataclasses import dataclass

import numpy as np
import osqp
import scipy.sparse as sp

ACCEPTED = (osqp.SolverStatus.OSQP_SOLVED, osqp.SolverStatus.OSQP_SOLVED_INACCURATE)
"""OSQP statuses whose solution is used; any other falls back to the pseudo-inverse."""

INTERRUPTED = osqp.SolverStatus.OSQP_SIGINT
"""OSQP catches SIGINT while it solves and only stops; the signal is raised again for the process."""

CHECK_TERMINATION = 5
"""Iterations between OSQP's convergence checks: warm-started samples often converge in a few."""


class Rows:
    """Constraint rows collected as explicit (row, column, value) triplets."""

    def __init__(self) -> None:
        self.rows: list[int] = []
        self.cols: list[int] = []
        self.vals: list[float] = []
        self.count = 0

    def add(self, entries: list[tuple[int, float]]) -> int:
        """Append one row; returns its index."""
        for col, val in entries:
            self.rows.append(self.count)
            self.cols.append(col)
            self.vals.append(val)
        self.count += 1
        return self.count - 1

    def matrix(self, columns: int) -> sp.csc_matrix:
        matrix = sp.coo_matrix((self.vals, (self.rows, self.cols)), shape=(self.count, columns)).tocsc()
        matrix.sort_indices()
        return matrix


def entry_index(matrix: sp.csc_matrix, row: int, col: int) -> int:
    """Position of the stored entry (row, col) in the CSC data array."""
    start, end = matrix.indptr[col], matrix.indptr[col + 1]
    return int(start + np.flatnonzero(matrix.indices[start:end] == row)[0])


def solver_settings(eps_abs: float, eps_rel: float, max_iter: int, time_limit: float) -> dict:
    """OSQP settings a configuration may change at runtime (time_limit 0: none)."""
    return dict(eps_abs=eps_abs, eps_rel=eps_rel, max_iter=max_iter,
                time_limit=time_limit if time_limit > 0.0 else 1e10)


class ScaledProblem:
    """min 1/2 x'Px + q'x s.t. l <= Ax <= u with diagonal P, set up once.

    ``column_scale`` holds the physical range of each variable. Values are passed and
    returned in physical units; the OSQP instance sees the normalised problem. The cost is
    divided by the largest curvature of the ``effort`` variables, so that the actuator-effort
    term is of order one and stays well above the solver tolerance even where a heavily
    weighted slack shares the objective (Q >> W); without curvature, by the largest |q|.
    """

    def __init__(self, p_diagonal: np.ndarray, q: np.ndarray, a: sp.csc_matrix, column_scale: np.ndarray,
                 settings: dict, effort: np.ndarray):
        self.a = a
        self.column_scale = column_scale
        self._entry_col = np.repeat(np.arange(a.shape[1]), np.diff(a.indptr))
        self._entry_row = a.indices.copy()
        scaled = np.abs(a.data) * column_scale[self._entry_col]
        row_max = np.zeros(a.shape[0])
        np.maximum.at(row_max, self._entry_row, scaled)
        self.row_scale = 1.0 / np.where(row_max > 0.0, row_max, 1.0)
        self._entry_scale = self.row_scale[self._entry_row] * column_scale[self._entry_col]
        curvature = float(np.max(p_diagonal[effort] * column_scale[effort] ** 2))
        reference = curvature if curvature > 0.0 else float(np.max(np.abs(q) * column_scale))
        self.cost_scale = 1.0 / max(reference, 1e-300)
        self.low = np.full(a.shape[0], -math.inf)
        self.up = np.full(a.shape[0], math.inf)
        self.solver = osqp.OSQP()
        self.solver.setup(P=self._p(p_diagonal), q=self._q(q), A=self._a(a.data), l=self.low, u=self.up,
                          verbose=False, warm_starting=True, polishing=False, scaling=0,
                          check_termination=CHECK_TERMINATION, **settings)
        self._infinity = float(osqp.constant("OSQP_INFTY"))
        self._index_type = self.solver._itype
        # The per-sample calls go to OSQP's extension object directly when it is there: the
        # Python wrapper's update() and solve() add about 25 us of bookkeeping per sample
        # (constant look-ups, an info dictionary), half of a 50 us budget. Same calls, same data.
        raw = getattr(self.solver, "_solver", None)
        self._raw = raw if all(hasattr(raw, name) for name in ("update_data_vec", "update_data_mat", "solve",
                                                               "solution", "info")) else None

    def _p(self, p_diagonal: np.ndarray) -> sp.csc_matrix:
        values = self.cost_scale * p_diagonal * self.column_scale ** 2
        index = np.arange(len(values))
        matrix = sp.csc_matrix((values, (index, index)), shape=(len(values), len(values)))
        matrix.sort_indices()
        return matrix

    def _q(self, q: np.ndarray) -> np.ndarray:
        return self.cost_scale * q * self.column_scale

    def _a(self, data: np.ndarray) -> sp.csc_matrix:
        return sp.csc_matrix((data * self._entry_scale, self.a.indices, self.a.indptr), shape=self.a.shape)

    def update_objective(self, p_diagonal: np.ndarray | None = None, q: np.ndarray | None = None) -> None:
        if p_diagonal is not None:
            self.solver.update(Px=self._p(p_diagonal).data)
        if q is not None:
            if self._raw is not None:
                self._raw.update_data_vec(q=self._q(q), l=None, u=None)
            else:
                self.solver.update(q=self._q(q))

    def update_matrix(self, values: np.ndarray, index: np.ndarray | None = None) -> None:
        """New values of stored entries (all of them, or those at ``index``)."""
        if index is None:
            self.solver.update(Ax=values * self._entry_scale)
        elif self._raw is not None:
            self._raw.update_data_mat(P_x=None, P_i=None, A_x=values * self._entry_scale[index],
                                      A_i=index.astype(self._index_type, copy=False))
        else:
            self.solver.update(Ax=values * self._entry_scale[index], Ax_idx=index)

    def update_settings(self, settings: dict) -> None:
        self.solver.update_settings(**settings)

    def solve(self, low: np.ndarray, up: np.ndarray) -> Solution:
        """Solve for physical bounds; the solution comes back in physical units."""
        if self._raw is None:
            self.solver.update(l=low * self.row_scale, u=up * self.row_scale)
            result = self.solver.solve(raise_error=False)
            info, solution = result.info, result
        else:
            bound = self._infinity
            self._raw.update_data_vec(q=None, l=np.maximum(low * self.row_scale, -bound),
                                      u=np.minimum(up * self.row_scale, bound))
            self._raw.solve()
            info, solution = self._raw.info, self._raw.solution
        if info.status_val == INTERRUPTED:
            signal.raise_signal(signal.SIGINT)      # Ctrl-C or a SIGINT stop meant for the process
        x = solution.x * self.column_scale
        usable = info.status_val in ACCEPTED and bool(np.isfinite(x).all())
        return Solution(x=x, status=info.status, iterations=int(info.iter), usable=usable)


@dataclass(frozen=True)
class Solution:
    """The primal solution in physical units, and how the solve went."""

    x: np.ndarray
    status: str
    iterations: int
    usable: bool
