"""allocator_pkg.simulation.environment: seeded slow variations with the stated statistics,
directions as where the environment comes from, and the hull loads of environment_loads."""

import math

import numpy as np
import pytest
from scipy import integrate

from allocator_pkg.hull.environment_loads import VesselParticulars, wave_drift_load, wind_load
from allocator_pkg.simulation.environment import Environment, EnvironmentSpec, GaussMarkov, SlowVariation

HULL = VesselParticulars(lpp=83.0, beam=18.0, draught=5.0, wind_area_frontal=230.0, wind_area_lateral=650.0,
                         wind_centre_x=8.0, underwater_centre_x=0.0)


def test_a_current_from_the_north_flows_south():
    environment = Environment(EnvironmentSpec(current_speed=0.5, current_direction=0.0, current_down=0.1), seed=1)
    assert environment.current() == pytest.approx([-0.5, 0.0, 0.1])
    environment = Environment(EnvironmentSpec(current_speed=0.5, current_direction=90.0), seed=1)
    assert environment.current() == pytest.approx([0.0, -0.5, 0.0], abs=1e-12)


def test_steady_hull_load_is_wind_plus_wave_drift_of_environment_loads():
    spec = EnvironmentSpec(wind_speed=15.0, wind_direction=30.0, wave_height=3.0, wave_period=9.0, wave_direction=60.0)
    environment = Environment(spec, seed=3, particulars=HULL)
    heading = math.radians(20.0)
    expected = wind_load(HULL, 15.0, math.radians(10.0)) + wave_drift_load(HULL, 3.0, 9.0, math.radians(40.0))
    environment.step(0.1)
    assert environment.hull_load(heading) == pytest.approx(expected)
    assert Environment(spec, seed=3).hull_load(heading) == pytest.approx(np.zeros(3))


def test_gauss_markov_has_the_stated_deviation_and_correlation():
    process = GaussMarkov(SlowVariation(sigma=2.0, time_constant=10.0), np.random.default_rng(5))
    samples = np.array([process.step(1.0) for _ in range(200_000)])
    assert samples.std() == pytest.approx(2.0, rel=0.03)
    lag = np.corrcoef(samples[:-10], samples[10:])[0, 1]
    assert lag == pytest.approx(math.exp(-1.0), abs=0.03)       # correlation exp(-10 s / 10 s)


def test_the_same_seed_gives_the_same_weather_and_another_seed_other_weather():
    spec = EnvironmentSpec(current_speed=0.5, current_speed_variation=SlowVariation(0.1, 30.0), wind_speed=10.0,
                           gusts=SlowVariation(2.0, 5.0))

    def series(seed):
        environment = Environment(spec, seed=seed, particulars=HULL)
        rows = []
        for _ in range(50):
            environment.step(0.5)
            rows.append([*environment.current(), environment.wind_speed()])
        return np.array(rows)

    assert np.array_equal(series(7), series(7))
    assert not np.array_equal(series(7), series(8))


def test_bad_variations_are_refused():
    with pytest.raises(ValueError, match="sigma"):
        SlowVariation(sigma=-1.0)
    with pytest.raises(ValueError, match="time_constant"):
        SlowVariation(sigma=1.0, time_constant=0.0)


@pytest.mark.parametrize("heading", np.radians([0.0, 60.0, 135.0, 270.0]))
@pytest.mark.parametrize("name", ["npd", "api", "harris"])
def test_the_wind_feedforward_is_the_load_of_the_wind_measured_now(heading, name):
    spec = EnvironmentSpec(wind_speed=14.0, wind_direction=40.0, wind_spectrum=name,
                           wind_direction_variation=SlowVariation(6.0, 40.0))
    environment = Environment(spec, seed=5, particulars=HULL)
    for _ in range(37):
        environment.step(0.25)
    speed, direction = environment.wind_speed(), environment.wind_direction()
    assert speed != 14.0 and direction != 40.0
    expected = wind_load(HULL, speed, math.radians(direction) - heading)
    assert environment.wind_feedforward(heading) == pytest.approx(expected)
    assert environment.wind_load(heading) == pytest.approx(expected)


@pytest.mark.parametrize("scale", [0.5, 1.0, 1.5])
def test_given_mean_loads_scale_with_the_gust_and_the_drift_factor(scale):
    wind, drift = (1e4, -2e4, 3e5), (-5e3, 4e4, -6e5)
    spec = EnvironmentSpec(wind_speed=12.0, wind_spectrum="npd", wave_height=3.0, wave_period=9.0,
                           wave_spectrum="jonswap", mean_wind_load=wind, mean_drift_load=drift)
    environment = Environment(spec, seed=2, particulars=HULL)
    environment.scale = scale
    environment.step(3.0)
    ratio = (environment.wind_speed() / (12.0 * scale)) ** 2
    assert environment.wind_load(1.0) == pytest.approx(np.array(wind) * ratio * scale ** 2)
    assert environment.drift_load(1.0) == pytest.approx(np.array(drift) * environment.drift_factor() * scale ** 2)
    assert environment.hull_load(1.0, mean=True) == pytest.approx((np.array(wind) + drift) * scale ** 2)


def test_without_spectra_the_environment_draws_as_the_first_order_processes_do():
    """The current's, the gust's and the drift's processes from one generator in that order."""
    spec = EnvironmentSpec(current_speed=0.5, current_speed_variation=SlowVariation(0.1, 30.0), wind_speed=10.0,
                           gusts=SlowVariation(2.0, 5.0), wave_height=2.0, drift_variation=SlowVariation(0.3, 60.0))
    environment = Environment(spec, seed=11, particulars=HULL)
    generator = np.random.default_rng(11)
    processes = [GaussMarkov(v, generator) for v in (spec.current_speed_variation, spec.current_direction_variation,
                                                     spec.gusts, spec.drift_variation)]
    for _ in range(20):
        environment.step(0.5)
        values = [p.step(0.5) for p in processes]
    assert environment.record is None and not np.any(environment.wave_motion())
    assert environment.wind_speed() == pytest.approx(10.0 + values[2])
    assert environment.drift_factor() == pytest.approx(1.0 + values[3])


@pytest.mark.parametrize(("field", "value", "key"), [("wind_spectrum", "kaimal", "wind.spectrum"),
                                                      ("wave_spectrum", "pm", "waves.spectrum"),
                                                      ("peak_factor", 0.5, "waves.peak_factor")])
def test_a_spectrum_the_environment_does_not_know_is_refused_with_its_key(field, value, key):
    with pytest.raises(ValueError, match=f"environment.{key}"):
        EnvironmentSpec(**{field: value})


@pytest.mark.parametrize("n", [1.0, 2.0, 4.0, 15.0])
@pytest.mark.parametrize("waves", [0.0, 40.0, 90.0, 170.0, 250.0])
@pytest.mark.parametrize("heading", [0.0, 1.2])
def test_a_spread_seas_mean_drift_is_the_spreading_weighted_mean(n, waves, heading):
    """The hull's long-crested drift averaged over the directions by the cos^n spreading
    (scipy's quadrature of D(theta) F(beta + theta), D's Gamma-function normalisation written
    out), within 0.5 % of the largest component; scaled by the weather's scale squared."""
    spec = EnvironmentSpec(wave_height=3.0, wave_period=9.0, wave_direction=waves, wave_spreading=n)
    environment = Environment(spec, seed=1, particulars=HULL)
    relative = math.radians(waves) - heading
    weight = math.gamma(1.0 + n / 2.0) / (math.sqrt(math.pi) * math.gamma(0.5 + n / 2.0))
    expected = np.array([integrate.quad(
        lambda t, k=k: wave_drift_load(HULL, 3.0, 9.0, relative + t)[k] * weight * math.cos(t) ** n,
        -math.pi / 2.0, math.pi / 2.0, limit=200)[0] for k in range(3)])
    scale = np.abs(expected).max()
    assert environment.drift_load(heading, mean=True) == pytest.approx(expected, abs=5e-3 * scale)
    environment.scale = 1.5
    assert environment.drift_load(heading, mean=True) == pytest.approx(2.25 * expected, abs=1.2e-2 * scale)
