"""The OSQP backend: SIGINT handling, the extension-object calls it makes per sample, and no
warm start from a solve that did not converge."""

import os
import signal
import threading
import time

import numpy as np
import osqp
import pytest
import scipy.sparse as sp
from conftest import ROOT, vehicle_from

from allocator_pkg import Allocator
from allocator_pkg.effectiveness.model import Model
from allocator_pkg.solvers.osqp_backend import RAW_CALLS, OSQPBackend
from allocator_pkg.solvers.problem import ScaledProblem
from allocator_pkg.vehicle.config import SolverSettings


def test_sigint_during_a_solve_is_raised_again_for_the_process():
    """OSQP installs its own SIGINT handler while it iterates and just stops (status
    'interrupted'); without passing it on, Ctrl-C or a launch system's SIGINT would be lost
    and the node would keep running."""
    size = 300
    rng = np.random.default_rng(0)
    a = sp.random(size, size, density=0.2, random_state=1, format="csc")
    a.sort_indices()
    problem = ScaledProblem(np.ones(size), rng.normal(size=size), a, np.ones(size),
                            SolverSettings(1e-15, 1e-15, 10**9, 20.0), np.arange(size), OSQPBackend())
    received = []
    previous = signal.signal(signal.SIGINT, lambda *_: received.append(time.monotonic()))
    try:
        threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT)).start()
        solution = problem.solve(-np.ones(size), np.ones(size))
    finally:
        signal.signal(signal.SIGINT, previous)
    assert solution.status == "interrupted" and not solution.usable
    assert len(received) == 1


def test_the_extension_calls_are_there_and_used():
    """The backend skips OSQP's Python wrapper per sample (about 25 us of bookkeeping) by
    calling the extension object. Its attribute is private to osqp; if a release drops or
    renames it, this fails, rather than the backend silently falling back to the slow path."""
    problem = osqp.OSQP()
    problem.setup(P=sp.eye(2, format="csc"), q=np.zeros(2), A=sp.eye(2, format="csc"), l=-np.ones(2),
                  u=np.ones(2), verbose=False)
    missing = [name for name in RAW_CALLS if not hasattr(problem._solver, name)]
    assert not missing, f"osqp {osqp.__version__} changed its extension object: {missing} gone"
    backend = OSQPBackend()
    backend.setup(np.ones(2), np.array([1.0, -1.0]), sp.eye(2, format="csc"), SolverSettings(1e-8, 1e-8, 1000, 0.0))
    assert backend._raw is not None
    result = backend.solve(np.array([-0.5, -0.5]), np.array([0.5, 0.5]))
    assert result.usable and np.allclose(result.x, [-0.5, 0.5], atol=1e-6)


def test_after_a_stopped_solve_the_next_starts_cold():
    """A solve stopped at max_iter far from feasible (its answer not used) leaves iterates that
    are no guide to the next problem; the next solve starts from zero, exactly as a new solver
    would (same iterations, same x)."""
    rng = np.random.default_rng(3)
    size = 12
    a = sp.csc_matrix(rng.normal(size=(size, size)))
    a.sort_indices()
    q = rng.normal(size=size)
    far, near = 1e9 * np.ones(size), 0.5 * np.ones(size)
    stopped = OSQPBackend()
    stopped.setup(np.ones(size), q, a, SolverSettings(1e-6, 1e-6, 3, 0.0))
    first = stopped.solve(far.copy(), far + 1.0)
    assert first.status.startswith("maximum iterations") and not first.usable
    stopped.update_settings(SolverSettings(1e-6, 1e-6, 4000, 0.0))
    fresh = OSQPBackend()
    fresh.setup(np.ones(size), q, a, SolverSettings(1e-6, 1e-6, 4000, 0.0))
    after, cold = stopped.solve(-near, near.copy()), fresh.solve(-near, near.copy())
    assert after.usable and after.iterations == cold.iterations
    assert np.array_equal(after.x, cold.x)


@pytest.mark.parametrize("config", ["dp_vessel.yaml", "bluerov2_heavy.yaml", "example1_rov.yaml"])
@pytest.mark.parametrize("excess", [10.0, 1e6, 1e12])
@pytest.mark.parametrize("method", ["qp", "nonlinear"])
def test_a_request_far_past_capability_does_not_poison_the_next_samples(method, config, excess):
    """Both methods on OSQP, with and without rotatable thrusters. Three samples of a request
    ``excess`` times each DOF's authority (a controller winding up, a 1e12 wrench), then
    ordinary requests again: the multipliers of the far request are no warm start for the
    ordinary ones. From the second ordinary sample on every solve converges, in every
    direction tried; before, the solver stopped at max_iter in every sample for as long as the
    stream went on."""
    vehicle = vehicle_from(ROOT / "config" / config)
    rng = np.random.default_rng(7)
    alloc = Allocator(vehicle, method=method)
    model = Model.build(vehicle, alloc.dt)
    authority = np.zeros(6)
    authority[model.dof_index] = model.dof_scale
    for _ in range(4):
        direction = rng.normal(size=6)
        ordinary = 0.3 * authority * direction / np.max(np.abs(direction))
        for _ in range(20):
            alloc.allocate(ordinary)
        for _ in range(3):
            far = alloc.allocate(excess * authority * np.sign(direction))
            assert np.all(np.isfinite(far.thrust)) and np.all(np.isfinite(far.command))
        after = [alloc.allocate(ordinary).status for _ in range(12)]
        assert all(status == "solved" for status in after[1:]), after


def test_a_stopped_solve_with_the_multipliers_of_a_far_request_is_no_warm_start():
    """The soak's stream on the DP vessel at 500 Hz (a random walk over +-60 % of each DOF's
    authority) with three samples of a 1e12 wrench every 1000 samples. A stopped solve right
    after such a burst may still have its iterate used, yet carry the burst's multipliers; warm-
    started from them, one burst left 500 ordinary samples at max_iter. Out of range (DUAL_RANGE)
    they are dropped: only the bursts' own samples and the first after each may stop."""
    vehicle = vehicle_from(ROOT / "config" / "dp_vessel.yaml")
    alloc = Allocator(vehicle, method="qp", dt=0.002)
    model = Model.build(vehicle, alloc.dt)
    authority = np.zeros(6)
    authority[model.dof_index] = model.dof_scale
    rng = np.random.default_rng(1)
    walk = np.zeros(6)
    stopped = 0
    for k in range(6000):
        walk += -walk * 0.001 + rng.normal(size=6) * np.sqrt(0.002)
        far = k % 1000 in (500, 501, 502)
        result = alloc.allocate(authority * (1e12 if far else 0.6 * walk))
        stopped += not far and result.iterations >= vehicle.solver.max_iter
    assert stopped <= 12
