"""The scaled problem and the backends behind it: every installed backend gives the same
answer, in physical units, as an independent solver of the same QP."""

import numpy as np
import pytest
from scipy.optimize import lsq_linear

from allocator_pkg.solvers import BACKENDS
from allocator_pkg.solvers.problem import Rows, ScaledProblem, entry_index
from allocator_pkg.vehicle.config import SolverSettings

SETTINGS = SolverSettings(eps_abs=1e-9, eps_rel=1e-9, max_iter=200000, time_limit=0.0)


def badly_scaled_problem():
    """min sum w_i x_i^2 + q s^2 s.t. x1 + 1e3 x2 - s = 5e3, 0 <= x1 <= 2e3, -1 <= x2 <= 3:
    variables six orders apart, as forces in N and small slacks are in an allocation."""
    rows = Rows()
    equality = rows.add([(0, 1.0), (1, 1e3), (2, -1.0)])
    rows.add([(0, 1.0)])
    rows.add([(1, 1.0)])
    a = rows.matrix(3)
    p = np.array([2.0, 2e6, 2e4])
    low = np.array([5e3, 0.0, -1.0])
    up = np.array([5e3, 2e3, 3.0])
    return p, a, low, up, equality


def reference(p, a, low, up):
    """The slack is the equality's residual, s = a0 . x - tau; what is left is a bounded
    least-squares problem in x (scipy's BVLS)."""
    row = a.toarray()[0]
    root = np.sqrt(0.5 * p)
    design = np.vstack([np.diag(root[:2]), root[2] * row[:2]])
    target = np.array([0.0, 0.0, root[2] * low[0]])
    x = lsq_linear(design, target, bounds=([low[1], low[2]], [up[1], up[2]]), method="bvls", tol=1e-14).x
    return np.array([x[0], x[1], row[:2] @ x - low[0]])


@pytest.mark.parametrize("backend", list(BACKENDS))
def test_every_backend_solves_the_scaled_problem_in_physical_units(backend):
    p, a, low, up, _ = badly_scaled_problem()
    problem = ScaledProblem(p, np.zeros(3), a, np.array([2e3, 3.0, 5e3]), SETTINGS, np.arange(2), BACKENDS[backend]())
    solution = problem.solve(low, up)
    expected = reference(p, a, low, up)
    assert solution.usable
    assert solution.x == pytest.approx(expected, rel=1e-4, abs=1e-3)


@pytest.mark.parametrize("backend", list(BACKENDS))
def test_values_on_the_same_pattern_change_the_answer(backend):
    """update_matrix by index and update_objective reach the backend (no new set-up)."""
    p, a, low, up, equality = badly_scaled_problem()
    problem = ScaledProblem(p, np.zeros(3), a, np.array([2e3, 3.0, 5e3]), SETTINGS, np.arange(2), BACKENDS[backend]())
    problem.solve(low, up)
    index = np.array([entry_index(a, equality, 1)])
    problem.update_matrix(np.array([2e3]), index)
    p_new = p * np.array([1.0, 0.5, 1.0])
    problem.update_objective(p_new)
    changed = a.copy()
    changed.data[index] = 2e3
    solution = problem.solve(low, up)
    assert solution.x == pytest.approx(reference(p_new, changed, low, up), rel=1e-4, abs=1e-3)


@pytest.mark.parametrize("backend", list(BACKENDS))
def test_every_backend_gives_the_multipliers_in_one_convention(backend):
    """y with P x + q + A'y = 0 (OSQP's convention): the methods read a thruster limit's
    multiplier from it, whichever backend solved. The active rows here: the equality (its
    multiplier is 2 q s, the slack's cost gradient: its column in A is -1) and x1's upper bound
    (x1 = 2000: its multiplier is positive); x2 stays just under its bound (multiplier 0)."""
    p, a, low, up, _ = badly_scaled_problem()
    problem = ScaledProblem(p, np.zeros(3), a, np.array([2e3, 3.0, 5e3]), SETTINGS, np.arange(2), BACKENDS[backend]())
    solution = problem.solve(low, up)
    stationarity = p * solution.x + a.T @ solution.y
    assert np.max(np.abs(stationarity)) <= 1e-4 * np.max(np.abs(solution.y))
    assert solution.y[0] == pytest.approx(p[2] * solution.x[2], rel=1e-4)
    assert solution.x[0] == pytest.approx(2e3) and solution.y[1] > 0.0
    assert solution.y[2] == pytest.approx(0.0, abs=1e-6 * abs(solution.y[0]))
