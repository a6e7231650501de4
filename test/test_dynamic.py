"""The dynamic method (section 5.1): its equilibrium is the optimum (independent references:
scipy's BVLS for fixed thrusters, SLSQP with the thrust circles for azimuths, qp on the shipped
vessels with sectors and rate limits), its Lyapunov function never rises for a held request,
and a smooth request is followed with no lag."""

import math

import numpy as np
import pytest
from conftest import DATA, ROOT, vehicle_from
from reference import bounded_least_squares, circle_allocation

from allocator_pkg import Allocator, FaultMode
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
