"""allocator_pkg.simulation.wave_drift: Newman's slowly varying drift of a JONSWAP sea. With
one drift coefficient, Var q = 2 int_0^inf int_0^inf S(w) S(w + mu) dw dmu / m0^2 = 1 (the double
integral over mu > 0 is half of m0^2, by symmetry in w and w + mu): the spectrum integrates to
it, the time series has mean 1 and that standard deviation within 10 %."""

import math

import numpy as np
import pytest

from allocator_pkg.simulation import spectra
from allocator_pkg.simulation.series import amplitudes, analytic_series, grid, real_series
from allocator_pkg.simulation.wave_drift import drift_factor, newman_spectrum

SEAS = [(1.3, 6.5), (3.1, 8.5), (5.7, 10.0), (9.5, 11.5)]
GRID = np.linspace(0.02, 4.0, 4000)


@pytest.mark.parametrize(("hs", "tp"), SEAS)
def test_newmans_spectrum_integrates_to_the_double_integral(hs, tp):
    mu = np.linspace(0.0, 3.0, 1500)
    assert np.trapezoid(newman_spectrum(mu, GRID, spectra.jonswap(GRID, hs, tp)), mu) == pytest.approx(1.0, rel=0.01)


@pytest.mark.parametrize(("hs", "tp"), SEAS)
@pytest.mark.parametrize("seed", [0, 1])
def test_the_drift_series_has_mean_one_and_newmans_deviation(hs, tp, seed):
    n, df = grid(25000.0, 0.4)
    omega = 2.0 * math.pi * df * np.arange(n // 2 + 1)
    coefficients = amplitudes(2.0 * math.pi * spectra.jonswap(omega, hs, tp), df, np.random.default_rng(seed))
    zeta = analytic_series(coefficients, n)
    assert zeta.real == pytest.approx(real_series(coefficients, n), abs=1e-9)
    q = drift_factor(zeta)
    assert np.mean(q) == pytest.approx(1.0, rel=1e-9)
    assert np.std(q) == pytest.approx(1.0, rel=0.10)


def test_a_calm_sea_drifts_nothing():
    assert not np.any(drift_factor(np.zeros(64, dtype=complex)))
