"""The lp method (section 5.3) on HiGHS, against scipy's linprog on the same criterion, the
survey's polygon error measured, and its sparsity against qp on every shipped vehicle."""

import math

import numpy as np
import pytest
from conftest import DATA, ROOT, bench_module, matrices, vehicle_from
from reference import largest_attainable_scale, weighted_l1_allocation

from allocator_pkg import Allocator, FaultMode
from allocator_pkg.effectiveness.model import AzimuthLimits, Model, SampleLimits
from allocator_pkg.methods.lp import LPAllocation
from allocator_pkg.methods.sample_lp import ORDER_SHARE, polygon_error, survey_apothem, tie_break
from allocator_pkg.solvers import BACKENDS

sparsity = bench_module("sparsity")
EIGHT = DATA / "eight_thrusters.yaml"
Q = [1e5] * 6
DIRECTIONS = [np.array(d, dtype=float) for d in (
    (1, 0, 0, 0, 0, 0), (0, 1, 0, 0, 0, 0), (0, 0, 1, 0, 0, 0), (0, 0, 0, 1, 0, 0), (0, 0, 0, 0, 1, 0),
    (0, 0, 0, 0, 0, 1), (1, 1, 0, 0, 0, 0.2), (1, -0.5, 0.8, 0.1, -0.1, 0.3), (-0.3, 0.7, -1, 0.2, 0.2, -0.4))]


@pytest.mark.parametrize("magnitude", [5.0, 30.0, 80.0, 300.0])
def test_the_optimum_is_scipy_highs_on_the_same_criterion_over_directions_and_magnitudes(magnitude):
    vehicle = vehicle_from(EIGHT, weights__slack=Q, **{f"actuators__t{i}__weight": 1.0 + 0.1 * i for i in range(1, 9)})
    t, w, low, high = matrices(vehicle)
    for direction in DIRECTIONS:
        tau = magnitude * direction / np.linalg.norm(direction)
        result = Allocator(vehicle, method="lp").allocate(tau)
        expected, cost = weighted_l1_allocation(t, w, np.array(Q), low, high, tau)
        ours = float(w @ np.abs(result.thrust) + np.array(Q) @ np.abs(t @ result.thrust - tau))
        assert ours == pytest.approx(cost, rel=1e-7, abs=1e-7)
        assert result.achieved == pytest.approx(t @ expected, abs=1e-6 * max(magnitude, 1.0))
        assert np.all(result.thrust >= low - 1e-9) and np.all(result.thrust <= high + 1e-9)


def test_an_attainable_request_is_met_exactly_with_the_default_slack_weight():
    vehicle = vehicle_from(EIGHT)
    t, _, low, high = matrices(vehicle)
    met = 0
    for direction in DIRECTIONS:
        tau = 20.0 * direction / np.linalg.norm(direction)
        if largest_attainable_scale(t, low, high, tau) < 1.0:
            continue
        result = Allocator(vehicle, method="lp").allocate(tau)
        assert not result.saturated
        assert result.achieved == pytest.approx(tau, abs=1e-9)
        met += 1
    assert met >= 7


def single_azimuth(sides):
    return vehicle_from(DATA / "four_azimuths.yaml", azimuth_polygon_sides=sides)


def test_the_worst_case_magnitude_error_of_the_survey_polygon_is_measured():
    """One free azimuth asked for far more than it can give, in 2880 directions: the force the
    LP plans (before the allocator clips it to the circle) is the polygon's extent, between
    1 - tan^2(pi/2N) and 1 + tan^2(pi/2N) of the thrust limit: +-3.96 % for the octagon."""
    for sides, expected in ((8, 0.0396), (16, 0.0097)):
        model = Model.build(vehicle_from(DATA / "four_azimuths.yaml", azimuth_polygon_sides=sides,
                                         dofs=["surge", "sway"]), 0.1)
        method = LPAllocation(model, BACKENDS["osqp"])
        limit = model.thrust_max[0]
        free = AzimuthLimits(-math.inf, math.inf, 1, 0.0, limit, physical_max=limit)
        dead = AzimuthLimits(0.0, 0.0, 1, 0.0, 0.0, physical_max=0.0)
        errors = []
        for angle in np.linspace(0.0, 2.0 * math.pi, 2880, endpoint=False):
            limits = SampleLimits(np.zeros(model.r), np.array([limit] + [0.0] * (model.r - 1)), model.rot,
                                  [free] + [dead] * (model.r - 1), np.zeros(model.r), np.zeros(model.r))
            output = method.solve(10.0 * limit * np.array([math.cos(angle), math.sin(angle)]), limits)
            errors.append(math.hypot(*output.force[:2]) / limit - 1.0)
        low, high = polygon_error(sides, survey_apothem(sides))
        assert (min(errors), max(errors)) == pytest.approx((low, high), abs=1e-6)
        assert -low == pytest.approx(high) == pytest.approx(math.tan(math.pi / (2 * sides)) ** 2)
        assert high == pytest.approx(expected, abs=5e-5)


def test_each_sample_starts_from_the_last_basis_and_faults_need_no_new_set_up():
    vehicle = vehicle_from(EIGHT)
    allocator = Allocator(vehicle, method="lp")
    tau = [10.0, 5.0, -8.0, 0.5, 0.2, -1.0]
    first = allocator.allocate(tau)
    again = allocator.allocate(tau)
    assert first.iterations > 0 and again.iterations == 0
    setups = allocator.stats.solver_setups
    allocator.set_fault("t2", FaultMode.FAILED)
    result = allocator.allocate(tau)
    assert result.thrust[1] == 0.0 and result.achieved == pytest.approx(tau, abs=1e-9)
    allocator.reconfigure(vehicle_from(EIGHT, actuators__t1__thrust_max=20.0))
    allocator.allocate(tau)
    assert allocator.stats.solver_setups == setups == 1


def test_sectors_and_rate_limits_hold_on_the_dp_vessel():
    vehicle = vehicle_from(ROOT / "config" / "dp_vessel.yaml", method="lp")
    allocator = Allocator(vehicle)
    model = Model.build(vehicle, allocator.dt)
    previous = allocator.stop()
    for k in range(300):
        angle = 2.0 * math.pi * k / 300
        result = allocator.allocate([3e5 * math.cos(angle), 3e5 * math.sin(angle), 0, 0, 0, 1e6 * math.sin(angle)])
        assert np.all(np.abs(result.thrust - previous.thrust) <= model.thrust_step + 1e-6)
        assert np.all(np.abs(np.angle(np.exp(1j * (result.azimuth - previous.azimuth)))) <= model.angle_step + 1e-9)
        previous = result
    assert allocator.stats.fallbacks == 0


@pytest.mark.parametrize("stem", ["bluerov2_heavy", "dp_vessel", "example1_rov", "infante_auv"])
def test_solutions_are_sparser_than_the_qps_on_the_shipped_vehicles(stem):
    vehicle = sparsity.without_rates(ROOT / "config" / f"{stem}.yaml")
    sequence = sparsity.requests(vehicle, 12)
    lp, qp = sparsity.working(vehicle, "lp", sequence), sparsity.working(vehicle, "qp", sequence)
    assert np.all(lp <= qp) and np.mean(lp) < np.mean(qp)
    assert np.all(lp >= 1)


def test_a_tied_optimum_is_the_same_after_any_history():
    """BlueROV2 Heavy with thruster_1 failed: the four vertical thrusters' effort is flat along
    a null direction of T, so without the tie-break the answer depends on the starting basis."""
    vehicle = vehicle_from(ROOT / "config" / "bluerov2_heavy.yaml")
    rng = np.random.default_rng(0)
    request = np.array([3.0, -2.0, -1.5, 0.1, 0.05, 0.2])
    answers = []
    for history in range(8):
        alloc = Allocator(vehicle, method="lp")
        alloc.set_fault("thruster_1", FaultMode.FAILED)
        for _ in range(history):
            alloc.allocate(rng.normal(size=6) * [20, 20, 20, 2, 2, 2])
            alloc.stop()
        answers.append(alloc.allocate(request).thrust)
    assert np.ptp(np.array(answers), axis=0) == pytest.approx(np.zeros(8), abs=1e-9)
    vertical = answers[0][4:]
    assert np.count_nonzero(np.abs(vertical) > 1e-9) == 3            # still a vertex: one of the four idle


def test_the_tie_break_weighs_each_actuator_by_its_squared_index():
    weights = tie_break(4)
    assert weights == pytest.approx(1.0 + ORDER_SHARE * np.array([1, 4, 9, 16]) / 16, rel=0, abs=1e-15)
    assert weights[0] - 1.0 + weights[3] - 1.0 != pytest.approx(weights[1] - 1.0 + weights[2] - 1.0, rel=1e-3)
