"""The actuation stage: forces within limits, the achieved wrench from T of what is
commanded, what is short, and the stop."""

import numpy as np
import pytest
from conftest import ROOT, matrices, vehicle_from

from allocator_pkg import Allocator, Outcome

EIGHT = ROOT / "test" / "data" / "eight_thrusters.yaml"


def test_an_unattainable_request_reports_the_rest_and_the_dofs_short():
    vehicle = vehicle_from(EIGHT)
    t, _, low, high = matrices(vehicle)
    alloc = Allocator(vehicle)
    tau = np.zeros(6)
    tau[vehicle.dof_indices[0]] = 10.0 * np.abs(t[0]) @ np.maximum(high, -low)      # ten times surge's authority
    result = alloc.allocate(tau)
    assert np.all(result.thrust >= low - 1e-9) and np.all(result.thrust <= high + 1e-9)
    controlled = list(vehicle.dof_indices)
    assert result.achieved[controlled] == pytest.approx(t @ result.thrust, abs=1e-9)
    assert result.unallocated[controlled] == pytest.approx(tau[controlled] - result.achieved[controlled], abs=1e-9)
    tolerance = alloc.dof_tolerance
    expected = tuple(d for d, m, tol in zip(vehicle.dofs, result.unallocated[controlled], tolerance) if abs(m) > tol)
    assert result.short == expected and result.short[0] == vehicle.dofs[0] and result.saturated


def test_stop_commands_zero_thrust_with_the_angles_held():
    alloc = Allocator(vehicle_from(ROOT / "config" / "dp_vessel.yaml"))
    for _ in range(30):
        alloc.allocate([2e5, 1e5, 0.0, 0.0, 0.0, 1e6])
    angles = alloc.azimuth
    result = alloc.stop()
    assert result.outcome is Outcome.STOPPED and result.status == "stopped"
    assert np.all(result.thrust == 0.0) and np.array_equal(result.azimuth, angles)
    assert np.array_equal(alloc.thrust, np.zeros(len(angles)))
