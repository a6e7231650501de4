"""The solvers, knowing matrices only: QP solvers behind one seam
(:class:`~.problem.ScaledProblem` owns the rows and their scaling, a :class:`~.backend.Backend`
solves the normalised problem), the HiGHS linear programme (:class:`~.linear_program.LinearProgram`),
and what every solve gives back (:class:`~.outcome.Solution` with its :class:`~.outcome.Outcome`).

``BACKENDS`` names every backend installed here: ``osqp`` (the package's solver: set up
once, updated and warm-started), ``osqp_fresh`` (a new OSQP every solve, a benchmark
pattern), ``daqp`` (dense dual active set: exact, the forbidden-sector planner's solver) and,
when installed, ``quadprog`` (dense active set, an exact reference). A new backend is one module with a class of the
:class:`~.backend.Backend` protocol and one line here.
"""

from __future__ import annotations

from .backend import Backend, BackendFactory
from .daqp_backend import DAQPBackend
from .osqp_backend import FreshOSQPBackend, OSQPBackend
from .outcome import Solution

BACKENDS: dict[str, BackendFactory] = {"osqp": OSQPBackend, "osqp_fresh": FreshOSQPBackend, "daqp": DAQPBackend}

try:
    from .quadprog_backend import QuadprogBackend
    BACKENDS["quadprog"] = QuadprogBackend
except ImportError:             # quadprog is a development dependency
    pass

DEFAULT_BACKEND = "osqp"

__all__ = ["BACKENDS", "DEFAULT_BACKEND", "Backend", "BackendFactory", "Solution"]
