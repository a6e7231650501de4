"""DAQP (dual active set, dense) behind the solver seam, warm-started from the previous
solve's active set: the exact active-set solver allocators in flight control use, as a
benchmark anchor."""

from __future__ import annotations

from typing import ClassVar

import daqp
import numpy as np
import scipy.sparse as sp

from ..vehicle.config import SolverSettings
from .backend import DenseObjective
from .outcome import Outcome, Solution

BOUND = 1e30
"""DAQP's infinity."""

EQUALITY, ACTIVE = 5, 1
"""DAQP's constraint senses: an equality row, and an inequality to start in the working set."""

SOLVED = (1, 2)
"""DAQP exit flags of an optimal (2: soft-optimal) solution."""


class DAQPBackend(DenseObjective):
    name: ClassVar[str] = "daqp"

    def setup(self, p_diagonal: np.ndarray, q: np.ndarray, a: sp.csc_matrix, settings: SolverSettings) -> None:
        self.update_objective(p_diagonal, q)
        self.dense = np.ascontiguousarray(a.toarray())
        self._entry_row = a.indices.copy()
        self._entry_col = np.repeat(np.arange(a.shape[1]), np.diff(a.indptr))
        self.active = np.zeros(a.shape[0], dtype=bool)
        self.update_settings(settings)

    def update_matrix(self, values: np.ndarray, index: np.ndarray | None, p_diagonal: np.ndarray | None = None) -> None:
        self.update_objective(p_diagonal, None)
        if index is None:
            self.dense[self._entry_row, self._entry_col] = values
        else:
            self.dense[self._entry_row[index], self._entry_col[index]] = values

    def update_settings(self, settings: SolverSettings) -> None:
        self.iter_limit = settings.max_iter

    def solve(self, low: np.ndarray, up: np.ndarray, q: np.ndarray | None = None) -> Solution:
        if q is not None:
            self.q = q.copy()
        sense = np.where(low == up, EQUALITY, np.where(self.active, ACTIVE, 0)).astype(np.int32)
        x, _, flag, info = daqp.solve(self.p, self.q, self.dense, np.minimum(up, BOUND), np.maximum(low, -BOUND),
                                      sense, iter_limit=self.iter_limit)
        usable = flag in SOLVED
        multipliers = np.asarray(info["lam"], dtype=float)
        if usable:
            self.active = multipliers != 0.0
        return Solution(x=np.asarray(x, dtype=float), status="solved" if usable else f"daqp exit flag {flag}",
                        iterations=int(info["iterations"]), outcome=Outcome.SOLVED if usable else Outcome.FAILED,
                        duals=multipliers)
