"""The hull models of allocator_pkg.simulation.vessel and .rov against hand calculations:
steady speeds where thrust equals damping, restoring moments of a tilt, mass matrices."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

from allocator_pkg.hull.environment_loads import VesselParticulars, current_load
from allocator_pkg.simulation.kinematics import euler, quaternion, rotation
from allocator_pkg.simulation.rov import Rov, RovParameters
from allocator_pkg.simulation.vessel import Vessel


def settle(model, tau, seconds, dt, current=None):
    """Integrate a hull from rest under a constant force (explicit RK4)."""
    n = model.dofs
    state = np.zeros(2 * n)
    current = np.zeros(3 if n == 6 else 2) if current is None else current

    def f(x):
        return np.concatenate(model.derivative(x[:n], x[n:], tau, current))

    for _ in range(int(seconds / dt)):
        k1 = f(state)
        k2 = f(state + dt / 2 * k1)
        k3 = f(state + dt / 2 * k2)
        k4 = f(state + dt * k3)
        state = state + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return state[:n], state[n:]


def test_rov_surge_speed_settles_where_thrust_equals_linear_plus_quadratic_drag():
    neutral = RovParameters(volume=13.5 / 1000.0)               # W = B: nothing sinks or tilts
    _, nu = settle(Rov(neutral), np.array([20.0, 0, 0, 0, 0, 0]), 20.0, 0.01)
    expected = (-13.7 + math.sqrt(13.7 ** 2 + 4 * 141.0 * 20.0)) / (2 * 141.0)    # 13.7 u + 141 u^2 = 20
    assert nu[0] == pytest.approx(expected, rel=1e-4)
    assert np.allclose(nu[1:], 0.0, atol=1e-9)


def test_rov_in_a_current_drifts_with_the_water():
    neutral = RovParameters(volume=13.5 / 1000.0)
    _, nu = settle(Rov(neutral), np.zeros(6), 200.0, 0.05, current=np.array([0.0, 0.2, 0.0]))
    # no force: the vehicle moves with the current (quadratic drag only: 1/t approach)
    assert nu[1] == pytest.approx(0.2, rel=5e-3)


def test_rov_restoring_moment_of_a_roll_and_a_pitch():
    rov = Rov()
    buoyancy = 1000.0 * 9.82 * 0.0134                           # 131.588 N, its centre 0.01 m above the CG
    weight = 13.5 * 9.82
    g = rov.restoring(np.array([0, 0, 0, 0.1, 0, 0]))
    assert g[3] == pytest.approx(0.01 * buoyancy * math.sin(0.1), rel=1e-12)     # the moment -g4 rights it
    g = rov.restoring(np.array([0, 0, 0, 0, -0.2, 0]))
    assert g[4] == pytest.approx(0.01 * buoyancy * math.sin(-0.2), rel=1e-12)
    assert g[0] == pytest.approx((weight - buoyancy) * math.sin(-0.2), rel=1e-12)
    level = rov.restoring(np.zeros(6))
    assert level[2] == pytest.approx(-(weight - buoyancy)) and np.allclose(level[[0, 1, 3, 4, 5]], 0.0)
    _, nu_dot = rov.derivative(np.array([0, 0, 0, 0.1, 0, 0]), np.zeros(6), np.zeros(6), np.zeros(3))
    assert nu_dot[3] == pytest.approx(-0.01 * buoyancy * math.sin(0.1) / (0.26 + 0.189), rel=1e-9)


def test_vessel_mass_matrix_from_the_osv_particulars():
    vessel = Vessel()
    m = 1025.0 * 0.65 * 83.0 * 18.0 * 5.0
    assert vessel.mass[0, 0] == pytest.approx(m + 1e6)
    assert vessel.mass[1, 2] == pytest.approx(-4.5 * m - 6e6)
    assert vessel.mass[2, 2] == pytest.approx(m * (0.25 * 83.0) ** 2 + m * 4.5 ** 2 + 1.156e9)
    assert np.allclose(vessel.mass, vessel.mass.T)


def test_vessel_sway_speed_settles_where_thrust_equals_linear_plus_crossflow_drag():
    vessel = Vessel()
    force = 200e3
    d22 = vessel.mass[1, 1] / 100.0
    quadratic = 0.5 * 1025.0 * 5.0 * 0.7 * 83.0                 # 1/2 rho T Cd L over the whole length
    expected = (-d22 + math.sqrt(d22 ** 2 + 4 * quadratic * force)) / (2 * quadratic)
    _, nu = settle(vessel, np.array([0.0, force, 0.0]), 900.0, 0.1)
    assert nu[1] == pytest.approx(expected, rel=2e-3)


def test_vessel_surge_speed_balances_the_blended_surge_damping():
    vessel = Vessel()
    force = 100e3
    expected = brentq(lambda u: vessel.surge_damping(u) + force, 0.0, 5.0)
    _, nu = settle(vessel, np.array([force, 0.0, 0.0]), 1200.0, 0.2)
    assert nu[0] == pytest.approx(expected, rel=2e-3)
    # at 4 m/s the blend is mostly quadratic: close to 1/2 rho 0.6 B T u^2
    assert -vessel.surge_damping(4.0) == pytest.approx(
        (1 - math.tanh(2)) * vessel.mass[0, 0] / 100 * 4 + math.tanh(2) * 0.5 * 1025 * 0.6 * 18 * 5 * 16)


def test_a_beam_current_loads_the_vessel_at_rest_as_the_capability_analysis_does():
    vessel = Vessel()
    particulars = VesselParticulars(lpp=83.0, beam=18.0, draught=5.0, wind_area_frontal=1.0, wind_area_lateral=1.0,
                                    wind_centre_x=0.0, underwater_centre_x=0.0)
    crossflow = vessel.crossflow(1.0, 0.0)      # water from starboard at 1 m/s: the hull moves through it to starboard
    load = current_load(particulars, 1.0, math.pi / 2)
    assert crossflow[1] == pytest.approx(load[1] * 1025.0 / 1026.0, rel=1e-12)
    assert crossflow[2] == pytest.approx(0.0, abs=1e-6)


def strip_sum(vessel, v_r, r):
    """(Y, N) of the cross-flow drag summed strip by strip: -1/2 rho T Cd |w| w dx at every strip
    centre x, w = v_r + x r (osv.m's loop)."""
    p = vessel.parameters
    dx = p.length / 20
    x = -p.length / 2 + (np.arange(20) + 0.5) * dx
    w = v_r + x * r
    drag = -0.5 * p.water_density * p.draught * p.coefficients.current_sway * dx * np.abs(w) * w
    return math.fsum(drag), math.fsum(drag * x)


@settings(max_examples=400, deadline=None)
@given(st.floats(-4.0, 4.0), st.one_of(st.just(0.0), st.floats(-0.2, 0.2)), st.integers(-1, 20))
def test_the_crossflow_in_closed_form_is_the_strip_sum(v_r, r, at):
    """The closed form against the strips one by one (``scale`` bounds |Y|, times L/2 |N|), with the
    flow turning at a strip's centre too (``at``: v_r set so that w = 0 there, to rounding)."""
    vessel = Vessel()
    p = vessel.parameters
    if 0 <= at < 20 and r != 0.0:
        v_r = -r * (-p.length / 2 + (at + 0.5) * (p.length / 20))     # w = 0 exactly at that centre
    half = p.length / 2
    scale = 0.5 * p.water_density * p.draught * p.coefficients.current_sway * p.length * (abs(v_r) + half * abs(r)) ** 2
    y, n = vessel.crossflow(v_r, r)[1:]
    expected = strip_sum(vessel, v_r, r)
    floor = 1e-300                                  # scale underflows for the tiniest flows
    assert y == pytest.approx(expected[0], abs=1e-12 * scale + floor)
    assert n == pytest.approx(expected[1], abs=1e-12 * scale * half + floor)


def test_quaternion_round_trip_and_rotation_is_orthonormal():
    angles = (0.1, -0.3, 2.5)
    assert euler(*quaternion(*angles)) == pytest.approx(angles)
    r = rotation(*angles)
    assert np.allclose(r @ r.T, np.eye(3)) and np.linalg.det(r) == pytest.approx(1.0)
    assert rotation(0, 0, math.pi / 2) @ np.array([1.0, 0, 0]) == pytest.approx([0, 1.0, 0])



def test_a_beam_current_loads_the_hull_at_rest_with_the_analysis_drag_plus_the_linear_damping():
    vessel = Vessel()
    particulars = VesselParticulars(lpp=83.0, beam=18.0, draught=5.0, wind_area_frontal=1.0, wind_area_lateral=1.0,
                                    wind_centre_x=0.0, underwater_centre_x=0.0)
    _, nu_dot = vessel.derivative(np.zeros(3), np.zeros(3), np.zeros(3), np.array([0.0, 0.75]))
    felt = vessel.mass @ nu_dot
    balance = current_load(particulars, 0.75, math.pi / 2)[1] * 1025.0 / 1026.0
    linear = (4.977e6 + 3e6) / 100.0 * 0.75           # (m + MA22) / T2 times the current, by hand
    assert felt[1] == pytest.approx(-balance + linear, rel=1e-3)
    assert (felt[1], -balance) == pytest.approx((143.6e3, 83.8e3), abs=0.1e3)


def test_the_vessel_derivative_is_fossens_planar_model():
    """(eta', nu') against the model written out plainly: eta' = R(psi) nu; M (nu - nu_c)' =
    tau - C(nu_r) nu_r - D nu_r + surge and cross-flow damping, nu_c' = -S(r) nu_c."""
    vessel = Vessel()
    rng = np.random.default_rng(11)
    for _ in range(50):
        eta, nu = rng.normal(size=3), rng.normal(size=3) * [2.0, 1.0, 0.05]
        tau, current = rng.normal(size=3) * [1e5, 1e5, 1e7], rng.normal(size=2) * 0.5
        c, s = math.cos(eta[2]), math.sin(eta[2])
        nu_c = np.array([c * current[0] + s * current[1], -s * current[0] + c * current[1], 0.0])
        nu_r = nu - nu_c
        m = vessel.mass
        coriolis = np.array([[0.0, 0.0, -m[1] @ nu_r], [0.0, 0.0, m[0] @ nu_r], [m[1] @ nu_r, -m[0] @ nu_r, 0.0]])
        damping = -vessel.linear_damping @ nu_r
        damping[0] = vessel.surge_damping(nu_r[0])
        p = vessel.parameters
        dx = p.length / 20
        x = -p.length / 2 + (np.arange(20) + 0.5) * dx                     # the 20 strips
        local = nu_r[1] + x * nu_r[2]
        drag = -0.5 * p.water_density * p.draught * p.coefficients.current_sway * dx * np.abs(local) * local
        damping += [0.0, drag.sum(), (drag * x).sum()]
        force = tau - coriolis @ nu_r + damping
        nu_dot = np.array([nu[2] * nu_c[1], -nu[2] * nu_c[0], 0.0]) + np.linalg.solve(m, force)
        eta_dot, got = vessel.derivative(eta, nu, tau, current)
        assert eta_dot == pytest.approx([c * nu[0] - s * nu[1], s * nu[0] + c * nu[1], nu[2]], rel=1e-12)
        assert got == pytest.approx(nu_dot, rel=1e-9, abs=1e-12)
