"""What a QP solver must offer to stand behind :class:`~allocator_pkg.solvers.problem.ScaledProblem`.

A backend receives the normalised problem once, min 1/2 x'Px + q'x s.t. low <= Ax <= up
with diagonal P and a fixed sparsity pattern of A, then only new values on that pattern and
new bounds each sample. Infinite bounds mean no bound. A backend keeps whatever state helps
it between solves (OSQP its iterates, an active-set solver its working set).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import ClassVar, Protocol

import numpy as np
import scipy.sparse as sp

from ..vehicle.config import SolverSettings
from .outcome import Solution

NO_BOUND = math.inf
"""The bound of a row or variable that has none, in every problem of the package; a backend
that needs a finite stand-in (OSQP's ``OSQP_INFTY``) clips to its own."""


class Backend(Protocol):
    name: ClassVar[str]

    def setup(self, p_diagonal: np.ndarray, q: np.ndarray, a: sp.csc_matrix, settings: SolverSettings) -> None:
        """Take the problem's structure and first values (bounds come with each solve)."""

    def update_objective(self, p_diagonal: np.ndarray | None, q: np.ndarray | None) -> None:
        """New values of the diagonal of P and/or of q."""

    def update_matrix(self, values: np.ndarray, index: np.ndarray | None, p_diagonal: np.ndarray | None = None) -> None:
        """New values of A's stored entries (all of them, or those at ``index``, CSC order), and
        of P's diagonal if given: one update, so a factorising solver refactorises once."""

    def update_settings(self, settings: SolverSettings) -> None:
        """Tolerances and limits changed by a reconfiguration."""

    def solve(self, low: np.ndarray, up: np.ndarray, q: np.ndarray | None = None) -> Solution:
        """Solve with these row bounds (the backend may change the arrays: they are scratch)
        and, if given, this q (sent with the bounds); the solution in normalised units, its
        multipliers in OSQP's convention (:class:`~.outcome.Solution`)."""


BackendFactory = Callable[[], Backend]


class DenseObjective:
    """The objective as the dense active-set solvers (quadprog, DAQP) take it: P a matrix,
    its diagonal raised by ``REGULARISATION`` (they need P positive definite, and the problems
    carry uncosted variables: the minimax bound fbar when beta = 0)."""

    REGULARISATION: ClassVar[float] = 1e-9

    p: np.ndarray
    q: np.ndarray

    def update_objective(self, p_diagonal: np.ndarray | None, q: np.ndarray | None) -> None:
        if p_diagonal is not None:
            self.p = np.diag(p_diagonal + self.REGULARISATION)
        if q is not None:
            self.q = q.copy()
