"""allocator_pkg.simulation.observer: the Fossen and Strand passive observer against its
transfer function derived here independently (Laplace algebra of one decoupled DOF, evaluated
by scipy.signal.freqs), Fossen's gain relations, the low-frequency estimate of a known track in
noise, the bias of an unmodelled load and the heading across +-180 deg."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.polynomial import polynomial as P
from scipy import signal

from allocator_pkg.simulation.observer import ObserverTuning, PassiveObserver
from allocator_pkg.simulation.vessel import Vessel

VESSEL = Vessel()
MASS = np.diag(np.diag(VESSEL.mass))                   # decoupled, so that each DOF is one transfer function
DAMPING = np.diag(np.diag(VESSEL.linear_damping))
DT = 0.1


def observer(tuning: ObserverTuning, mass: np.ndarray = MASS) -> PassiveObserver:
    return PassiveObserver(tuning, mass, DAMPING, VESSEL.parameters.mass, VESSEL.parameters.length)


def estimate_response(tuning: ObserverTuning, dof: int, omega: float) -> complex:
    """eta^ / y of DOF ``dof`` at ``omega`` [rad/s], heading 0 and no thrust: with e = y~,
    xi_2 = Hw e, Hw = (k12 s - omega_o^2 k11) / (s^2 + 2 lambda omega_o s + omega_o^2),
    eta^ = G e, G = (K2 + (K4 + K3 / (s + 1/T)) / (m s + d)) / s, e = y - eta^ - xi_2, so
    eta^ / y = G / (1 + G + Hw)."""
    probe = observer(tuning)
    wo, lam, t = tuning.omega_o, tuning.wave_damping, tuning.bias_time_constant
    k11, k12 = tuning.k1()[dof, dof], tuning.k1()[3 + dof, dof]
    m, d, k3, k4 = MASS[dof, dof], DAMPING[dof, dof], probe.k3[dof, dof], probe.k4[dof, dof]
    mass_damping, bias = [d, m], [1.0 / t, 1.0]                                # ascending powers
    num_g = P.polyadd(P.polymul([tuning.omega_c], P.polymul(mass_damping, bias)),
                      P.polyadd(P.polymul([k4], bias), [k3]))
    den_g = P.polymul([0.0, 1.0], P.polymul(mass_damping, bias))
    num_w, den_w = [-wo ** 2 * k11, k12], [wo ** 2, 2.0 * lam * wo, 1.0]
    num = P.polymul(num_g, den_w)
    den = P.polyadd(P.polyadd(P.polymul(den_g, den_w), num), P.polymul(num_w, den_g))
    _, response = signal.freqs(num[::-1], den[::-1], worN=[omega])
    return complex(response[0])


def steady_amplitude(estimator: PassiveObserver, dof: int, omega: float, amplitude: float = 1.0) -> float:
    """The amplitude of eta^ in DOF ``dof`` over the last cycles of a measured sinusoid, the
    observer run in the time domain from rest."""
    estimator.start(np.zeros(3))
    steps = round(1500.0 / DT)
    found = []
    for k in range(steps):
        measured = np.zeros(3)
        measured[dof] = amplitude * math.sin(omega * k * DT)
        estimator.step(measured, np.zeros(3), DT)
        if k > steps - round(4 * 2 * math.pi / omega / DT):
            found.append(estimator.eta[dof])
    return max(abs(v) for v in found)


@pytest.mark.slow
@pytest.mark.parametrize("period", [6.0, 9.0, 12.0])
@pytest.mark.parametrize("dof", [0, 1, 2])
@pytest.mark.parametrize("share", [1.0, 0.5, 2.0])
def test_a_sinusoid_passes_as_the_transfer_function_predicts(period, dof, share):
    tuning = ObserverTuning(wave_period=period)
    omega = share * tuning.omega_o
    amplitude = 0.01 if dof == 2 else 0.8
    predicted = abs(estimate_response(tuning, dof, omega)) * amplitude
    assert steady_amplitude(observer(tuning), dof, omega, amplitude) == pytest.approx(predicted, rel=0.03)
    if share == 1.0 and period <= 12.0:  # the notch: the wave frequency passes at under 0.14
        assert predicted < 0.14 * amplitude


def test_the_low_frequency_passes_and_the_notch_holds_at_every_wave_period():
    for period in np.linspace(3.5, 12.0, 18):               # Table 2-1's peak periods
        tuning = ObserverTuning(wave_period=float(period))
        for dof in range(3):
            assert abs(estimate_response(tuning, dof, 2 * math.pi / 900.0)) == pytest.approx(1.0, abs=0.02)
            assert abs(estimate_response(tuning, dof, tuning.omega_o)) < 0.14


@pytest.mark.parametrize("period", [3.0, 5.0, 8.0, 14.0, 20.0, 25.0])
def test_fossens_gains_make_the_notch_and_a_strictly_positive_real_loop(period):
    tuning = ObserverTuning(wave_period=period)
    wo, wc, lam, zeta = tuning.omega_o, tuning.omega_c, tuning.wave_damping, tuning.notch_damping
    k1 = tuning.k1()
    assert np.diag(k1[:3]) == pytest.approx([-2 * (zeta - lam) * wc / wo] * 3)
    assert np.diag(k1[3:]) == pytest.approx([2 * wo * (zeta - lam)] * 3)
    for i in range(3):                   # h0: the position loop's denominator with K1, K2 (MSS ExPassiveObs)
        loop = [1.0, k1[3 + i, i] + wc + 2 * lam * wo, wo ** 2 + 2 * lam * wo * wc - k1[i, i] * wo ** 2, wo ** 2 * wc]
        assert np.polymul([1.0, 2 * zeta * wo, wo ** 2], [1.0, wc]) == pytest.approx(loop)
    probe = observer(tuning)
    omegas = np.logspace(-5, 2, 2000)
    for i in range(3):
        k3, k4, t = probe.k3[i, i], probe.k4[i, i], tuning.bias_time_constant
        assert 1.0 / t <= 0.1 * k3 / k4 and k3 / k4 < wo < wc
        h0 = signal.TransferFunction([1.0, 2 * lam * wo, wo ** 2], np.polymul([1.0, 2 * zeta * wo, wo ** 2], [1, wc]))
        hb = signal.TransferFunction(k4 * np.array([1.0, 1.0 / t + k3 / k4]), [1.0, 1.0 / t])
        _, first = signal.freqresp(h0, omegas)
        _, second = signal.freqresp(hb, omegas)
        assert np.all((first * second).real > 0.0)


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(["wave_damping", "cutoff_ratio", "bias_time_constant", "k3_ratio", "wave_period"]),
       st.floats(-10.0, 0.0))
def test_a_tuning_off_fossens_relations_is_refused_naming_the_key(key, value):
    bad = {"wave_damping": 1.0 + abs(value), "cutoff_ratio": min(1.0, 1.0 + value), "bias_time_constant":
           5.0 + abs(value), "k3_ratio": 0.8 + abs(value), "wave_period": value}[key]
    with pytest.raises(ValueError, match=f"observer.{key}"):
        ObserverTuning(wave_period=8.0, **{key: bad}) if key != "wave_period" else ObserverTuning(wave_period=bad)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_low_frequency_track_is_estimated_through_waves_and_noise(seed):
    """A track the model's own thrust drives (M eta'' + D eta' = tau at heading 0), the
    measurement that track plus wave motion at omega_o plus white noise: after 300 s the
    position estimate stays within 0.2 m of the track (the notch's leak, |T(j omega_o)| 0.6 m =
    0.06 m, plus the noise it passes) with an RMS under 0.07 m, and the heading within 0.1 deg,
    though the waves move the measurement +-0.6 m."""
    tuning, rng = ObserverTuning(wave_period=8.0), np.random.default_rng(seed)
    times = np.arange(round(1200.0 / DT)) * DT
    track = np.stack([2.0 * np.sin(2 * np.pi * times / 600.0), 1.5 * np.sin(2 * np.pi * times / 900.0 + 1.0),
                      0.02 * np.sin(2 * np.pi * times / 700.0)], axis=1)
    waves = 0.6 * np.stack([np.sin(tuning.omega_o * times), np.cos(tuning.omega_o * times), 0.0 * times], axis=1)
    noise = rng.normal(0.0, [0.1, 0.1, math.radians(0.05)], track.shape)
    velocity = np.gradient(track, DT, axis=0)
    tau = (MASS @ np.gradient(velocity, DT, axis=0).T + DAMPING @ velocity.T).T
    estimator = observer(tuning)
    estimator.start(track[0] + waves[0])
    errors = []
    for k in range(len(times)):
        errors.append(estimator.eta - track[k])
        estimator.step(track[k] + waves[k] + noise[k], tau[k], DT)
    late = np.array(errors[round(300.0 / DT):])
    assert abs(estimate_response(tuning, 0, tuning.omega_o)) * 0.6 < 0.065
    assert np.max(np.abs(late[:, :2])) < 0.2
    assert np.sqrt(np.mean(late[:, :2] ** 2)) < 0.07
    assert np.degrees(np.max(np.abs(late[:, 2]))) < 0.1


@pytest.mark.slow
@pytest.mark.parametrize("heading", [0.0, 1.0, -2.5])
def test_an_unmodelled_constant_load_settles_where_the_steady_equations_put_it(heading):
    """The hull at rest at ``heading`` under a constant NED load the observer does not know,
    balanced by a known thrust tau = -R^T load. With every derivative zero: nu = -R^T K2 y~,
    b = T K3 y~ and -D nu + R^T b + tau + R^T K4 y~ = 0, so y~ = (R D R^T K2 + T K3 + K4)^-1 load,
    and xi_2 = -k11 y~ (xi_1' = 0), so eta^ = y - y~ - xi_2 = y - (1 - k11) y~."""
    load = np.array([80e3, -120e3, 2e6])
    c, s = math.cos(heading), math.sin(heading)
    rotation = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    tuning = ObserverTuning(wave_period=8.0)
    estimator = observer(tuning, VESSEL.mass)
    t = tuning.bias_time_constant
    innovation = np.linalg.solve(rotation @ DAMPING @ rotation.T * tuning.omega_c + t * estimator.k3 + estimator.k4,
                                 load)
    measured = np.array([3.0, -2.0, heading])
    estimator.start(measured)
    for _ in range(round(6000.0 / DT)):
        estimator.step(measured, -rotation.T @ load, DT)
    assert estimator.bias == pytest.approx(t * estimator.k3 @ innovation, rel=0.01)
    k11 = tuning.k1()[0, 0]
    assert estimator.eta == pytest.approx(measured - (1.0 - k11) * innovation, rel=1e-3, abs=1e-5)
    assert estimator.nu == pytest.approx(-rotation.T @ (tuning.omega_c * innovation), rel=0.01, abs=1e-7)


def test_the_heading_estimate_crosses_180_deg_without_a_jump():
    """A heading swinging +-0.3 deg about 180 deg every 200 s: the estimate stays within
    0.05 deg of it though the measurement jumps between +-180 deg."""
    estimator = observer(ObserverTuning(wave_period=8.0))
    swing = [math.pi + math.radians(0.3) * math.sin(2 * math.pi * k * DT / 200.0) for k in range(round(400.0 / DT))]
    estimator.start(np.array([0.0, 0.0, math.remainder(swing[0], 2 * math.pi)]))
    for heading in swing:
        assert abs(math.remainder(estimator.eta[2] - heading, 2 * math.pi)) < math.radians(0.05)
        estimator.step(np.array([0.0, 0.0, math.remainder(heading, 2 * math.pi)]), np.zeros(3), DT)
