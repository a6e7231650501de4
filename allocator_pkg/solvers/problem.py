"""A QP with a fixed sparsity pattern, in physical units outside and normalised inside.

The allocation methods write their constraints here as rows (:class:`Rows`) and solve
through a :class:`ScaledProblem`, which owns the scaling and hands the normalised problem to
a backend (:mod:`allocator_pkg.solvers`). Every entry that can ever be non-zero is stored
explicitly (zeros included), so that new values go in by index and never need a new set-up.

Allocation problems mix newtons, newton-metres and weights six orders of magnitude apart
(Q >> W in (1.35)); a first-order solver's own equilibration handles that badly (thousands
of iterations on saturated samples). So the problem is scaled here, once per configuration,
from physical knowledge instead: each variable by its range (a force by its actuator's
largest force, a slack by the largest force its DOF can see), each row by its largest
coefficient, and the cost by its largest curvature. The backend then runs without scaling of
its own, and its tolerances read as fractions of those ranges.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..vehicle.config import SolverSettings
from .backend import Backend
from .outcome import Outcome, Solution


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


def block_index(matrix: sp.csc_matrix, rows: np.ndarray, columns: int) -> np.ndarray:
    """Positions in the CSC data array of the stored entries (row, c) for each of ``rows``
    and c < ``columns``, row by row: where a dense block such as T_e goes."""
    return np.array([entry_index(matrix, int(row), c) for row in rows for c in range(columns)], dtype=np.int64)


@dataclass(slots=True)
class Entries:
    """Stored entries of A updated together: their CSC positions and scales (see
    :meth:`ScaledProblem.entries`)."""

    index: np.ndarray
    scale: np.ndarray


class ScaledProblem:
    """min 1/2 x'Px + q'x s.t. low <= Ax <= up with diagonal P, set up once on a backend.

    ``column_scale`` holds the physical range of each variable. Values are passed and
    returned in physical units; the backend sees the normalised problem. The cost is divided
    by the largest curvature of the ``effort`` variables, so that the actuator-effort term is
    of order one and stays well above the solver tolerance even where a heavily weighted
    slack shares the objective (Q >> W); without curvature, by the largest |q|.
    ``low`` and ``up`` are the row bounds a method fills in before each :meth:`solve`.
    """

    def __init__(self, p_diagonal: np.ndarray, q: np.ndarray, a: sp.csc_matrix, column_scale: np.ndarray,
                 settings: SolverSettings, effort: np.ndarray, backend: Backend):
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
        self._low = np.empty(a.shape[0])
        self._up = np.empty(a.shape[0])
        self.backend = backend
        backend.setup(self._p(p_diagonal), self._q(q), self._a(a.data), settings)

    def _p(self, p_diagonal: np.ndarray) -> np.ndarray:
        return self.cost_scale * p_diagonal * self.column_scale ** 2

    def _q(self, q: np.ndarray) -> np.ndarray:
        return self.cost_scale * q * self.column_scale

    def _a(self, data: np.ndarray) -> sp.csc_matrix:
        return sp.csc_matrix((data * self._entry_scale, self.a.indices, self.a.indptr), shape=self.a.shape)

    def update_objective(self, p_diagonal: np.ndarray | None = None, q: np.ndarray | None = None) -> None:
        """New diagonal of P and/or q, physical units."""
        self.backend.update_objective(None if p_diagonal is None else self._p(p_diagonal),
                                      None if q is None else self._q(q))

    def update_matrix(self, values: np.ndarray, index: np.ndarray | None = None,
                      p_diagonal: np.ndarray | None = None) -> None:
        """New values of stored entries of A (all of them, or those at ``index``) and, if given,
        of P's diagonal, physical units, in one update of the backend."""
        self.backend.update_matrix(values * (self._entry_scale if index is None else self._entry_scale[index]), index,
                                   None if p_diagonal is None else self._p(p_diagonal))

    def entries(self, index: np.ndarray) -> Entries:
        """A fixed set of stored entries of A that a method updates together, sample after
        sample: their index and scale are prepared once here."""
        index = np.asarray(index, dtype=np.int64)
        return Entries(index, self._entry_scale[index])

    def update_entries(self, entries: Entries, values: np.ndarray, p_diagonal: np.ndarray | None = None) -> None:
        """New values of one set of entries (physical units) and, if given, of P's diagonal."""
        self.backend.update_matrix(values * entries.scale, entries.index,
                                   None if p_diagonal is None else self._p(p_diagonal))

    def update_settings(self, settings: SolverSettings) -> None:
        self.backend.update_settings(settings)

    def solve(self, low: np.ndarray, up: np.ndarray, q: np.ndarray | None = None) -> Solution:
        """Solve for physical bounds (and a new q, if given); the solution, and its multipliers
        when read, come back in physical units."""
        result = self.backend.solve(np.multiply(low, self.row_scale, out=self._low),
                                    np.multiply(up, self.row_scale, out=self._up), None if q is None else self._q(q))
        x = result.x * self.column_scale
        outcome = result.outcome if math.isfinite(x.sum()) else Outcome.FAILED
        return Solution(x=x, status=result.status, iterations=result.iterations, outcome=outcome,
                        residual=result.residual, duals=lambda: result.y * self.row_scale / self.cost_scale)
