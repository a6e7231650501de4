"""The qp method (1.35) on OSQP, against independent solutions."""

import numpy as np
import pytest
from conftest import DATA, ROOT, vehicle_from
from reference import constrained_allocation, largest_attainable_scale, weighted_pseudo_inverse

from allocator_pkg import Allocator, FaultMode
from allocator_pkg.configuration_matrix import configuration_matrix

Q = [1e7] * 6
EIGHT = DATA / "eight_thrusters.yaml"


def matrices(vehicle):
    t = configuration_matrix(vehicle.actuators, [0.0] * len(vehicle.actuators))[list(vehicle.dof_indices)]
    w = np.array([a.weight for a in vehicle.actuators])
    low = np.array([a.thrust_min for a in vehicle.actuators])
    high = np.array([a.thrust_max for a in vehicle.actuators])
    return t, w, low, high


def test_attainable_request_is_met_and_equals_the_weighted_pseudo_inverse():
    vehicle = vehicle_from(EIGHT, weights__slack=Q, **{f"actuators__t{i}__weight": 1.0 + 0.25 * i for i in range(1, 9)})
    alloc = Allocator(vehicle)
    tau = np.array([10.0, -5.0, 8.0, 1.0, -0.5, 2.0])
    result = alloc.allocate(tau)
    t, w, _, _ = matrices(vehicle)
    expected = weighted_pseudo_inverse(t, w) @ tau
    assert not result.saturated
    assert np.max(np.abs(result.achieved - tau)) <= 1e-4 * np.max(np.abs(tau))
    assert result.thrust == pytest.approx(expected, rel=1e-4, abs=1e-4)
    assert result.thrust @ (w * result.thrust) == pytest.approx(expected @ (w * expected), rel=1e-4)


@pytest.mark.parametrize("tau", [
    [60.0, 0.0, 0.0, 0.0, 0.0, 0.0],             # attainable, horizontal thrusters near their limits
    [20.0, 30.0, 40.0, 5.0, 0.0, 3.0],
    [200.0, -100.0, 150.0, 20.0, -15.0, 12.0],   # far outside: saturated
])
def test_active_bounds_match_an_independent_solver(tau):
    vehicle = vehicle_from(EIGHT, weights__slack=Q)
    t, w, low, high = matrices(vehicle)
    tau = np.array(tau)
    expected = constrained_allocation(t, w, np.array(Q), low, high, tau)
    result = Allocator(vehicle).allocate(tau)
    assert np.all(result.thrust >= low - 1e-9) and np.all(result.thrust <= high + 1e-9)
    scale = np.max(high)
    assert np.max(np.abs(result.thrust - expected)) <= 1e-3 * scale
    assert result.saturated == bool(np.max(np.abs(t @ expected - tau)) > 1e-2)


def test_minimax_weight_lowers_the_largest_force():
    # Two surge thrusters of very different weight: least squares loads the cheap one.
    plain = vehicle_from(EIGHT, weights__slack=Q, actuators__t1__weight=0.2)
    tau = np.array([30.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    f0 = Allocator(plain).allocate(tau).thrust
    minimax = vehicle_from(EIGHT, weights__slack=Q, actuators__t1__weight=0.2, weights__minimax=200.0)
    result = Allocator(minimax).allocate(tau)
    assert not result.saturated
    assert np.max(np.abs(result.thrust)) < np.max(np.abs(f0)) - 1.0
    t, w, low, high = matrices(minimax)
    expected = constrained_allocation(t, w, np.array(Q), low, high, tau, beta=200.0)
    assert np.max(np.abs(result.thrust - expected)) <= 1e-3 * np.max(high)


def test_rate_limits_tighten_the_box_around_the_previous_thrust():
    vehicle = vehicle_from(EIGHT, **{f"actuators__t{i}__thrust_rate_max": 50.0 for i in range(1, 9)})
    alloc = Allocator(vehicle, dt=0.1)                   # 5 N per sample
    previous = np.zeros(8)
    for _ in range(4):
        result = alloc.allocate([80.0, 0.0, 60.0, 0.0, 0.0, 0.0])
        assert np.all(np.abs(result.thrust - previous) <= 5.0 + 1e-9)
        previous = result.thrust
    assert result.saturated


def test_faults_change_bounds_without_a_new_solver():
    vehicle = vehicle_from(EIGHT, weights__slack=Q)
    alloc = Allocator(vehicle)
    tau = np.array([15.0, 5.0, 10.0, 0.0, 0.0, 1.0])
    alloc.allocate(tau)
    setups = alloc.stats.solver_setups
    alloc.set_fault("t1", FaultMode.FAILED)
    result = alloc.allocate(tau)
    assert result.thrust[0] == 0.0
    assert result.mode[0] == FaultMode.FAILED
    assert not result.saturated and np.max(np.abs(result.achieved - tau)) < 1e-3
    alloc.set_fault("t5", FaultMode.DEGRADED, efficiency=0.25)
    result = alloc.allocate([0.0, 0.0, 120.0, 0.0, 0.0, 0.0])
    assert -30.0 * 0.25 - 1e-9 <= result.thrust[4] <= 40.0 * 0.25 + 1e-9
    alloc.clear_faults()
    result = alloc.allocate(tau)
    assert np.all(result.mode == FaultMode.NOMINAL)
    assert alloc.stats.solver_setups == setups


def test_value_changes_update_the_solver_and_structure_changes_rebuild_it():
    alloc = Allocator(vehicle_from(EIGHT))
    alloc.allocate([1.0, 0, 0, 0, 0, 0])
    alloc.reconfigure(vehicle_from(EIGHT, actuators__t1__thrust_max=20.0, actuators__t2__position=[0.2, -0.1, 0.1],
                                   weights__minimax=1.0))
    result = alloc.allocate([100.0, 0, 0, 0, 0, 0])
    assert result.thrust[0] <= 20.0 + 1e-9
    assert alloc.stats.solver_setups == 1
    alloc.reconfigure(vehicle_from(EIGHT, dofs=["surge", "sway", "yaw"]))
    alloc.allocate([1.0, 0, 0, 0, 0, 0])
    assert alloc.stats.solver_setups == 2


def test_preserve_direction_scales_the_request_to_the_attainable_boundary():
    vehicle = vehicle_from(EIGHT, saturation="preserve_direction", weights__slack=Q)
    tau = np.array([150.0, 60.0, 40.0, 0.0, 0.0, 10.0])
    result = Allocator(vehicle).allocate(tau)
    t, _, low, high = matrices(vehicle)
    scale = largest_attainable_scale(t, low, high, tau)
    assert 0.2 < scale < 1.0
    assert result.saturated
    assert result.achieved == pytest.approx(scale * tau, rel=2e-3, abs=2e-2)


def test_solver_failure_falls_back_to_the_clipped_pseudo_inverse_and_recovers():
    vehicle = vehicle_from(EIGHT, solver__max_iter=1, weights__slack=Q)
    alloc = Allocator(vehicle)
    result = alloc.allocate([300.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert result.status.startswith("fallback")
    assert alloc.stats.fallbacks == 1
    assert np.all(np.abs(result.thrust) <= 40.0) and np.all(np.isfinite(result.thrust))
    alloc.reconfigure(vehicle_from(EIGHT, weights__slack=Q))
    result = alloc.allocate([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert result.status == "solved"
    assert alloc.stats.solver_setups == 1


def test_example_vehicle_allocates_surge_sway_yaw():
    vehicle = vehicle_from(ROOT / "config" / "example1_rov.yaml")
    alloc = Allocator(vehicle)
    for _ in range(200):
        result = alloc.allocate([150.0, 40.0, 0.0, 0.0, 0.0, 30.0])
    assert not result.saturated
    assert result.achieved[[0, 1, 5]] == pytest.approx([150.0, 40.0, 30.0], rel=1e-4)
