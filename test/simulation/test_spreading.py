"""allocator_pkg.simulation.spreading: DNV-RP-C205's cos^n spreading integrates to 1 (scipy's
quadrature and the Gamma-function closed form), its sampled directions have the closed-form
moments within the sample's error, and spread means are its weighted integrals."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate, special

from allocator_pkg.simulation.spreading import check_exponent, density, normalisation, sample_directions, spread_mean

EXPONENTS = [0.5, 1.0, 2.0, 3.0, 4.0, 7.5, 10.0, 30.0]


@settings(max_examples=40, deadline=None)
@given(st.floats(0.1, 80.0))
def test_the_spreading_integrates_to_one(n):
    total, _ = integrate.quad(lambda t: float(density(np.array(t), n)), -math.pi / 2.0, math.pi / 2.0)
    assert total == pytest.approx(1.0, rel=1e-7)
    assert normalisation(n) == pytest.approx(special.gamma(1.0 + n / 2.0)
                                             / (math.sqrt(math.pi) * special.gamma(0.5 + n / 2.0)), rel=1e-10)


def test_no_energy_beyond_a_right_angle():
    assert np.all(density(np.array([-2.0, 1.6, 3.0]), 2.0) == 0.0)


@pytest.mark.parametrize("n", EXPONENTS)
@pytest.mark.parametrize("seed", [0, 7])
def test_sampled_directions_have_the_closed_form_moments(n, seed):
    """E[cos^2] = (n + 1) / (n + 2) and E[cos^4] = (n + 1)(n + 3) / ((n + 2)(n + 4)) (ratios of
    int cos^(n+2k) = sqrt(pi) Gamma((n+2k+1)/2) / Gamma((n+2k)/2 + 1)); within 4 standard errors."""
    count = 20000
    theta = sample_directions(n, count, np.random.default_rng(seed))
    assert np.all(np.abs(theta) <= math.pi / 2.0)
    for power, expected in ((2, (n + 1) / (n + 2)), (4, (n + 1) * (n + 3) / ((n + 2) * (n + 4)))):
        values = np.cos(theta) ** power
        error = 4.0 * np.std(values) / math.sqrt(count)
        assert abs(np.mean(values) - expected) < error
    assert abs(np.mean(np.sin(theta))) < 4.0 * np.std(np.sin(theta)) / math.sqrt(count)


def test_a_long_crested_sea_draws_nothing():
    generator = np.random.default_rng(3)
    assert np.all(sample_directions(0.0, 100, generator) == 0.0)
    assert generator.uniform() == np.random.default_rng(3).uniform()


@pytest.mark.parametrize("n", EXPONENTS)
def test_a_spread_mean_is_the_weighted_integral(n):
    def function(theta: float) -> np.ndarray:
        return np.array([math.cos(theta) ** 2, math.sin(theta + 0.3), abs(theta), abs(theta - 0.2)])

    expected = [integrate.quad(lambda t, k=k: function(t)[k] * float(density(np.array(t), n)),
                               -math.pi / 2.0, math.pi / 2.0, points=[0.0, 0.2])[0] for k in range(4)]
    assert spread_mean(function, n) == pytest.approx(expected, rel=2e-3, abs=1e-6)
    assert spread_mean(function, n)[0] == pytest.approx((n + 1) / (n + 2), rel=1e-6)


def test_long_crested_is_the_value_at_the_main_direction():
    assert spread_mean(lambda t: np.array([math.cos(t), t + 1.0]), 0.0) == pytest.approx([1.0, 1.0])


@pytest.mark.parametrize("bad", [-1.0, math.nan, math.inf, "2", True])
def test_bad_exponents_are_refused_naming_the_key(bad):
    with pytest.raises(ValueError, match=r"environment\.waves\.spreading: the spreading exponent"):
        check_exponent(bad, "environment.waves.spreading")
