"""How a solve ended: the :class:`Outcome`, and the :class:`Solution` every solver gives back.

:class:`Outcome` is the one vocabulary for it, from a solver's answer up to the
:class:`~allocator_pkg.allocation.result.AllocationResult` that diagnostics, counters and
``AllocationStatus.outcome`` read; the status texts stay for people."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum

import numpy as np


class Outcome(Enum):
    """What one solve, or one sample, ended as."""

    SOLVED = "solved"
    """Converged to the solver's tolerances (or a closed form that needs none)."""
    INACCURATE = "inaccurate"
    """Accepted at the solver's looser tolerances (OSQP's "solved inaccurate")."""
    ITERATION_LIMIT = "iteration limit"
    """Stopped by ``solver.max_iter`` or ``solver.time_limit``, its iterate feasible enough to use."""
    FAILED = "failed"
    """No usable answer; the allocator then lets the pseudo-inverse answer (never a sample's outcome)."""
    FALLBACK = "fallback"
    """The sample's forces come from the weighted pseudo-inverse because the method failed."""
    STOPPED = "stopped"
    """Zero thrust at once: the wrench input went stale, or the node is shutting down."""

    @property
    def usable(self) -> bool:
        """Whether a solve that ended so gave forces to use (all but ``FAILED``)."""
        return self is not Outcome.FAILED


@dataclass(slots=True, kw_only=True)
class Solution:
    """A solver's answer: the primal solution ``x`` (normalised units from a QP backend,
    physical units from :class:`~.problem.ScaledProblem`, the columns of a
    :class:`~.linear_program.LinearProgram`), its ``outcome`` (``usable`` when that gives a
    solution), the status text, the iterations and the primal ``residual`` where the solver
    reports one.

    ``y`` holds the row multipliers of a QP in OSQP's convention: P x + q + A' y = 0, y >= 0
    where a row's upper bound holds it, y <= 0 where its lower bound does. ``duals`` is that
    array, or a function that returns it (called only when ``y`` is read: most samples never
    need the multipliers)."""

    x: np.ndarray
    status: str
    iterations: int
    outcome: Outcome
    residual: float | None = None
    duals: np.ndarray | Callable[[], np.ndarray] | None = None

    @property
    def usable(self) -> bool:
        return self.outcome is not Outcome.FAILED

    @property
    def y(self) -> np.ndarray:
        if callable(self.duals):
            self.duals = np.asarray(self.duals())
        return self.duals
