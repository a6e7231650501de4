"""quadprog (Goldfarb-Idnani dual active set, dense) behind the solver seam: an exact
reference and a speed anchor for the benchmarks. Every solve starts from scratch."""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np
import quadprog
import scipy.sparse as sp

from ..vehicle.config import SolverSettings
from .backend import DenseObjective
from .outcome import Outcome, Solution


class QuadprogBackend(DenseObjective):
    name: ClassVar[str] = "quadprog"

    def setup(self, p_diagonal: np.ndarray, q: np.ndarray, a: sp.csc_matrix, settings: SolverSettings) -> None:
        self.update_objective(p_diagonal, q)
        self.a = a.copy()
        self.dense = self.a.toarray()

    def update_matrix(self, values: np.ndarray, index: np.ndarray | None, p_diagonal: np.ndarray | None = None) -> None:
        self.update_objective(p_diagonal, None)
        if index is None:
            self.a.data[:] = values
        else:
            self.a.data[index] = values
        self.dense = self.a.toarray()

    def update_settings(self, settings: SolverSettings) -> None:
        """quadprog has no tolerances to set."""

    def solve(self, low: np.ndarray, up: np.ndarray, q: np.ndarray | None = None) -> Solution:
        if q is not None:
            self.q = q.copy()
        equal = low == up
        lower = ~equal & (low > -math.inf)
        upper = ~equal & (up < math.inf)
        a = self.dense
        constraints = np.vstack([a[equal], a[lower], -a[upper]]).T
        bounds = np.concatenate([low[equal], low[lower], -up[upper]])
        try:
            x, _, _, iterations, multipliers, _ = quadprog.solve_qp(self.p, -self.q, constraints, bounds,
                                                                    meq=int(equal.sum()))
        except ValueError as error:
            return Solution(x=np.zeros(len(self.q)), status=f"quadprog: {error}", iterations=0, outcome=Outcome.FAILED,
                            duals=np.zeros(len(low)))
        # quadprog: P x + q = C lambda, lambda >= 0 on inequalities; OSQP's y is minus that per row.
        y = np.zeros(len(low))
        counts = np.cumsum([equal.sum(), lower.sum(), upper.sum()])
        y[equal] = -multipliers[:counts[0]]
        y[lower] -= multipliers[counts[0]:counts[1]]
        y[upper] += multipliers[counts[1]:]
        return Solution(x=x, status="solved", iterations=int(iterations[0]), outcome=Outcome.SOLVED, duals=y)
