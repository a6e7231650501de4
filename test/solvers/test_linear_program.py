"""solvers.linear_program.solve_linear_programme: one programme with inequality rows, equality
rows and column bounds, against scipy's linprog (both HiGHS); FAILED when infeasible or
unbounded."""

import numpy as np
import pytest
from scipy.optimize import linprog

from allocator_pkg.solvers.linear_program import solve_linear_programme
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
