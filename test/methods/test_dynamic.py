"""The dynamic method (section 5.1): its equilibrium is the optimum (independent references:
scipy's BVLS for fixed thrusters, SLSQP with the thrust circles for azimuths, qp on the shipped
vessels with sectors and rate limits), its Lyapunov function never rises for a held request,
and a smooth request is followed with no lag."""

import math

import numpy as np
import pytest
from conftest import DATA, ROOT, vehicle_from
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from reference import bounded_least_squares, circle_allocation

from allocator_pkg import Allocator, FaultMode, vehicle_from_parameters
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix
from allocator_pkg.effectiveness.model import Model

EIGHT = DATA / "eight_thrusters.yaml"
DIRECTIONS = [np.array(d, dtype=float) for d in (
    (1, 0, 0, 0, 0, 0), (0, 1, 0, 0, 0, 0), (0, 0, 1, 0, 0, 0), (0, 0, 0, 1, 0, 0), (0, 0, 0, 0, 0, 1),
    (1, 1, 0, 0, 0, 0.2), (1, -0.5, 0.8, 0.1, -0.1, 0.3), (-0.3, 0.7, -1, 0.2, 0.2, -0.4))]


def held(allocator, tau, samples):
    return [allocator.allocate(tau) for _ in range(samples)]


@pytest.mark.parametrize("magnitude", [10.0, 60.0, 250.0])
def test_a_held_request_settles_on_the_optimum_of_1_35_for_fixed_thrusters(magnitude):
    weights = {f"actuators__t{i}__weight": 1.0 + 0.2 * i for i in range(1, 9)}
    vehicle = vehicle_from(EIGHT, **weights)
    model = Model.build(vehicle, 0.02)
    t = configuration_matrix(vehicle.actuators, [0.0] * 8)
    q = model.slack_weights(model.weight)
    low, high = model.thrust_min, model.thrust_max
    for direction in DIRECTIONS:
        tau = magnitude * direction / np.linalg.norm(direction)
        expected = bounded_least_squares(t, model.weight, q, low, high, tau)
        result = held(Allocator(vehicle, method="dynamic"), tau, 40)[-1]
        assert result.thrust == pytest.approx(expected, abs=1e-6 * 40.0)


def test_with_azimuths_the_equilibrium_is_the_optimum_with_the_exact_thrust_circle():
    """Example 1 without rate limits (so that only the optimum decides), against SLSQP on the
    same convex problem with |f| <= B for each azimuth."""
    free = {f"actuators__{name}__{key}": 0.0 for name in ("azimuth_fwd", "azimuth_aft")
            for key in ("azimuth_rate_max", "thrust_rate_max")}
    free.update({f"actuators__{name}__thrust_rate_max": 0.0 for name in ("main_port", "main_stbd")})
    vehicle = vehicle_from(ROOT / "config" / "example1_rov.yaml", weights__slack=[1e4] * 3, **free)
    model = Model.build(vehicle, 0.02)
    columns = {0: (0, 1), 1: (2, 3), 2: 4, 3: 5}
    for angle in np.radians(np.arange(0.0, 360.0, 30.0)):
        for magnitude in (150.0, 400.0, 900.0):
            tau = np.array([magnitude * math.cos(angle), 0.5 * magnitude * math.sin(angle), 0.0, 0.0, 0.0, 40.0])
            expected = circle_allocation(model.t_ec, model.weight_ext, np.array([1e4] * 3), columns,
                                         {2: (-200.0, 300.0), 3: (-200.0, 300.0)}, {0: 150.0, 1: 150.0},
                                         tau[[0, 1, 5]])
            result = held(Allocator(vehicle, method="dynamic"), tau, 60)[-1]
            extended = np.array([result.thrust[0] * math.cos(result.azimuth[0]),
                                 result.thrust[0] * math.sin(result.azimuth[0]),
                                 result.thrust[1] * math.cos(result.azimuth[1]),
                                 result.thrust[1] * math.sin(result.azimuth[1]), result.thrust[2], result.thrust[3]])
            assert extended == pytest.approx(expected, abs=2e-3 * 150.0)


@pytest.mark.parametrize("stem", ["dp_vessel", "example1_rov", "otter_usv", "infante_auv"])
def test_held_requests_reach_the_qp_optimum_within_every_limit_on_the_shipped_vehicles(stem):
    """Every 45 deg in the plane of the first two controlled DOFs, at 0.3 and 0.6 of the
    authority: after 300 samples the extended forces are within 1e-3 of each actuator's range
    of qp's settled answer (sectors, rate limits and the planner as shipped)."""
    vehicle = vehicle_from(ROOT / "config" / f"{stem}.yaml")
    model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
    first, second = model.dof_index[:2]
    for angle in np.radians(np.arange(0.0, 360.0, 45.0)):
        for share in (0.3, 0.6):
            tau = np.zeros(6)
            tau[first] = share * model.authority[0] * math.cos(angle)
            tau[second] = share * model.authority[1] * math.sin(angle)
            answers = []
            for method in ("qp", "dynamic"):
                allocator = Allocator(vehicle, method=method)
                allocator.set_speed(2.0)
                result = held(allocator, tau, 300)[-1]
                answers.append(np.concatenate((result.thrust * np.cos(result.azimuth),
                                               result.thrust * np.sin(result.azimuth))))
            scale = np.tile(model.force_scale, 2)
            assert np.max(np.abs(answers[1] - answers[0]) / scale) < 1e-3


def test_the_lyapunov_function_never_rises_for_a_held_request_and_falls_by_the_gain():
    vehicle = vehicle_from(EIGHT, dynamic__gain=0.3)
    for direction in DIRECTIONS:
        allocator = Allocator(vehicle, method="dynamic")
        method = allocator._solver.method
        tau = 120.0 * direction / np.linalg.norm(direction)
        request = tau / method._dof
        values = []
        for _ in range(60):
            allocator.allocate(tau)
            values.append(method._cost(method._x, request))
        floor = values[-1]
        excess = np.array(values) - floor
        assert np.all(np.diff(values) <= 1e-12 * max(abs(floor), 1.0))
        assert excess[-20] <= 1e-9 * max(abs(floor), 1.0)


def test_a_request_change_is_taken_whole_and_the_rest_falls_by_one_minus_the_gain_per_sample():
    """No limit active: the feed-forward follows a step of the request in one sample. A
    saturation from a request the thrusters cannot follow at once (a fault) is then removed at
    the gain's rate: (1 - h) per sample."""
    vehicle = vehicle_from(EIGHT, dynamic__gain=0.4)
    model = Model.build(vehicle, 0.02)
    t = configuration_matrix(vehicle.actuators, [0.0] * 8)
    q = model.slack_weights(model.weight)
    allocator = Allocator(vehicle, method="dynamic")
    tau = np.array([10.0, -4.0, 6.0, 0.5, 0.2, -0.8])
    result = allocator.allocate(tau)
    optimum = bounded_least_squares(t, model.weight, q, model.thrust_min, model.thrust_max, tau)
    assert result.thrust == pytest.approx(optimum, abs=1e-9 * 40.0)
    allocator.set_fault("t1", FaultMode.DEGRADED, efficiency=0.1)
    tau = np.array([30.0, -10.0, 6.0, 0.5, 0.2, -0.8])
    low, high = model.thrust_min.copy(), model.thrust_max.copy()
    low[0], high[0] = 0.1 * low[0], 0.1 * high[0]
    optimum = bounded_least_squares(t, model.weight, q, low, high, tau)
    distance = [np.max(np.abs(allocator.allocate(tau).thrust - optimum)) for _ in range(12)]
    ratios = np.array(distance[3:9]) / np.array(distance[2:8])
    assert ratios == pytest.approx(0.6, abs=0.02)


def test_a_smooth_request_is_followed_with_no_lag_while_no_limit_binds():
    """BlueROV2 Heavy (no rate limits), a request turning through every horizontal direction
    with the other DOFs varying: every sample is the optimum of that sample (scipy's BVLS)."""
    vehicle = vehicle_from(ROOT / "config" / "bluerov2_heavy.yaml")
    model = Model.build(vehicle, 0.02)
    t = model.t_ec
    q = model.slack_weights(model.weight)
    dynamic = Allocator(vehicle, method="dynamic")
    for k in range(200):
        turn = 2.0 * math.pi * k / 200
        tau = 0.2 * model.authority * np.array([math.cos(turn), math.sin(turn), 0.5 * math.sin(3 * turn),
                                                0.3 * math.cos(2 * turn), 0.2, 0.4 * math.sin(turn)])
        result = dynamic.allocate(tau)
        optimum = bounded_least_squares(t, model.weight, q, model.thrust_min, model.thrust_max, tau)
        assert result.thrust == pytest.approx(optimum, abs=1e-9 * 51.5)
        assert not result.saturated


# -- the optimum from any state, on vehicles nobody picked -----------------------------------

SETTLED = 1e-6
"""Relative excess of the objective (1.35) (beta = 0) over scipy's bounded least squares at
which a held request counts as settled."""


def work_class_rov(seed: int, slack: float | None = None):
    """Eight fixed thrusters of a work-class ROV drawn from ``seed``: four horizontal ones
    vectored 30-60 deg in the z = 0 plane, four vertical ones 0.4 m above it (z = -0.4, FRD),
    every lever arm drawn on its own (0.5-1.5 m fore and aft, 0.3-0.8 m to the sides), forward
    limits of 1500-3000 N and reverse ones 1/1.45 of them."""
    rng = np.random.default_rng(seed)
    parameters = {"dofs": ["surge", "sway", "heave", "roll", "pitch", "yaw"],
                  "actuators.names": [f"t{i}" for i in range(8)]}
    for i in range(8):
        fore, side = (1.0 if i % 4 < 2 else -1.0), (1.0 if i % 2 == 0 else -1.0)
        position = [fore * rng.uniform(0.5, 1.5), side * rng.uniform(0.3, 0.8), 0.0 if i < 4 else -0.4]
        angle = fore * side * math.radians(rng.uniform(30.0, 60.0))
        direction = [math.cos(angle), math.sin(angle), 0.0] if i < 4 else [0.0, 0.0, 1.0]
        forward = rng.uniform(1500.0, 3000.0)
        parameters.update({f"actuators.t{i}.type": "fixed", f"actuators.t{i}.position": position,
                           f"actuators.t{i}.direction": direction, f"actuators.t{i}.thrust_max": forward,
                           f"actuators.t{i}.thrust_min": -forward / 1.45})
    if slack is not None:
        parameters["weights.slack"] = [slack] * 6
    return vehicle_from_parameters(parameters)


def objective(model: Model, thrust: np.ndarray, tau: np.ndarray) -> float:
    """(1.35) with beta = 0 and the slack eliminated, in newtons: 1/2 f'Wf + 1/2 s'Qs."""
    miss = model.t_ec @ thrust - tau
    return 0.5 * float(thrust @ (model.weight_ext * thrust) + miss @ (model.slack_weights(model.weight) * miss))


def least_objective(model: Model, tau: np.ndarray) -> float:
    """The minimum of (1.35) (beta = 0) within the thrust ranges, from scipy's BVLS."""
    q = model.slack_weights(model.weight)
    optimum = bounded_least_squares(model.t_ec, model.weight_ext, q, model.thrust_min, model.thrust_max, tau)
    return objective(model, optimum, tau)


def excess_after(allocator: Allocator, tau: np.ndarray, samples: int) -> float:
    """The objective's relative excess over the optimum after holding ``tau`` for ``samples``."""
    result = held(allocator, tau, samples)[-1]
    best = least_objective(allocator.model, tau)
    return (objective(allocator.model, result.thrust, tau) - best) / best


def requests(model: Model, seed: int, count: int) -> list[np.ndarray]:
    """Held requests, each controlled DOF uniform in +-0.8 of its authority."""
    rng = np.random.default_rng(seed)
    return [0.8 * rng.uniform(-1.0, 1.0, model.n) * model.authority for _ in range(count)]


@pytest.mark.parametrize("slack", [None, 1e4])
def test_held_requests_from_rest_settle_on_the_optimum_of_a_work_class_rov(slack):
    """Seed 1's ROV: with three or more bounds active, every request settles within 60 samples
    from rest, with the default slack weights and with weights.slack 1e4 on every DOF."""
    vehicle = work_class_rov(1, slack)
    model = Allocator(vehicle, method="dynamic").model
    excess = [excess_after(Allocator(vehicle, method="dynamic"), tau, 60) for tau in requests(model, 101, 40)]
    assert max(excess) < SETTLED


@pytest.mark.parametrize("slack", [None, 1e4])
def test_a_sequence_of_held_requests_settles_on_each_optimum_of_a_work_class_rov(slack):
    """One allocator follows 40 requests to seed 1's ROV, 60 samples each: each settles."""
    vehicle = work_class_rov(1, slack)
    allocator = Allocator(vehicle, method="dynamic")
    excess = [excess_after(allocator, tau, 60) for tau in requests(allocator.model, 101, 40)]
    assert max(excess) < SETTLED


def test_a_sequence_of_held_requests_settles_on_each_optimum_of_eight_thrusters():
    """test/data/eight_thrusters.yaml: 170 requests in sequence (seed 11), 200 samples each;
    the 170th starts from the 169th's optimum, three bounds active and one 0.05 N short of
    its bound."""
    allocator = Allocator(vehicle_from(EIGHT), method="dynamic")
    excess = [excess_after(allocator, tau, 200) for tau in requests(allocator.model, 11, 170)]
    assert max(excess) < SETTLED


@st.composite
def fixed_vehicle(draw):
    """4-10 fixed thrusters anywhere within 2 m, in any direction, forward limits of 10-1000 N,
    reverse ones 0.2-1 of those, weights 0.5-3; all six DOFs controlled."""
    count = draw(st.integers(min_value=4, max_value=10))
    coordinate = st.floats(min_value=-2.0, max_value=2.0, allow_nan=False)
    parameters = {"dofs": ["surge", "sway", "heave", "roll", "pitch", "yaw"],
                  "actuators.names": [f"t{i}" for i in range(count)]}
    for i in range(count):
        direction = draw(st.tuples(coordinate, coordinate, coordinate).filter(lambda v: math.hypot(*v) > 0.2))
        forward = draw(st.floats(min_value=10.0, max_value=1000.0))
        parameters.update({f"actuators.t{i}.type": "fixed",
                           f"actuators.t{i}.position": list(draw(st.tuples(coordinate, coordinate, coordinate))),
                           f"actuators.t{i}.direction": list(direction), f"actuators.t{i}.thrust_max": forward,
                           f"actuators.t{i}.thrust_min": -forward * draw(st.floats(min_value=0.2, max_value=1.0)),
                           f"actuators.t{i}.weight": draw(st.floats(min_value=0.5, max_value=3.0))})
    return vehicle_from_parameters(parameters)


@settings(derandomize=True, max_examples=30, deadline=None, database=None)
@given(vehicle=fixed_vehicle(), share=st.lists(st.floats(min_value=-0.8, max_value=0.8), min_size=6, max_size=6))
def test_on_any_fixed_thruster_vehicle_a_held_request_settles_on_the_optimum(vehicle, share):
    """From rest and then from that optimum to the opposite request: within 150 samples each."""
    allocator = Allocator(vehicle, method="dynamic")
    tau = np.array(share) * allocator.model.authority
    assume(np.any(np.abs(tau) > 1e-6 * np.max(allocator.model.authority)))
    assert excess_after(allocator, tau, 150) < SETTLED
    assert excess_after(allocator, -tau, 150) < SETTLED
