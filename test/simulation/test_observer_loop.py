"""allocator_pkg.simulation.observer_loop: the joint state space of vessel, thruster lag, PID,
passive observer and wind feed-forward, checked piece by piece against independent derivations:
without observer and feed-forward it is the plain loop's receptance (closed form of
:class:`LinearLoop`); the observer's rows give the estimate/measurement transfer a time-domain
run of :class:`PassiveObserver` alone shows; the whole loop's transfers against scipy.signal's
frequency response of the same state space as transfer functions; the feed-forward leaves of a
slow gust at most its filter's residual; the noise and wave-motion spectra against their variances."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import signal
from test_observer import steady_amplitude

from allocator_pkg.simulation.controller import Gains
from allocator_pkg.simulation.frequency_domain import LinearLoop, current_vector, linear_damping
from allocator_pkg.simulation.observer import ObserverTuning, PassiveObserver
from allocator_pkg.simulation.observer_loop import PLANT, ObservedLoop, noise_spectrum, wave_motion_spectrum
from allocator_pkg.simulation.spectra import jonswap
from allocator_pkg.simulation.vessel import Vessel
from allocator_pkg.simulation.wave_motion import transfer

VESSEL = Vessel()
GAINS = Gains((4.0e5, 4.0e5, 4.0e8), (4.0e6, 4.0e6, 4.0e9), (4.0e3, 4.0e3, 4.0e6))
DT = 0.1


def observer(period: float) -> PassiveObserver:
    return PassiveObserver(ObserverTuning(wave_period=period), VESSEL.mass, VESSEL.linear_damping,
                           VESSEL.parameters.mass, VESSEL.parameters.length)


@settings(max_examples=10, deadline=None)
@given(st.floats(0.0, 1.5), st.floats(0.0, 2.0 * math.pi), st.floats(1.0, 20.0), st.floats(0.3, 1.0))
def test_without_observer_and_feedforward_the_loop_is_the_plain_receptance(speed, direction, lag, factor):
    """... with the thrust loss factor as the same factor on the plain loop's gains."""
    damping = linear_damping(VESSEL, current_vector(speed, direction))
    omega = np.geomspace(1e-3, 2.0, 25)
    scaled = Gains(*(tuple(factor * k for k in gain) for gain in (GAINS.kp, GAINS.kd, GAINS.ki)))
    plain = LinearLoop(VESSEL.mass, damping, scaled, lag).receptance(omega)
    joint = ObservedLoop(VESSEL.mass, damping, GAINS, lag, thrust_factor=factor).response(omega)
    np.testing.assert_allclose(joint[:, :, 0:3], plain, rtol=1e-9, atol=1e-12 * np.abs(plain).max())
    np.testing.assert_allclose(joint[:, :, 3:6], plain, rtol=1e-9, atol=1e-12 * np.abs(plain).max())


@pytest.mark.parametrize("key,value", [("lag", 0.0), ("lag", math.nan), ("wind_filter", -1.0),
                                       ("thrust_factor", 0.0), ("thrust_factor", 1.2)])
def test_a_bad_loop_value_is_refused_naming_its_key(key, value):
    names = {"lag": "thruster_time_constant", "wind_filter": "controller.wind_filter",
             "thrust_factor": "thrust_losses"}
    values = {"lag": 5.0, "wind_filter": None, "thrust_factor": 1.0, key: value}
    with pytest.raises(ValueError, match=names[key]):
        ObservedLoop(VESSEL.mass, VESSEL.linear_damping, GAINS, **values)


@pytest.mark.slow
@pytest.mark.parametrize("period", [6.0, 11.0])
@pytest.mark.parametrize("dof", [0, 1, 2])
def test_the_observer_rows_give_the_estimate_a_time_domain_observer_shows(period, dof):
    # no controller: the observer's model gets no thrust, as in the run alone
    loop = ObservedLoop(VESSEL.mass, VESSEL.linear_damping, Gains((0.0,) * 3, (0.0,) * 3, (0.0,) * 3), 5.0,
                        observer(period))
    a, b = loop.matrices()
    rows = slice(PLANT, PLANT + 15)
    for omega in (0.1, math.pi / period, 2.0 * math.pi / period, 2.0):
        # the observer's rows, fed by y (the noise column)
        estimate = np.linalg.solve(1j * omega * np.eye(15) - a[rows, rows], b[rows, 9 + dof])[6 + dof]
        assert abs(estimate) == pytest.approx(steady_amplitude(observer(period), dof, omega), rel=0.03, abs=2e-3)


@pytest.mark.parametrize("feedforward", [None, 20.0])
@pytest.mark.parametrize("period", [5.0, 12.0])
@pytest.mark.filterwarnings("ignore::scipy.signal.BadCoefficients")
def test_the_joint_loop_is_scipys_transfer_function(feedforward, period):
    damping = linear_damping(VESSEL, current_vector(0.7, 1.0))
    loop = ObservedLoop(VESSEL.mass, damping, GAINS, 5.0, observer(period), feedforward)
    a, b = loop.matrices()
    omega = np.geomspace(5e-3, 1.5, 9)
    joint = loop.response(omega)
    for dof in range(3):
        for source in (dof, 3 + dof, 9 + dof):
            output = np.zeros((1, a.shape[0]))
            output[0, dof] = 1.0
            system = signal.StateSpace(a, b[:, [source]], output, np.zeros((1, 1)))
            _, expected = signal.freqresp(system, w=omega)
            # 30 states as polynomials lose about 1e-4 of the response to conditioning
            np.testing.assert_allclose(joint[:, dof, source], expected, rtol=2e-3,
                                       atol=1e-6 * np.abs(expected).max())


def test_the_feedforward_leaves_of_a_slow_gust_at_most_its_filters_residual():
    """The feed-forward answers the gust through 1 / (1 + s T_f): what it leaves, s T_f / (1 + s T_f),
    bounds, within half again (the observer and the integral share the rest), the gust's response
    with it over the response without it."""
    damping = linear_damping(VESSEL, current_vector(0.5, 0.0))
    omega = np.array([1e-4, 1e-3, 3e-3, 1e-2])
    for period in (6.0, 10.0):
        for filter_time in (10.0, 20.0, 60.0):
            fed = ObservedLoop(VESSEL.mass, damping, GAINS, 5.0, observer(period), filter_time).response(omega)
            bare = ObservedLoop(VESSEL.mass, damping, GAINS, 5.0, observer(period)).response(omega)
            s = 1j * omega * filter_time
            for dof in range(3):
                assert np.all(np.abs(fed[:, dof, dof] / bare[:, dof, dof]) <= 1.5 * np.abs(s / (1.0 + s)))
                # the other forces are not measured: the feed-forward leaves them alone
                np.testing.assert_allclose(fed[:, dof, 3 + dof], bare[:, dof, 3 + dof], rtol=1e-6)


@settings(max_examples=20, deadline=None)
@given(st.floats(0.01, 1.0), st.floats(0.0, 0.1), st.floats(0.05, 1.0))
def test_the_noise_spectrum_integrates_to_the_variance_up_to_nyquist(position, heading, period):
    omega = np.linspace(0.0, 2.0 * math.pi / period, 40001)
    spectrum = noise_spectrum(omega, np.array([position, position, heading]), period)
    variance = np.trapezoid(np.diagonal(spectrum, axis1=1, axis2=2), omega, axis=0)
    np.testing.assert_allclose(variance, [position ** 2, position ** 2, heading ** 2], rtol=1e-3)


@pytest.mark.parametrize("height,period", [(2.0, 7.0), (4.5, 10.0), (8.0, 13.0)])
@pytest.mark.parametrize("direction_deg", [0.0, 30.0, 90.0, 150.0])
def test_a_long_crested_wave_motion_spectrum_is_the_transfer_on_jonswap(height, period, direction_deg):
    omega = np.linspace(0.05, 3.0, 3000)
    direction = math.radians(direction_deg)
    spectrum = wave_motion_spectrum(omega, height, period, 0.0, direction, 0.0, 80.0, 18.0)
    t = transfer(omega, direction, 80.0, 18.0)
    sea = jonswap(omega, height, period, None)
    np.testing.assert_allclose(np.diagonal(spectrum, axis1=1, axis2=2).real, (np.abs(t) ** 2 * sea).T, rtol=1e-12)
    # in long waves the hull moves with the water: the horizontal motion's variance tends to the elevation's
    horizontal = np.trapezoid(spectrum[:, 0, 0].real + spectrum[:, 1, 1].real, omega)
    assert horizontal <= np.trapezoid(sea, omega) * (1.0 + 1e-9)


@settings(max_examples=10, deadline=None)
@given(st.floats(0.0, 2.0 * math.pi), st.floats(1.0, 10.0))
def test_a_spread_wave_motion_spectrum_is_hermitian_and_nonnegative(direction, spreading):
    omega = np.linspace(0.2, 2.0, 40)
    spectrum = wave_motion_spectrum(omega, 4.0, 9.0, 0.0, direction, spreading, 80.0, 18.0)
    np.testing.assert_allclose(spectrum, np.conj(np.swapaxes(spectrum, 1, 2)), atol=1e-15)
    assert np.linalg.eigvalsh(spectrum).min() > -1e-12 * np.abs(spectrum).max()
