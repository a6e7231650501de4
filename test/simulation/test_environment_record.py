"""allocator_pkg.simulation.environment_record: a record only where a spectrum is asked for, long
enough for the run, each column from its own source (and zero where the spec has none)."""

import numpy as np
import pytest

from allocator_pkg.hull.environment_loads import VesselParticulars
from allocator_pkg.simulation.environment import EnvironmentSpec, SlowVariation
from allocator_pkg.simulation.environment_record import RECORD_MARGIN, build_record

HULL = VesselParticulars(lpp=83.0, beam=18.0, draught=5.0, wind_area_frontal=230.0, wind_area_lateral=650.0,
                         wind_centre_x=8.0, underwater_centre_x=0.0)


def test_no_spectrum_no_record():
    assert build_record(EnvironmentSpec(wind_speed=10.0, wave_height=2.0), 1, HULL, 600.0, 0.0) is None


@pytest.mark.parametrize("duration", [30.0, 660.0, 3660.0])
def test_a_record_covers_the_run_and_its_warm_up(duration):
    record = build_record(EnvironmentSpec(wind_speed=10.0, wind_spectrum="npd"), 1, HULL, duration, 0.0)
    assert record.samples * record.step >= duration + RECORD_MARGIN
    assert record.samples * record.step < 2.0 * (duration + RECORD_MARGIN)


@pytest.mark.parametrize(("wind", "waves", "live"), [
    ("npd", "none", {"gust"}),
    ("first_order", "jonswap", {"drift", "north", "east", "yaw"}),
    ("api", "jonswap", {"gust", "wind_direction", "drift", "north", "east", "yaw"})])
def test_each_column_comes_from_its_source(wind, waves, live):
    spec = EnvironmentSpec(wind_speed=10.0, wind_direction=30.0, wind_spectrum=wind,
                           wind_direction_variation=SlowVariation(5.0 if wind == "api" else 0.0, 30.0),
                           wave_height=2.5, wave_period=8.0, wave_direction=30.0, wave_spectrum=waves)
    record = build_record(spec, 3, HULL, 600.0, 0.0)
    nonzero = {name for name in record.names if np.any(record.data[:, record.index[name]] != 0.0)}
    assert nonzero == live


def test_without_particulars_there_is_no_wave_motion():
    spec = EnvironmentSpec(wave_height=2.5, wave_period=8.0, wave_spectrum="jonswap")
    record = build_record(spec, 3, None, 600.0, 0.0)
    assert not np.any(record.data[:, [record.index[n] for n in ("north", "east", "yaw")]])
    assert np.mean(record.data[:-1, record.index["drift"]]) == pytest.approx(1.0)


TINY = VesselParticulars(lpp=0.01, beam=0.01, draught=0.01, wind_area_frontal=1.0, wind_area_lateral=1.0,
                         wind_centre_x=0.0, underwater_centre_x=0.0)
"""A hull that moves with the water at a point: the wave motion is the surface displacement."""


@pytest.mark.parametrize("n", [1.0, 2.0, 4.0, 10.0])
@pytest.mark.parametrize("seed", [1, 2])
def test_a_spread_sea_moves_the_hull_across_the_main_direction(n, seed):
    """Waves from north at heading 0 move a point hull along each component's direction, so the
    east (sway) variance over the north (surge) variance is E[sin^2] / E[cos^2] = 1 / (n + 1)
    of the cos^n spreading (within 15 %, the record's components being finite in number); a
    long-crested sea moves it north only."""
    spec = EnvironmentSpec(wave_height=2.5, wave_period=8.0, wave_spectrum="jonswap", wave_spreading=n)
    record = build_record(spec, seed, TINY, 3600.0, 0.0)
    north, east = (record.data[:, record.index[name]] for name in ("north", "east"))
    assert np.var(east) / np.var(north) == pytest.approx(1.0 / (n + 1.0), rel=0.15)
    long_crested = build_record(EnvironmentSpec(wave_height=2.5, wave_period=8.0, wave_spectrum="jonswap"), seed,
                                TINY, 3600.0, 0.0)
    assert np.all(long_crested.data[:, long_crested.index["east"]] == pytest.approx(0.0, abs=1e-12))
    drift = record.index["drift"]                  # the elevation's envelope at the origin: the same phases
    assert np.array_equal(long_crested.data[:, drift], record.data[:, drift])
