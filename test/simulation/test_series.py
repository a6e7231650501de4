"""allocator_pkg.simulation.series: random-phase series whose Welch spectrum (scipy.signal.welch)
has the target's energy per frequency band within 10 %, wind and waves, through the environment's
record for the wind; reproducible from the seed; the record's look-up linear and periodic."""

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate, signal

from allocator_pkg.simulation import spectra
from allocator_pkg.simulation.environment import Environment, EnvironmentSpec
from allocator_pkg.simulation.series import Record, amplitudes, grid, real_series


def assert_bands(series, step, function, edges):
    """Welch's energy in the bins whose centres fall in each band against the target's integral
    over those bins."""
    f, density = signal.welch(series, fs=1.0 / step, nperseg=series.size // 4)
    width = f[1] - f[0]
    for low, high in itertools.pairwise(edges):
        bins = (f >= low) & (f < high)
        measured = density[bins].sum() * width
        expected = integrate.quad(function, f[bins][0] - width / 2, f[bins][-1] + width / 2, limit=200)[0]
        assert measured == pytest.approx(expected, rel=0.10), f"band {low:.4f} to {high:.4f} Hz"


@pytest.mark.parametrize("name", ["npd", "api", "harris"])
@pytest.mark.parametrize("speed", [8.0, 20.0, 32.0])
def test_the_environments_gust_has_its_spectrums_energy_per_band(name, speed):
    environment = Environment(EnvironmentSpec(wind_speed=speed, wind_spectrum=name), seed=4, duration=6000.0)
    record = environment.record
    gust = record.data[:-1, record.index["gust"]]
    edges = np.geomspace(0.01, 0.5, 7)
    assert_bands(gust, record.step, lambda f: float(spectra.wind_spectrum(name, np.array([f]), speed)[0]), edges)


@pytest.mark.parametrize(("hs", "tp"), [(1.3, 6.5), (4.2, 9.0), (9.5, 11.5)])
def test_a_jonswap_sea_has_its_spectrums_energy_per_band(hs, tp):
    n, df = grid(4000.0, 0.1)
    omega = 2.0 * math.pi * df * np.arange(n // 2 + 1)
    elevation = real_series(amplitudes(2.0 * math.pi * spectra.jonswap(omega, hs, tp), df,
                                       np.random.default_rng(9)), n)
    fp = 1.0 / tp
    edges = fp * np.array([0.6, 0.85, 0.95, 1.05, 1.2, 1.5, 2.0, 3.0])
    per_hz = lambda f: 2.0 * math.pi * float(spectra.jonswap(np.array([2.0 * math.pi * f]), hs, tp)[0])  # noqa: E731
    assert_bands(elevation, 0.1, per_hz, edges)
    assert np.var(elevation) == pytest.approx(hs * hs / 16.0, rel=0.03)


def test_the_same_seed_gives_the_same_series_and_another_seed_others():
    spec = EnvironmentSpec(wind_speed=15.0, wind_spectrum="npd", wave_height=3.0, wave_period=9.0,
                           wave_spectrum="jonswap")
    first, again, other = (Environment(spec, seed=s).record.data for s in (3, 3, 4))
    assert np.array_equal(first, again) and not np.array_equal(first, other)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.0, 1000.0), st.floats(0.05, 1.0))
def test_a_record_is_linear_between_samples_and_periodic(t, step):
    values = np.random.default_rng(1).standard_normal(64)
    record = Record(step, {"x": values, "twice": 2.0 * values})
    period = 64 * step
    expected = np.interp(t % period, step * np.arange(65), np.append(values, values[0]))
    assert record.at(t) == pytest.approx([expected, 2.0 * expected], abs=1e-9)
    assert record.at(t + period) == pytest.approx(record.at(t), abs=1e-9)


def test_a_record_needs_a_positive_duration_and_step():
    with pytest.raises(ValueError, match="duration and a step"):
        grid(0.0, 0.1)
