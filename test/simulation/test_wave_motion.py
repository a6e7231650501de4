"""allocator_pkg.simulation.wave_motion: the water's displacement averaged over the hull, against
numerical averages of the displacement field (numpy) over a sweep of directions and frequencies,
its long-wave limit and the environment's motion series."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg.hull.environment_loads import GRAVITY, VesselParticulars
from allocator_pkg.simulation import spectra
from allocator_pkg.simulation.environment import Environment, EnvironmentSpec
from allocator_pkg.simulation.wave_motion import to_ned, transfer

HULL = VesselParticulars(lpp=83.0, beam=18.0, draught=5.0, wind_area_frontal=230.0, wind_area_lateral=650.0,
                         wind_centre_x=8.0, underwater_centre_x=0.0)


def field_average(omega, direction, length, beam):
    """Surge, sway and yaw of the displacement field sampled over the waterplane: the mean and the
    least-squares slope along x (numpy.polyfit) of -i exp(-i k p.r) along p."""
    k = omega * omega / GRAVITY
    px, py = -math.cos(direction), -math.sin(direction)
    x, y = np.meshgrid(np.linspace(-length / 2, length / 2, 801), np.linspace(-beam / 2, beam / 2, 201))
    shift = -1j * np.exp(-1j * k * (px * x + py * y))
    mean = np.trapezoid(np.trapezoid(shift, axis=0) / 200, axis=0) / 800
    along = np.trapezoid(shift, axis=0) / 200                       # averaged over the beam, per x
    slope = np.polyfit(x[0], along.real, 1)[0] + 1j * np.polyfit(x[0], along.imag, 1)[0]
    return np.array([px * mean, py * mean, py * slope])


@settings(max_examples=40, deadline=None)
@given(st.floats(0.2, 2.0), st.floats(-math.pi, math.pi))
def test_the_transfer_is_the_fields_average_over_the_hull(omega, direction):
    expected = field_average(omega, direction, 83.0, 18.0)
    assert transfer(np.array([omega]), direction, 83.0, 18.0)[:, 0] == pytest.approx(expected, abs=2e-3)


@pytest.mark.parametrize("direction", np.radians([0.0, 30.0, 90.0, 150.0, 180.0, 270.0]))
def test_long_waves_move_the_hull_as_the_water(direction):
    surge, sway, yaw = transfer(np.array([0.01]), direction, 83.0, 18.0)[:, 0]
    assert abs(surge) == pytest.approx(abs(math.cos(direction)), abs=1e-6)
    assert abs(sway) == pytest.approx(abs(math.sin(direction)), abs=1e-6)
    assert abs(yaw) < 1e-4


def test_head_seas_move_the_hull_only_in_surge_and_to_ned_turns_by_the_heading():
    surge, sway, yaw = transfer(np.linspace(0.2, 2.0, 10), 0.0, 83.0, 18.0)
    assert np.all(np.abs(sway) < 1e-12) and np.all(np.abs(yaw) < 1e-12) and np.all(np.abs(surge) > 0.0)
    north, east = to_ned(np.array([1.0]), np.array([0.0]), math.radians(90.0))
    assert (north[0], east[0]) == pytest.approx((0.0, 1.0), abs=1e-12)


@pytest.mark.parametrize("direction", [0.0, 45.0, 90.0])
def test_the_environments_wave_motion_has_the_variance_of_its_transfer(direction):
    spec = EnvironmentSpec(wave_height=3.1, wave_period=8.5, wave_direction=direction, wave_spectrum="jonswap")
    environment = Environment(spec, seed=2, particulars=HULL, duration=6000.0)
    motion = []
    for _ in range(20000):
        environment.step(0.3)
        motion.append(environment.wave_motion())
    omega = np.linspace(0.05, 4.0, 4000)
    gain = np.abs(transfer(omega, math.radians(direction), HULL.lpp, HULL.beam)) ** 2
    expected = np.sqrt(np.trapezoid(gain * spectra.jonswap(omega, 3.1, 8.5), omega, axis=1))
    north, east = to_ned(expected[0], expected[1], 0.0)
    assert np.std(motion, axis=0) == pytest.approx([abs(north), abs(east), expected[2]], rel=0.1, abs=1e-3)
    assert not np.any(Environment(EnvironmentSpec(wave_height=3.1), seed=2, particulars=HULL).wave_motion())
