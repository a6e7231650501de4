"""OSQP (ADMM) behind the solver seam: set up once, updated in place and warm-started from
the previous solve's primal and dual iterates; and, as a benchmark pattern, the same solver
set up afresh and solved cold on every call."""

from __future__ import annotations

import signal
from typing import ClassVar

import numpy as np
import osqp
import scipy.sparse as sp

from ..vehicle.config import SolverSettings
from .outcome import Outcome, Solution

ACCEPTED = {int(osqp.SolverStatus.OSQP_SOLVED): Outcome.SOLVED,
            int(osqp.SolverStatus.OSQP_SOLVED_INACCURATE): Outcome.INACCURATE}
"""OSQP statuses whose solution is used, and the outcome each is; after any other the pseudo-inverse answers, unless a
stopped iterate is feasible enough (ITERATE_TOLERANCE), and an answer not used makes the next
solve start cold."""

INTERRUPTED = int(osqp.SolverStatus.OSQP_SIGINT)
"""OSQP catches SIGINT while it solves and only stops; the signal is raised again for the process."""

CHECK_TERMINATION = 5
"""Iterations between OSQP's convergence checks: warm-started samples often converge in a few."""

OSQP_INFINITY = float(osqp.constant("OSQP_INFTY"))
"""OSQP's stand-in for an infinite bound (``NO_BOUND``); larger values are clipped to it."""

STOPPED = frozenset((int(osqp.SolverStatus.OSQP_MAX_ITER_REACHED), int(osqp.SolverStatus.OSQP_TIME_LIMIT_REACHED)))
"""Statuses of a solve stopped by its budget: the iterate is used when it is feasible enough."""

ITERATE_TOLERANCE = 100.0
"""A stopped solve's iterate is used when its primal residual is within this many eps_abs
(normalised units, 1e-3 of a variable's range by default): with Q >> W the wrench converges
long before the split of effort among actuators (directions only W decides, 1e6 flatter), so
such an iterate gives the wrench and keeps every limit; warm starting carries the remaining
work over to the next sample."""

DUAL_RANGE = 10.0
"""A stopped solve whose row multipliers exceed this many times the cost's largest curvature is
no warm start, even when its iterate is used: with the problem's scaling those are the
multipliers of a request missed by more than ten times a DOF's authority (a 1e12 N wrench),
and warm-started from them the ordinary requests after it stopped at ``max_iter`` every
sample."""


def osqp_settings(settings: SolverSettings) -> dict:
    """OSQP settings a configuration may change at runtime (time_limit 0: none)."""
    return dict(eps_abs=settings.eps_abs, eps_rel=settings.eps_rel, max_iter=settings.max_iter,
                time_limit=settings.time_limit if settings.time_limit > 0.0 else 1e10)


def _diagonal(values: np.ndarray) -> sp.csc_matrix:
    index = np.arange(len(values))
    matrix = sp.csc_matrix((values, (index, index)), shape=(len(values), len(values)))
    matrix.sort_indices()
    return matrix


_STATUS: dict[int, str] = {}
"""OSQP's status texts by value, read from OSQP once each."""


def _result(info, solution, settings: SolverSettings) -> Solution:
    value = info.status_val
    if value == INTERRUPTED:
        signal.raise_signal(signal.SIGINT)      # Ctrl-C or a SIGINT stop meant for the process
    status = _STATUS.get(value)
    if status is None:
        status = _STATUS[value] = info.status
    outcome = ACCEPTED.get(value, Outcome.FAILED)
    if value in STOPPED and info.prim_res <= ITERATE_TOLERANCE * settings.eps_abs:
        outcome = Outcome.ITERATION_LIMIT
        status = f"{status}: iterate used (primal residual {info.prim_res:.1e})"
    return Solution(x=solution.x, status=status, iterations=info.iter, outcome=outcome, residual=info.prim_res,
                    duals=lambda: solution.y)


class OSQPBackend:
    """One OSQP instance for the life of the problem: values updated, warm-started."""

    name: ClassVar[str] = "osqp"

    def setup(self, p_diagonal: np.ndarray, q: np.ndarray, a: sp.csc_matrix, settings: SolverSettings) -> None:
        rows = a.shape[0]
        self.solver = osqp.OSQP()
        self.solver.setup(P=_diagonal(p_diagonal), q=q, A=a, l=np.full(rows, -OSQP_INFINITY),
                          u=np.full(rows, OSQP_INFINITY), verbose=False, warm_starting=True, polishing=False, scaling=0,
                          check_termination=CHECK_TERMINATION, **osqp_settings(settings))
        self.settings = settings
        self._index_type = np.int64 if self.solver.ext.OSQP_USE_LONG == 1 else np.int32
        # The per-sample calls go to OSQP's extension object when it offers them: the Python
        # wrapper's update() and solve() add about 25 us of bookkeeping per sample (constant
        # look-ups, an info dictionary). Same calls, same data; test_osqp_backend pins the
        # attributes used, so an OSQP release that drops them fails there, not silently here.
        raw = getattr(self.solver, "_solver", None)
        self._raw = raw if all(hasattr(raw, name) for name in RAW_CALLS) else None
        self._cold = (np.zeros(a.shape[1]), np.zeros(rows))
        self._p_diagonal = p_diagonal

    def update_objective(self, p_diagonal: np.ndarray | None, q: np.ndarray | None) -> None:
        if p_diagonal is not None:
            self.solver.update(Px=p_diagonal)
            self._p_diagonal = p_diagonal
        if q is not None:
            if self._raw is not None:
                self._raw.update_data_vec(q=q, l=None, u=None)
            else:
                self.solver.update(q=q)

    def update_matrix(self, values: np.ndarray, index: np.ndarray | None, p_diagonal: np.ndarray | None = None) -> None:
        if p_diagonal is not None:
            self._p_diagonal = p_diagonal
        if index is None:
            self.solver.update(Ax=values, Px=p_diagonal)
        elif self._raw is not None:
            self._raw.update_data_mat(P_x=p_diagonal, P_i=None, A_x=values,
                                      A_i=index.astype(self._index_type, copy=False))
        elif p_diagonal is None:
            self.solver.update(Ax=values, Ax_idx=index)
        else:
            self.solver.update(Ax=values, Ax_idx=index, Px=p_diagonal)

    def update_settings(self, settings: SolverSettings) -> None:
        self.solver.update_settings(**osqp_settings(settings))
        self.settings = settings

    def solve(self, low: np.ndarray, up: np.ndarray, q: np.ndarray | None = None) -> Solution:
        """Solve from the previous solve's iterates, or from zero after a solve whose answer
        could not be used or that stopped with multipliers out of range (DUAL_RANGE). Such
        iterates are no guide to the next problem: after a request far past the vehicle's
        capability (the multipliers grow with the miss), a warm start from them took
        ``max_iter`` every sample, for as long as anyone watched. Any other stopped solve whose
        iterate is used warm-starts the next: its work carries over (at a thruster's limit on
        the DP vessel without rate limits, restarting cold after each such stop left every
        sample at ``max_iter``)."""
        np.maximum(low, -OSQP_INFINITY, out=low)
        np.minimum(up, OSQP_INFINITY, out=up)
        if self._raw is None:
            self.solver.update(l=low, u=up) if q is None else self.solver.update(q=q, l=low, u=up)
            result = self.solver.solve(raise_error=False)
            info, solution, restart = result.info, result, self.solver.warm_start
        else:
            self._raw.update_data_vec(q=q, l=low, u=up)
            self._raw.solve()
            info, solution, restart = self._raw.info, self._raw.solution, self._raw.warm_start
        answer = _result(info, solution, self.settings)
        if not answer.usable or (info.status_val in STOPPED and np.max(np.abs(solution.y))
                                 > DUAL_RANGE * np.max(self._p_diagonal, initial=0.0)):
            restart(*self._cold)
        return answer


RAW_CALLS = ("update_data_vec", "update_data_mat", "solve", "solution", "info", "warm_start")
"""What :class:`OSQPBackend` calls on OSQP's extension object."""


class FreshOSQPBackend:
    """A new OSQP instance set up and solved cold on every call: what allocators that build
    their QP each sample do. For benchmarks; the node never uses it."""

    name: ClassVar[str] = "osqp_fresh"

    def setup(self, p_diagonal: np.ndarray, q: np.ndarray, a: sp.csc_matrix, settings: SolverSettings) -> None:
        self.p = _diagonal(p_diagonal)
        self.q = q.copy()
        self.a = a.copy()
        self.settings = settings

    def update_objective(self, p_diagonal: np.ndarray | None, q: np.ndarray | None) -> None:
        if p_diagonal is not None:
            self.p = _diagonal(p_diagonal)
        if q is not None:
            self.q = q.copy()

    def update_matrix(self, values: np.ndarray, index: np.ndarray | None, p_diagonal: np.ndarray | None = None) -> None:
        if index is None:
            self.a.data[:] = values
        else:
            self.a.data[index] = values
        if p_diagonal is not None:
            self.p = _diagonal(p_diagonal)

    def update_settings(self, settings: SolverSettings) -> None:
        self.settings = settings

    def solve(self, low: np.ndarray, up: np.ndarray, q: np.ndarray | None = None) -> Solution:
        if q is not None:
            self.q = q.copy()
        solver = osqp.OSQP()
        solver.setup(P=self.p, q=self.q, A=self.a, l=np.maximum(low, -OSQP_INFINITY), u=np.minimum(up, OSQP_INFINITY),
                     verbose=False, polishing=False, scaling=0, check_termination=CHECK_TERMINATION,
                     **osqp_settings(self.settings))
        result = solver.solve(raise_error=False)
        return _result(result.info, result, self.settings)
