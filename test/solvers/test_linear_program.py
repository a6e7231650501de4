"""solvers.linear_program: solve_linear_programme, one programme with inequality rows, equality
rows and column bounds, against scipy's linprog (both HiGHS); FAILED when infeasible or
unbounded; a kept LinearProgram with new values, solved from the last basis and from none."""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.optimize import linprog

from allocator_pkg.solvers.linear_program import LinearProgram, solve_linear_programme
from allocator_pkg.solvers.outcome import Outcome


def test_the_optimum_of_a_small_programme_is_linprogs():
    rng = np.random.default_rng(3)
    for _ in range(20):
        cost = rng.normal(size=5)
        a_ub, b_ub = rng.normal(size=(6, 5)), rng.uniform(1.0, 2.0, size=6)
        a_eq, b_eq = rng.normal(size=(2, 5)), rng.normal(size=2) * 0.1
        bounds = [(-3.0, 3.0), (None, 2.0), (-1.0, None), (-2.0, 2.0), (0.0, 1.0)]
        ours = solve_linear_programme(cost, bounds, a_ub, b_ub, a_eq, b_eq)
        theirs = linprog(cost, A_ub=a_ub, b_ub=b_ub, A_eq=a_eq, b_eq=b_eq, bounds=bounds, method="highs")
        assert (ours.outcome is Outcome.SOLVED) == (theirs.status == 0)
        if theirs.status == 0:
            assert cost @ ours.x == pytest.approx(theirs.fun, rel=1e-9, abs=1e-9)
            assert np.all(a_ub @ ours.x <= b_ub + 1e-9)
            np.testing.assert_allclose(a_eq @ ours.x, b_eq, atol=1e-9)


def test_infeasible_and_unbounded_fail_with_zeros():
    infeasible = solve_linear_programme(np.array([1.0]), [(0.0, None)], np.array([[1.0]]), np.array([-1.0]))
    unbounded = solve_linear_programme(np.array([-1.0]), [(0.0, None)])
    for solution in (infeasible, unbounded):
        assert solution.outcome is Outcome.FAILED and not solution.usable
        np.testing.assert_array_equal(solution.x, [0.0])


def test_a_kept_programme_solved_again_cold_or_warm_is_linprogs():
    """LinearProgram kept between solves: new row bounds and coefficients, solved from the last
    basis and from none (``cold``), each at linprog's optimum; cold starts with no basis to keep."""
    rng = np.random.default_rng(5)
    a = rng.normal(size=(8, 4))
    programme = LinearProgram()
    programme.setup(np.array([-1.0, -0.5, 0.2, -0.3]), np.full(4, -2.0), np.full(4, 2.0), sp.csc_matrix(a),
                    np.full(8, -np.inf), np.ones(8), 0.0)
    for k in range(12):
        up = rng.uniform(0.5, 2.0, size=8)
        value = float(rng.uniform(-1.0, 1.0))
        programme.up[:] = up
        programme.coefficient(0, 1, value)
        a[0, 1] = value
        cold = k % 3 == 2
        ours = programme.solve(cold=cold)
        theirs = linprog([-1.0, -0.5, 0.2, -0.3], A_ub=a, b_ub=up, bounds=[(-2.0, 2.0)] * 4, method="highs")
        assert ours.outcome is Outcome.SOLVED and theirs.status == 0
        assert np.array([-1.0, -0.5, 0.2, -0.3]) @ ours.x == pytest.approx(theirs.fun, rel=1e-9, abs=1e-9)
        if cold:
            assert ours.iterations > 0
