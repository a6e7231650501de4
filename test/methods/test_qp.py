"""The qp method (1.35) on OSQP, against independent solutions."""

import math

import numpy as np
import pytest
from conftest import DATA, ROOT, matrices, vehicle_from
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import constrained_allocation, largest_attainable_scale, weighted_pseudo_inverse

from allocator_pkg import Allocator, FaultMode

Q = [1e7] * 6
EIGHT = DATA / "eight_thrusters.yaml"


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


@pytest.mark.parametrize(("config", "base", "moved"), [
    ("dp_vessel.yaml", {}, {"actuators__azimuth_stbd__position": [-38.0, 6.0, 4.5],
                            "actuators__tunnel_fwd__position": [33.0, 0.5, 3.5]}),
    ("example1_rov.yaml", {"weights__minimax": 2.0},
     {"actuators__azimuth_fwd__position": [1.0, 0.1, 0.3], "actuators__main_port__position": [-1.1, -0.6, 0.0]}),
])
def test_a_moved_thruster_is_taken_by_values_and_answers_as_a_fresh_allocator(config, base, moved):
    """New positions change T_e's values, the only values of the solvers' constraint matrices
    a configuration of the same structure changes: the updated solvers (the method's and the
    forbidden-sector planner's) answer as ones set up for the moved geometry."""
    alloc = Allocator(vehicle_from(ROOT / "config" / config, **base))
    authority = alloc.model.authority
    requests = [np.array([c * math.cos(a), c * math.sin(a), 0.0, 0.0, 0.0, 0.2 * c * math.sin(3 * a)])
                for a in np.linspace(0.0, 2.0 * math.pi, 7, endpoint=False) for c in (0.4, 1.2)]
    scale = np.array([authority[0], authority[1], 0, 0, 0, authority[2]])
    for tau in requests:
        alloc.allocate(tau * scale)
    setups = alloc.stats.solver_setups
    moved_vehicle = vehicle_from(ROOT / "config" / config, **base, **moved)
    alloc.reconfigure(moved_vehicle)
    fresh = Allocator(moved_vehicle)
    for tau in requests:
        alloc.reset()
        fresh.reset()
        for _ in range(150):
            mine, theirs = alloc.allocate(tau * scale), fresh.allocate(tau * scale)
        assert mine.achieved == pytest.approx(theirs.achieved, abs=2e-3 * float(np.max(authority)))
        assert mine.thrust == pytest.approx(theirs.thrust, abs=2e-3 * float(np.max(np.abs(alloc.ranges))))
    assert alloc.stats.solver_setups == setups


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


PRIORITY_CASES = [
    (ROOT / "config" / "bluerov2_heavy.yaml", [2, 2, 0, 0, 0, 1], {}),  # depth and attitude, then yaw, then the rest
    (EIGHT, [1, 1, 0, 2, 2, 0], {}),                                    # heave and yaw, surge and sway, attitude
    (ROOT / "config" / "otter_usv.yaml", [1, 0],                         # yaw before surge; static: no rate limits
     {"actuators__propeller_port__thrust_rate_max": 0.0, "actuators__propeller_stbd__thrust_rate_max": 0.0}),
]


def _authority(t, low, high):
    return np.abs(t) @ np.maximum(np.abs(low), np.abs(high))


@pytest.mark.parametrize("path, priorities, static", PRIORITY_CASES,
                         ids=["bluerov2_heavy", "eight_thrusters", "otter_usv"])
def test_priorities_match_an_independent_lexicographic_solution(path, priorities, static):
    """A sweep of directions x magnitudes (0.5 to 4 times what the actuators can give along
    them): each level's achieved wrench equals scipy's level-by-level optimum."""
    from reference import lexicographic_allocation

    from allocator_pkg.capability.envelope import Capability
    vehicle = vehicle_from(path, priorities=priorities, **static)
    alloc = Allocator(vehicle)
    t, _, low, high = matrices(vehicle)
    low, high = alloc.ranges                                             # the voltage's limits on a T200 table
    authority = _authority(t, low, high)
    levels = [tuple(k for k, p in enumerate(vehicle.priorities) if p == level) for level in sorted(set(priorities))]
    capability = Capability(vehicle_from(path, **static))
    rng = np.random.default_rng(15)
    checked = 0
    setups = alloc.stats.solver_setups
    for _ in range(10):
        direction = np.zeros(6)
        direction[list(vehicle.dof_indices)] = rng.normal(size=len(vehicle.dofs)) * authority
        reach = capability.scale(direction)
        for magnitude in (0.5, 1.0, 1.5, 4.0):
            tau = magnitude * reach * direction
            result = alloc.allocate(tau)
            tau_c = tau[list(vehicle.dof_indices)]
            expected = lexicographic_allocation(t, low, high, tau_c, levels, 1.0 / authority ** 2)
            achieved = result.achieved[list(vehicle.dof_indices)]
            assert np.all(np.abs(achieved - expected) <= 2e-3 * authority), (tau_c, achieved, expected)
            checked += magnitude > 1.0
    assert checked == 20
    assert alloc.stats.solver_setups == setups                           # the cascade is values only


def test_without_priorities_the_same_request_trades_every_dof():
    """The lexicographic answer differs from the weighted one where it matters: a heave
    request beyond the verticals with a roll moment, roll first: roll is met exactly."""
    tau = np.array([0.0, 0.0, 400.0, 15.0, 0.0, 0.0])
    ordered = Allocator(vehicle_from(EIGHT, priorities=[1, 1, 1, 0, 1, 1])).allocate(tau)
    weighted = Allocator(vehicle_from(EIGHT)).allocate(tau)
    assert ordered.achieved[3] == pytest.approx(15.0, abs=1e-3)
    assert abs(weighted.achieved[3] - 15.0) > 0.1
    assert ordered.achieved[2] < weighted.achieved[2]


@settings(deadline=None)
@given(st.lists(st.floats(-1.0, 1.0), min_size=6, max_size=6), st.floats(0.2, 5.0))
def test_the_top_level_is_never_worse_for_the_levels_below(direction, magnitude):
    """Lexicographic: the highest level misses by no more than it would alone (the lower
    levels asking nothing)."""
    vehicle = vehicle_from(EIGHT, priorities=[1, 1, 0, 0, 0, 2])
    tau = magnitude * 160.0 * np.array(direction)
    full = Allocator(vehicle).allocate(tau)
    alone = Allocator(vehicle).allocate(np.where([False, False, True, True, True, False], tau, 0.0))
    top = [2, 3, 4]
    assert np.abs(full.achieved[top] - alone.achieved[top]).max() <= 1e-3 * 160.0
