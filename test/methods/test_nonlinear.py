"""The nonlinear method (1.44)/(1.45) against an independent optimum, and its singularity term."""

import numpy as np
import pytest
from conftest import DATA, vehicle_from
from scipy.optimize import minimize

from allocator_pkg import Allocator, FaultMode
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix

FOUR = DATA / "four_azimuths.yaml"
IDLE = DATA / "nonlinear_idle_azimuth.yaml"


def authority(vehicle):
    """Surge, sway and yaw authority of azimuths able to point anywhere: sum f_max in X and Y,
    sum f_max |l| in N, with |l| each thruster's distance from the origin in the plane."""
    f_max = np.array([a.thrust_max for a in vehicle.actuators])
    lever = np.array([np.hypot(*a.position[:2]) for a in vehicle.actuators])
    return np.array([f_max.sum(), f_max.sum(), f_max @ lever])


def slsqp_optimum(vehicle, tau, starts=20):
    """min sum_i |f_i|^(3/2) s.t. T(alpha) f = tau, 0 <= f <= f_max, from several starts."""
    actuators = vehicle.actuators
    rows = list(vehicle.dof_indices)
    f_max = np.array([a.thrust_max for a in actuators])
    rng = np.random.default_rng(1)

    def residual(x):
        return (configuration_matrix(actuators, x[4:])[rows] @ x[:4] - tau[rows]) / 1e5

    best = None
    for _ in range(starts):
        x0 = np.concatenate((rng.uniform(0.1, 0.5, 4) * f_max, rng.uniform(-np.pi, np.pi, 4)))
        result = minimize(lambda x: np.sum(np.abs(x[:4]) ** 1.5), x0, method="SLSQP",
                          constraints=[{"type": "eq", "fun": residual}],
                          bounds=[(0.0, f) for f in f_max] + [(None, None)] * 4,
                          options={"maxiter": 500, "ftol": 1e-12})
        if result.success and (best is None or result.fun < best.fun):
            best = result
    return best.fun


@pytest.mark.parametrize("tau", [[2e5, 1e5, 0, 0, 0, 3e6], [-1e5, 2.5e5, 0, 0, 0, -4e6], [3e5, 0, 0, 0, 0, 1e6]])
def test_power_is_within_a_few_percent_of_an_independent_optimum(tau):
    vehicle = vehicle_from(FOUR)
    alloc = Allocator(vehicle, method="nonlinear")
    tau = np.array(tau, dtype=float)
    for _ in range(400):
        result = alloc.allocate(tau)
    assert not result.saturated
    assert np.all(np.abs(result.achieved[[0, 1, 5]] - tau[[0, 1, 5]]) <= 1e-4 * authority(vehicle))
    optimum = slsqp_optimum(vehicle, tau)
    assert result.power <= 1.03 * optimum
    assert alloc.stats.solver_setups == 1


def test_nonlinear_uses_less_power_than_the_quadratic_effort_of_qp():
    vehicle = vehicle_from(FOUR)
    tau = [2e5, 1e5, 0, 0, 0, 3e6]
    nonlinear, qp = Allocator(vehicle, method="nonlinear"), Allocator(vehicle, method="qp")
    for _ in range(400):
        a, b = nonlinear.allocate(tau), qp.allocate(tau)
    assert a.power < b.power


def determinants(rho):
    vehicle = vehicle_from(FOUR, singularity__rho=rho)
    alloc = Allocator(vehicle, method="nonlinear")
    values = []
    for k in range(600):
        # Spread the azimuths with a sway and yaw request, then ask for pure surge: the
        # least-power answer lines all four up, where T T' is singular.
        alloc.allocate([1e5, 2e5, 0, 0, 0, 2e6] if k < 150 else [3e5, 0, 0, 0, 0, 0])
        t = alloc.configuration_matrix()[[0, 1, 5]]
        values.append(np.linalg.det(t @ t.T))
    return np.array(values[150:])


def test_singularity_avoidance_keeps_the_configuration_away_from_det_zero():
    plain, avoiding = determinants(0.0), determinants(1e6)
    assert plain.min() < 1e-6
    assert avoiding.min() > 1.0
    assert np.all(avoiding[-100:] > plain[-100:])


def test_more_linearised_qps_per_sample_leave_less_linearisation_error():
    """One linearised QP (1.45) meets T(alpha0) + dT/dalpha dalpha, not T(alpha0 + dalpha): a
    sample that turns the thrusters misses by the second-order term. Solving again around the
    new point (nonlinear.max_iterations) shrinks that miss, on the same OSQP problem. Without
    rate limits, from rest, the second sample shows it plainly."""
    free = {f"actuators__{name}__{key}": 0.0 for name in ("bow_port", "bow_stbd", "stern_port", "stern_stbd")
            for key in ("azimuth_rate_max", "thrust_rate_max")}
    tau = np.array([5e4, 8e4, 0.0, 0.0, 0.0, 3e5])
    errors = {}
    for iterations in (1, 5):
        vehicle = vehicle_from(FOUR, nonlinear__max_iterations=iterations, **free)
        alloc = Allocator(vehicle, method="nonlinear")
        errors[iterations] = [np.max(np.abs(alloc.allocate(tau).achieved[[0, 1, 5]] - tau[[0, 1, 5]])
                                     / authority(vehicle)) for _ in range(2)]
        assert alloc.stats.solver_setups == 1
    assert errors[5][0] < errors[1][0]
    assert errors[5][1] < 1e-2 * errors[1][1]


def test_the_linearised_qps_are_solved_to_a_tenth_of_the_configured_tolerance():
    """The iteration runs on the QPs' answers across samples; within 1e-5 they moved the angles
    along flat valleys of (1.44) (test_settling's off-grid cases). Kept through a change of the
    configured tolerance, which reaches the running solver as values."""
    vehicle = vehicle_from(FOUR)
    alloc = Allocator(vehicle, method="nonlinear")
    settings = alloc._solver.method._qp.backend.settings
    assert (settings.eps_abs, settings.eps_rel) == pytest.approx((1e-6, 1e-6))
    alloc.reconfigure(vehicle_from(FOUR, solver__eps_abs=1e-4, solver__eps_rel=2e-4))
    settings = alloc._solver.method._qp.backend.settings
    assert (settings.eps_abs, settings.eps_rel) == pytest.approx((1e-5, 2e-5))
    assert alloc.stats.solver_setups == 1


def settled_idle_case(sectors, mode, angle):
    """Thrusts, angles and wrench after 600 samples of 320 kN sway on the idle-azimuth vessel
    (az1 10 m forward, idle along x at the start), az0 with ``sectors`` and the fault."""
    vehicle = vehicle_from(IDLE, actuators__az0__forbidden_sectors=sectors)
    alloc = Allocator(vehicle, method="nonlinear")
    alloc.set_fault("az0", mode, efficiency=0.0 if mode == FaultMode.FAILED else 1.0, angle=angle)
    tau = np.array([0.0, 320e3, 0.0, 0.0, 0.0, 0.0])
    for _ in range(600):
        result = alloc.allocate(tau)
    return result


@pytest.mark.parametrize(("mode", "angle"), [(FaultMode.FAILED, 0.0), (FaultMode.STUCK, 0.0), (FaultMode.STUCK, 1.5)])
def test_the_sectors_of_a_failed_or_stuck_thruster_do_not_keep_an_idle_one_from_turning(mode, angle):
    """az0 out of play: failed, stuck clear of its sector (1-2 rad) or stuck inside it (no
    thrust, the same as failed). Its sector changes nothing the others may do, so the idle az1
    turns to give sway (past capability, 120 kN short) as it does on the vessel without that
    sector, where az0 failed."""
    reference = settled_idle_case([], FaultMode.FAILED, 0.0)
    assert reference.thrust[1] > 1e3 and np.sin(reference.azimuth[1]) > 0.99
    result = settled_idle_case([1.0, 2.0], mode, angle)
    assert result.thrust[1:] == pytest.approx(reference.thrust[1:], rel=1e-4)
    assert result.azimuth[1:] == pytest.approx(reference.azimuth[1:], abs=1e-4)
    assert result.achieved[[0, 1, 5]] == pytest.approx(reference.achieved[[0, 1, 5]], rel=1e-4, abs=1.0)
