"""Every method on generated vehicles (test/generators.py), judged against an independent
reference, never itself; every sample also within every thrust, rate, sector and fault limit.

- ``qp``, ``explicit``, ``dynamic`` (fixed directions): the settled answer to a held request
  against the bounded least-squares optimum of (1.35) with beta = 0 (scipy's BVLS), relative
  objective within RELATIVE (``qp``: QP_RELATIVE);
- ``qp`` and ``nonlinear`` on azimuth vessels: the settled wrench against a multi-start SLSQP
  over the convex sector pieces (reference.best_attainable_wrench), within WRENCH of each DOF's
  authority;
- ``lp``: its own criterion (5.3) by scipy's linprog (HiGHS), cost within LP_RELATIVE;
- ``pseudoinverse``: its closed form (the weighted pseudo-inverse of T) where no limit binds.

The CI profile is a fixed, derandomised set (:func:`profile`); tools/explore.py runs the same judges on
fresh vehicles by the thousand (``make explore``).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from generators import azimuth_vessels, faults, fixed_vehicles, request_sequences
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from reference import best_attainable_wrench, weighted_l1_allocation, weighted_pseudo_inverse
from scipy.optimize import lsq_linear
from test_properties import check

from allocator_pkg import Allocator
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix

RELATIVE = 1e-6
"""The objective of (1.35) within this fraction of the BVLS optimum's (explicit, dynamic)."""

QP_RELATIVE = 1e-3
"""The qp method's objective within this fraction of the optimum's: OSQP stops when its
residuals are below solver.eps_abs = 1e-5 of each scaled variable's range, and the objective's
slack term, 1e6 times the effort per unit of authority (DEFAULT_SLACK_RATIO), turns a residual
of eps_abs into up to about 1e2 eps_abs of the objective; measured worst on the CI set 2e-5."""

WRENCH = 2e-3
"""The settled wrench within this fraction of each DOF's authority of the SLSQP reference's."""

LP_RELATIVE = 1e-7
"""The lp method's cost within this fraction of linprog's (both HiGHS, to its tolerances)."""

SETTLE = {"qp": 8, "explicit": 8, "lp": 8, "pseudoinverse": 8, "dynamic": 200, "nonlinear": 40, "svd_filter": 150}
"""Samples a held request is given before its answer is judged, beyond those the rate limits need."""

HEALTH = [HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large]


def profile(examples: int) -> settings:
    """The CI profile: a fixed set of ``examples`` draws, the same on every run."""
    return settings(derandomize=True, max_examples=examples, deadline=None, database=None,
                    suppress_health_check=HEALTH)

DYNAMIC_STALL = "dynamic stops short of the optimum with several bounds active (a fix is under way elsewhere)"


def objective(t, w, q, f, tau):
    """(1.35) with beta = 0, the slack eliminated: f'Wf + (Tf - tau)'Q(Tf - tau)."""
    s = t @ f - tau
    return float(f @ (w * f) + s @ (q * s))


def bvls(t, w, q, low, high, tau):
    """The bounded least-squares optimum of (1.35), beta = 0, by scipy's BVLS on
    [W^1/2; Q^1/2 T] f ~ [0; Q^1/2 tau]; forces whose bounds meet are fixed there."""
    fixed = high - low <= 0.0
    f = np.where(fixed, low, 0.0)
    free = ~fixed
    if not free.any():
        return f
    design = np.vstack((np.diag(np.sqrt(w[free])), np.sqrt(q)[:, None] * t[:, free]))
    target = np.concatenate((np.zeros(free.sum()), np.sqrt(q) * (tau - t @ f)))
    f[free] = lsq_linear(design, target, bounds=(low[free], high[free]), method="bvls", tol=1e-15).x
    return f


def allocator_with(vehicle, method, fault_set, speed=0.0):
    allocator = Allocator(vehicle, method=method)
    allocator.set_speed(speed)
    for name, (mode, efficiency, angle) in fault_set.items():
        allocator.set_fault(name, mode, efficiency=efficiency, angle=angle)
    return allocator


def settle_samples(allocator, method):
    """Samples enough for every rate limit to reach any force or angle, plus SETTLE[method]."""
    model = allocator.model
    low, high = allocator.ranges
    span = np.where(np.isfinite(model.thrust_step) & (model.thrust_step > 0),
                    (high - low) / np.where(model.thrust_step > 0, model.thrust_step, 1.0), 0.0)
    turns = [2.0 * math.pi / step for step in model.angle_step[model.rot] if np.isfinite(step) and step > 0]
    return math.ceil(max([0.0, *span.tolist(), *turns])) + SETTLE[method]


def follow(allocator, vehicle, fault_set, sequence):
    """Every request of ``sequence`` in turn, each sample judged within every limit."""
    previous = allocator.stop()
    results = []
    for tau in sequence:
        result = allocator.allocate(tau)
        check(vehicle, allocator, fault_set, previous, result, np.asarray(tau))
        previous = result
        results.append(result)
    return results


def problem(allocator):
    """T of a fixed-direction vehicle (controlled rows), W, Q and the static ranges in force."""
    vehicle, model = allocator.vehicle, allocator.model
    t = configuration_matrix(vehicle.actuators, np.zeros(len(vehicle.actuators)))[list(vehicle.dof_indices)]
    w = np.array([a.weight for a in vehicle.actuators])
    low, high = allocator.ranges
    return t, w, model.slack_weights(w), low.copy(), high.copy()


def judge_bounded_least_squares(vehicle, method, fault_set, tau, speed=0.0):
    """The settled answer to a held ``tau`` against BVLS; returns (ours, optimum) objectives."""
    allocator = allocator_with(vehicle, method, fault_set, speed)
    samples = settle_samples(allocator, method)
    result = follow(allocator, vehicle, fault_set, np.tile(tau, (samples, 1)))[-1]
    t, w, q, low, high = problem(allocator)
    rows = list(vehicle.dof_indices)
    optimum = objective(t, w, q, bvls(t, w, q, low, high, tau[rows]), tau[rows])
    return objective(t, w, q, result.thrust, tau[rows]), optimum


def judge_lp(vehicle, fault_set, tau):
    """lp's settled answer to a held ``tau`` on its own criterion against linprog: (ours, best)."""
    allocator = allocator_with(vehicle, "lp", fault_set)
    t, w, _, low, high = problem(allocator)
    q = np.array(vehicle.weights.slack)
    result = follow(allocator, vehicle, fault_set, np.tile(tau, (settle_samples(allocator, "lp"), 1)))[-1]
    rows = list(vehicle.dof_indices)
    _, best = weighted_l1_allocation(t, w, q, low, high, tau[rows])
    ours = float(w @ np.abs(result.thrust) + q @ np.abs(t @ result.thrust - tau[rows]))
    return ours, best


def with_lp_slack(vehicle):
    """The vehicle with weights.slack set: 1e3 times all actuators' weighted full force per
    unit of each DOF's authority (an exact penalty of (5.3), so the reference needs no default)."""
    model = Allocator(vehicle).model
    effort = float(np.sum(model.weight * model.force_scale))
    return replace(vehicle, method="lp",
                   weights=replace(vehicle.weights, slack=tuple(1e3 * effort / model.dof_scale)))


def judge_azimuths(vehicle, method, fault_set, tau):
    """The settled wrench against SLSQP over the sector pieces: the largest error per DOF, as a
    fraction of the DOF's authority, of ours past the reference's weighted error."""
    allocator = allocator_with(vehicle, method, fault_set)
    result = follow(allocator, vehicle, fault_set, np.tile(tau, (settle_samples(allocator, method), 1)))[-1]
    model = allocator.model
    rows = list(vehicle.dof_indices)
    low, high = allocator.ranges
    q = model.slack_weights(model.weight)
    best = best_attainable_wrench(vehicle, tau, q, low, high, starts=3)
    authority = model.dof_scale
    ours = (result.achieved[rows] - tau[rows]) / authority
    reference = (best - tau[rows]) / authority
    weights = q * authority ** 2 / np.max(q * authority ** 2)
    if math.sqrt(weights @ (ours * ours)) <= math.sqrt(weights @ (reference * reference)) + WRENCH:
        return 0.0
    return float(np.max(np.abs(ours - reference)))


def pieces(vehicle):
    """How many combinations of convex sector pieces the SLSQP reference tries."""
    count = 1
    for a in vehicle.actuators:
        if a.rotatable and a.rotation.forbidden_sectors:
            count *= 4
    return count


# -- the cases: one draw of a vehicle, faults and requests, judged -----------------------------------

def bounded_least_squares_case(data, method):
    """qp, explicit, dynamic on fixed thrusters: the settled answer is the BVLS optimum."""
    vehicle, _ = data.draw(fixed_vehicles(method))
    fault_set = data.draw(faults(vehicle, stuck=False, at_most=2))
    _, sequence = data.draw(request_sequences(vehicle, 1, kinds=("held", "past capability")))
    ours, optimum = judge_bounded_least_squares(vehicle, method, fault_set, sequence[0])
    tolerance = QP_RELATIVE if method == "qp" else RELATIVE
    assert ours <= optimum * (1.0 + tolerance) + 1e-12 * max(optimum, 1.0)


def lp_case(data, method="lp"):
    """lp on fixed thrusters: linprog's optimum of its own criterion."""
    vehicle, _ = data.draw(fixed_vehicles(method))
    vehicle = with_lp_slack(vehicle)
    fault_set = data.draw(faults(vehicle, stuck=False, at_most=2))
    _, sequence = data.draw(request_sequences(vehicle, 1, kinds=("held", "past capability")))
    ours, best = judge_lp(vehicle, fault_set, sequence[0])
    assert ours == pytest.approx(best, rel=LP_RELATIVE, abs=1e-9 * max(best, 1.0))


def pseudoinverse_case(data, method="pseudoinverse"):
    """A request the unconstrained (1.29) answer meets within half of every range: the answer."""
    vehicle, _ = data.draw(fixed_vehicles(method))
    allocator = Allocator(vehicle)
    t, w, _, low, high = problem(allocator)
    if np.linalg.matrix_rank(t) < t.shape[0]:
        return                                   # (1.29) needs T of full row rank
    gain = weighted_pseudo_inverse(t, w)
    _, sequence = data.draw(request_sequences(vehicle, 1, kinds=("held",)))
    rows = list(vehicle.dof_indices)
    f = gain @ sequence[0][rows]
    tau = sequence[0] / max(float(np.max(np.maximum(f / (0.5 * high), f / (0.5 * low)))), 1.0)
    result = follow(allocator, vehicle, {}, np.tile(tau, (settle_samples(allocator, method), 1)))[-1]
    assert result.thrust == pytest.approx(gain @ tau[rows], rel=1e-9, abs=1e-9 * float(np.max(high)))


def azimuth_case(data, method, units=(2, 4), rates=False):
    """qp, nonlinear on azimuth vessels: the settled wrench is SLSQP's over the sector pieces."""
    vehicle, _ = data.draw(azimuth_vessels(method, rates=rates, units=units))
    if pieces(vehicle) > 64:
        return                                   # too many combinations for the reference
    fault_set = data.draw(faults(vehicle, stuck=False, at_most=1))
    _, sequence = data.draw(request_sequences(vehicle, 1, kinds=("held", "past capability")))
    assert judge_azimuths(vehicle, method, fault_set, sequence[0]) <= WRENCH


def limits_case(data, method, samples=30):
    """Any method on an azimuth vessel with sectors, rate limits, tunnels and any faults, over a
    held, stepped, smooth or past-capability sequence: every sample within every limit."""
    vehicle, _ = data.draw(azimuth_vessels(method, units=(2, 5)))
    fault_set = data.draw(faults(vehicle))
    _, sequence = data.draw(request_sequences(vehicle, samples))
    follow(allocator_with(vehicle, method, fault_set), vehicle, fault_set, sequence)


def fixed_limits_case(data, method, samples=30):
    """Any method of fixed directions on a fixed-thruster vehicle with faults, over a sequence."""
    vehicle, _ = data.draw(fixed_vehicles(method))
    fault_set = data.draw(faults(vehicle))
    _, sequence = data.draw(request_sequences(vehicle, samples))
    follow(allocator_with(vehicle, method, fault_set), vehicle, fault_set, sequence)


CASES = {
    "bounded_least_squares": (bounded_least_squares_case, ("qp", "explicit", "dynamic")),
    "lp": (lp_case, ("lp",)),
    "pseudoinverse": (pseudoinverse_case, ("pseudoinverse",)),
    "azimuths": (azimuth_case, ("qp", "nonlinear")),
    "limits": (limits_case, ("qp", "lp", "dynamic", "nonlinear", "pseudoinverse", "svd_filter")),
    "fixed_limits": (fixed_limits_case, ("qp", "explicit", "lp", "dynamic", "pseudoinverse")),
}
"""Every case and the methods it judges (tools/explore.py runs them all)."""


# -- the CI profile -----------------------------------------------------------------------------

@pytest.mark.parametrize("method", ["qp", "explicit",
                                    pytest.param("dynamic", marks=pytest.mark.xfail(reason=DYNAMIC_STALL,
                                                                                   strict=False))])
@profile(10)
@given(data=st.data())
def test_the_settled_answer_on_fixed_thrusters_is_the_bounded_least_squares_optimum(method, data):
    bounded_least_squares_case(data, method)


@profile(10)
@given(data=st.data())
def test_lp_is_linprog_on_its_own_criterion(data):
    lp_case(data)


@profile(10)
@given(data=st.data())
def test_pseudoinverse_is_the_weighted_pseudo_inverse_where_no_limit_binds(data):
    pseudoinverse_case(data)


@pytest.mark.parametrize("method", ["qp", "nonlinear"])
@profile(5)
@given(data=st.data())
def test_azimuth_vessels_settle_on_the_best_attainable_wrench(method, data):
    azimuth_case(data, method)


@pytest.mark.parametrize("method", CASES["limits"][1])
@profile(3)
@given(data=st.data())
def test_every_sample_on_azimuth_vessels_is_within_every_limit(method, data):
    limits_case(data, method)


@pytest.mark.parametrize("method", CASES["fixed_limits"][1])
@profile(3)
@given(data=st.data())
def test_every_sample_on_fixed_thrusters_is_within_every_limit(method, data):
    fixed_limits_case(data, method)


def test_the_objective_and_bvls_on_a_problem_by_hand():
    """T = I (two DOFs), W = 1, Q = 1, tau = (4, 0), bounds [-1, 1]: the optimum is f = (1, 0)
    with objective 1 + 9 = 10."""
    t, w, q = np.eye(2), np.ones(2), np.ones(2)
    f = bvls(t, w, q, -np.ones(2), np.ones(2), np.array([4.0, 0.0]))
    assert f == pytest.approx([1.0, 0.0]) and objective(t, w, q, f, np.array([4.0, 0.0])) == pytest.approx(10.0)
