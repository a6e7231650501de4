"""The svd_filter method (section 5.4): driven through a singular configuration (all azimuths
parallel) its thrust stays bounded where the plain pseudo-inverse of T(alpha) blows up, its
angles move smoothly, and the damped inverse keeps a bounded condition number; at rest it is
the extended pseudo-inverse (1.33)."""

import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from reference import weighted_pseudo_inverse

from allocator_pkg import Allocator, vehicle_from_parameters
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix, extended_configuration_matrix
from allocator_pkg.effectiveness.model import Model

EPSILON = 0.05


def three_azimuths(**overrides):
    """Three reversible azimuths on the centre line (x = 10, 0, -10 m): surge, sway and yaw.
    With all three parallel, T(alpha) loses the force across them."""
    parameters = {"actuators.names": ["bow", "mid", "stern"], "rate_hz": 10.0, "dofs": ["surge", "sway", "yaw"],
                  "method": "svd_filter", "svd_filter.damping_threshold": EPSILON}
    for name, x in (("bow", 10.0), ("mid", 0.0), ("stern", -10.0)):
        parameters.update({f"actuators.{name}.type": "azimuth", f"actuators.{name}.position": [x, 0.0, 0.0],
                           f"actuators.{name}.thrust_max": 100.0, f"actuators.{name}.reversible": True,
                           f"actuators.{name}.azimuth_rate_max": 0.5})
    parameters.update(overrides)
    return vehicle_from_parameters(parameters)


def normalised(vehicle, angles):
    """D^-1 T(alpha) F (equal weights, F the largest range): the matrix whose singular values
    the method damps."""
    model = Model.build(vehicle, 0.1)
    t = configuration_matrix(vehicle.actuators, angles)[list(vehicle.dof_indices)]
    return t * np.max(model.force_scale) / model.dof_scale[:, None]


def test_through_a_singular_configuration_thrust_stays_bounded_angles_smooth_condition_kept():
    vehicle = three_azimuths()
    allocator = Allocator(vehicle)
    method = allocator._solver.method
    model = Model.build(vehicle, allocator.dt)
    surge = np.array([150.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    for _ in range(80):                                     # all three along x: singular in sway
        allocator.allocate(surge)
    assert np.ptp(np.mod(allocator.azimuth, math.pi)) < 1e-9
    angles, raw, plain, condition, effective = [], [], [], [], []
    for k in range(160):            # the request turns to sway and back, a yaw moment through zero
        turn = 0.5 * math.pi * math.sin(math.pi * k / 160)
        yaw = 200.0 * math.cos(2.0 * math.pi * k / 160)
        tau = np.array([150.0 * math.cos(turn), 150.0 * math.sin(turn), 0.0, 0.0, 0.0, yaw])
        result = allocator.allocate(tau)
        angles.append(result.azimuth.copy())
        raw.append(np.max(np.abs(method.thrust)))
        a = normalised(vehicle, result.azimuth)
        with np.errstate(divide="ignore"):
            plain.append(np.max(np.abs(np.linalg.pinv(a, rcond=0.0) @ (tau[[0, 1, 5]] / model.dof_scale)))
                         * 100.0)
        s = np.linalg.svd(a, compute_uv=False)
        condition.append(s[0] / s[-1] if s[-1] > 0 else math.inf)
        effective.append(s[0] * np.max(method.gains))
    request = math.hypot(150.0 / np.min(model.dof_scale[:2]), 200.0 / model.dof_scale[2])
    assert max(raw) <= 100.0 * request / EPSILON * (1 + 1e-9)          # |x| <= |request| / eps
    assert max(condition) > 1e3 and max(plain) > 20.0 * max(raw)        # the plain inverse blows up
    assert max(effective) <= max(s[0] for s in [np.linalg.svd(normalised(vehicle, a), compute_uv=False)
                                                 for a in angles]) / EPSILON + 1e-9
    steps = np.angle(np.exp(1j * np.diff(np.array(angles), axis=0)))
    assert np.all(np.abs(steps) <= 0.05 + 1e-9)                         # the rate limit
    for column in steps.T:                                              # no chatter: few reversals
        moving = column[np.abs(column) > 1e-6]
        assert np.sum(np.diff(np.sign(moving)) != 0) <= 2
    assert not result.saturated                                         # back to surge, met


def test_the_gains_are_the_pseudo_inverses_above_epsilon_and_linear_below():
    vehicle = three_azimuths()
    allocator = Allocator(vehicle)
    method = allocator._solver.method
    for spread in (1.0, 0.3, 0.05, 0.01, 0.0):
        allocator.reset()
        method._damped(normalised(vehicle, [0.0, spread, -spread]), np.array([0.3, 0.1, 0.05]))
        s, gains = method.singular_values, method.gains
        expected = np.where(s >= EPSILON, 1.0 / np.maximum(s, 1e-300), s / EPSILON ** 2)
        assert gains == pytest.approx(expected, rel=1e-12)
        assert np.max(gains) <= 1.0 / EPSILON * (1 + 1e-12)


def test_at_rest_the_answer_is_the_extended_pseudo_inverse():
    free = {f"actuators__{name}__{key}": 0.0 for name in ("azimuth_fwd", "azimuth_aft")
            for key in ("azimuth_rate_max", "thrust_rate_max")}
    free.update({f"actuators__{name}__thrust_rate_max": 0.0 for name in ("main_port", "main_stbd")})
    vehicle = vehicle_from(ROOT / "config" / "example1_rov.yaml", method="svd_filter", **free)
    t_e = extended_configuration_matrix(vehicle.actuators)[[0, 1, 5]]
    gain = weighted_pseudo_inverse(t_e, np.ones(6))
    for angle in np.radians(np.arange(0.0, 360.0, 45.0)):
        tau = np.array([120.0 * math.cos(angle), 80.0 * math.sin(angle), 0.0, 0.0, 0.0, 30.0])
        allocator = Allocator(vehicle)
        for _ in range(100):
            result = allocator.allocate(tau)
        expected = gain @ tau[[0, 1, 5]]
        extended = np.array([result.thrust[0] * math.cos(result.azimuth[0]),
                             result.thrust[0] * math.sin(result.azimuth[0]),
                             result.thrust[1] * math.cos(result.azimuth[1]),
                             result.thrust[1] * math.sin(result.azimuth[1]), result.thrust[2], result.thrust[3]])
        assert extended == pytest.approx(expected, abs=1e-6 * 150.0)
        assert result.achieved[[0, 1, 5]] == pytest.approx(tau[[0, 1, 5]], abs=1e-6)


def test_an_azimuth_pinned_at_zero_thrust_with_a_free_angle_gives_zero():
    """A reversible azimuth whose rate limit brings its thrust to exactly zero in a sample, its
    angle free (no turning-rate limit): its bounds meet at zero, so the methods hold it there
    whatever the angle (a counter-example hypothesis found: the angle window's -inf reached cos)."""
    parameters = {"rate_hz": 10.0, "actuators.names": [f"a{i}" for i in range(8)]}
    for i, (position, direction) in enumerate([((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))] * 5 + [
            ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)), ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0))]):
        parameters.update({f"actuators.a{i}.type": "fixed", f"actuators.a{i}.position": list(position),
                           f"actuators.a{i}.direction": list(direction), f"actuators.a{i}.thrust_max": 1.0,
                           f"actuators.a{i}.thrust_min": 0.0})
    parameters.update({"actuators.a7.type": "azimuth", "actuators.a7.position": [0.0, 1.0, 0.0],
                       "actuators.a7.thrust_max": 1000.0, "actuators.a7.reversible": True,
                       "actuators.a7.thrust_rate_max": 1.0})
    vehicle = vehicle_from_parameters(parameters)
    for method in ("svd_filter", "pseudoinverse"):
        allocator = Allocator(vehicle, method=method)
        first = allocator.allocate([0.0, 0.0, 0.0, 0.0, 0.0, 1.0])
        assert first.thrust[7] == pytest.approx(-0.1)                   # one rate step, 1 N/s at 10 Hz
        second = allocator.allocate([0.0, 0.0, 0.0, 0.0, 0.0, -1.0])
        assert second.thrust[7] == 0.0 and np.all(np.isfinite(second.command))
