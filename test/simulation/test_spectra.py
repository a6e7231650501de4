"""allocator_pkg.simulation.spectra: each spectrum's variance against its closed form (Beta and
Gamma functions, scipy), the JONSWAP's m0 against Hs^2 / 16 and its peak at 2 pi / Tp."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate, special

from allocator_pkg.simulation import spectra

SPEEDS = st.floats(2.0, 35.0)


def variance(function, *args, upper=np.inf):
    return integrate.quad(lambda f: float(function(np.array([f]), *args)[0]), 0.0, upper, limit=400)[0]


@settings(max_examples=15, deadline=None)
@given(SPEEDS)
def test_npd_variance_is_its_beta_function_integral(speed):
    """int (1 + (a f)^n)^(-5/(3n)) df = B(1/n, 2/(3n)) / (n a)."""
    n, u = spectra.NPD_EXPONENT, speed / 10.0
    a = 172.0 * u ** -0.75
    expected = 320.0 * u * u * special.beta(1.0 / n, 2.0 / (3.0 * n)) / (n * a)
    assert variance(spectra.npd, speed) == pytest.approx(expected, rel=2e-3)


@settings(max_examples=15, deadline=None)
@given(SPEEDS, st.floats(0.05, 0.25), st.floats(0.01, 0.1))
def test_api_variance_is_intensity_times_speed_squared(speed, intensity, peak):
    assert variance(spectra.api, speed, intensity, peak) == pytest.approx((intensity * speed) ** 2, rel=1e-3)


@settings(max_examples=15, deadline=None)
@given(SPEEDS)
def test_harris_variance_is_its_gamma_function_integral(speed):
    """int 4 k U L / (2 + (L f / U)^2)^(5/6) df = 4 k U^2 2^(-1/3) sqrt(pi) G(1/3) / (2 G(5/6))."""
    expected = (4.0 * spectra.HARRIS_DRAG * speed ** 2 * 2.0 ** (-1.0 / 3.0) * math.sqrt(math.pi)
                * special.gamma(1.0 / 3.0) / (2.0 * special.gamma(5.0 / 6.0)))
    assert variance(spectra.harris, speed) == pytest.approx(expected, rel=2e-3)


@settings(max_examples=25, deadline=None)
@given(st.floats(0.5, 12.0), st.floats(4.0, 16.0), st.floats(1.0, 7.0))
def test_jonswap_m0_is_hs_squared_over_16_and_peaks_at_tp(hs, tp, gamma):
    """DNV-RP-C205 3.5.5: A_gamma normalises to within 2 % (exactly for gamma 1, Pierson-Moskowitz)."""
    m0 = integrate.quad(lambda w: float(spectra.jonswap(np.array([w]), hs, tp, gamma)[0]), 0.0, 20.0, limit=400,
                        points=[2.0 * math.pi / tp])[0]
    assert m0 == pytest.approx(hs * hs / 16.0, rel=0.02 if gamma > 1.0 else 1e-4)    # the tail past 20 rad/s
    omega = np.linspace(0.2, 3.0, 28001) * 2.0 * math.pi / tp
    assert omega[np.argmax(spectra.jonswap(omega, hs, tp, gamma))] == pytest.approx(2.0 * math.pi / tp, rel=1e-3)


def test_the_peak_factor_is_dnv_rp_c205s_and_continuous():
    for hs in (1.0, 4.0, 9.0):
        assert spectra.peak_factor(hs, 3.0 * math.sqrt(hs)) == 5.0
        assert spectra.peak_factor(hs, 6.0 * math.sqrt(hs)) == 1.0
        assert spectra.peak_factor(hs, 3.6 * math.sqrt(hs) * (1 + 1e-9)) == pytest.approx(5.0, rel=1e-3)    # exp(1.61)
        assert spectra.peak_factor(hs, 5.0 * math.sqrt(hs) * (1 - 1e-9)) == pytest.approx(1.0, rel=1e-6)


def test_first_order_spectrum_integrates_to_sigma_squared():
    assert variance(spectra.first_order, 2.0, 30.0) == pytest.approx(4.0, rel=1e-6)


def test_an_unknown_spectrum_is_refused_with_its_key():
    with pytest.raises(ValueError, match=r"environment\.wind\.spectrum"):
        spectra.wind_spectrum("kaimal", np.array([0.1]), 10.0)
