"""The method stage: the configured method, and the weighted pseudo-inverse when it fails."""

import numpy as np
import pytest
from conftest import ROOT, matrices, vehicle_from
from reference import weighted_pseudo_inverse

from allocator_pkg import Allocator, ConfigError, Outcome
from allocator_pkg.allocation.solve import check_method

EIGHT = ROOT / "test" / "data" / "eight_thrusters.yaml"
DP = ROOT / "config" / "dp_vessel.yaml"


def test_a_method_that_fails_is_answered_by_the_pseudo_inverse_with_its_reason():
    vehicle = vehicle_from(EIGHT, solver__max_iter=1)
    t, w, _, _ = matrices(vehicle)
    alloc = Allocator(vehicle)
    tau = np.zeros(6)
    tau[list(vehicle.dof_indices)] = 0.05 * np.abs(t).sum(axis=1).max()       # well inside every limit
    result = alloc.allocate(tau)
    assert result.outcome is Outcome.FALLBACK and result.reason.startswith("maximum iterations")
    assert result.status == f"fallback: pseudoinverse ({result.reason})"
    assert result.thrust == pytest.approx(weighted_pseudo_inverse(t, w) @ tau[list(vehicle.dof_indices)], abs=1e-9)
    assert alloc.stats.fallbacks == 1 and alloc.stats.samples == 1


def test_a_method_that_converges_says_so_with_its_residual():
    alloc = Allocator(vehicle_from(EIGHT))
    result = alloc.allocate([20.0, -10.0, 5.0, 0.0, 0.0, 3.0])
    assert result.outcome is Outcome.SOLVED and result.status == "solved" and result.reason == ""
    assert result.residual is not None and 0.0 <= result.residual <= alloc.vehicle.solver.eps_abs
    assert alloc.stats.fallbacks == 0


def test_a_method_is_refused_with_the_reason_it_cannot_serve_the_vehicle():
    with pytest.raises(ConfigError, match="method: 'explicit' cannot serve this vehicle: it needs actuators of fixed"):
        check_method("explicit", vehicle_from(DP))
    check_method("qp", vehicle_from(DP))
