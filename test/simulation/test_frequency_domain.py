"""allocator_pkg.simulation.frequency_domain: the linearised closed loop's excursion against the
closed form of a mass-spring-damper in white noise, pi S0 / (2 c k) (one-sided S0 per rad/s),
swept over masses, gains and DOFs; the thruster lag and the integral against scipy.signal's
frequency response; the damping's linearisation against the hull's own."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import signal

from allocator_pkg.simulation.controller import Gains
from allocator_pkg.simulation.frequency_domain import (
    LinearLoop,
    current_gradients,
    current_vector,
    linear_damping,
    outer,
    rest_force,
)
from allocator_pkg.simulation.vessel import Vessel

OMEGA = np.geomspace(1e-6, 100.0, 40001)


@settings(max_examples=12, deadline=None)
@given(st.floats(1e6, 1e7), st.floats(1e4, 1e5), st.floats(2e5, 2e6), st.integers(0, 2))
def test_a_pd_loop_in_white_noise_has_the_closed_form_variance(mass, kp, kd, dof):
    gains = [[1.0, 1.0, 1.0], [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]]
    gains[0][dof], gains[1][dof] = kp, kd
    loop = LinearLoop(np.eye(3) * mass, np.eye(3) * 1e4, Gains(*map(tuple, gains)), 0.0)
    direction = np.zeros(3)
    direction[dof] = 1.0
    s0 = 1e8
    std = loop.excursion_std(OMEGA, outer(direction, np.full(OMEGA.size, s0)))
    assert std[dof] == pytest.approx(math.sqrt(math.pi * s0 / (2.0 * (kd + 1e4) * kp)), rel=0.01)


@pytest.mark.parametrize("lag", [0.5, 2.0, 5.0])
def test_the_receptance_is_scipys_transfer_function_with_lag_and_integral(lag):
    """x / F = s (1 + T s) / ((m s^2 + d s)(1 + T s) s + kd s^2 + kp s + ki), per DOF."""
    m, d, kp, kd, ki = 8e6, 8e4, 4e4, 8e5, 300.0
    loop = LinearLoop(np.eye(3) * m, np.eye(3) * d, Gains((kp,) * 3, (kd,) * 3, (ki,) * 3), lag)
    omega = np.geomspace(1e-3, 2.0, 50)
    denominator = np.polyadd(np.polymul([m, d, 0.0, 0.0], [lag, 1.0]), [kd, kp, ki])
    _, expected = signal.freqs(np.polymul([1.0, 0.0], [lag, 1.0]), denominator, worN=omega)
    assert loop.receptance(omega)[:, 1, 1] == pytest.approx(expected, rel=1e-9)


def test_without_current_the_damping_is_the_hulls_linear_damping():
    vessel = Vessel()
    assert linear_damping(vessel, np.zeros(2)) == pytest.approx(vessel.linear_damping, rel=1e-3, abs=1.0)


@pytest.mark.parametrize("direction", np.radians([0.0, 45.0, 90.0, 135.0]))
def test_current_gradients_are_the_quadratic_drags_derivatives(direction):
    """The hull's side force and yaw moment at rest grow with the square of the speed (cross-flow
    drag) plus the linear damping's share: F(U) = a U^2 + b U, so dF/dU = 2 a U + b from F at U
    and 2 U (the surge damping's blend is not of that form)."""
    vessel = Vessel()
    speed = 0.6
    one, two = (rest_force(vessel, current_vector(u, direction)) for u in (speed, 2.0 * speed))
    a = (two - 2.0 * one) / (2.0 * speed * speed)
    b = (one - a * speed * speed) / speed
    by_speed, _ = current_gradients(vessel, speed, direction)
    assert by_speed[1:] == pytest.approx((2.0 * a * speed + b)[1:], rel=1e-3, abs=50.0)
