"""allocator_pkg.simulation.environment: seeded slow variations with the stated statistics,
directions as where the environment comes from, and the hull loads of environment_loads."""

import math

import numpy as np
import pytest

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
