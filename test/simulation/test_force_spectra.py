"""allocator_pkg.simulation.force_spectra: each force spectrum's variance against what its
source gives independently: the gust's (2 F / U)^2 sigma_u^2 (sigma_u^2 by scipy's quad of the
spectrum), the drift's F^2 sigma^2 (first-order) or F^2 (Newman), the current's by the hull's
force at rest at the speed and direction one sigma off, swept over headings and spectra."""

import math

import numpy as np
import pytest
from scipy import integrate

from allocator_pkg.hull.environment_loads import VesselParticulars, wave_drift_load, wind_load
from allocator_pkg.simulation import spectra
from allocator_pkg.simulation.environment import EnvironmentSpec, SlowVariation
from allocator_pkg.simulation.force_spectra import force_spectrum
from allocator_pkg.simulation.frequency_domain import current_vector, rest_force
from allocator_pkg.simulation.vessel import Vessel

HULL = VesselParticulars(lpp=83.0, beam=18.0, draught=5.0, wind_area_frontal=230.0, wind_area_lateral=650.0,
                         wind_centre_x=8.0, underwater_centre_x=0.0)
OMEGA = np.concatenate([np.linspace(1e-6, 0.01, 20001)[:-1], np.linspace(0.01, 6.0, 60000)])


COARSE = np.linspace(1e-4, 6.0, 6000)


def variances(spec, heading=0.0, omega=OMEGA):
    return np.diagonal(np.trapezoid(force_spectrum(spec, HULL, Vessel(), omega, heading), omega, axis=0))


@pytest.mark.parametrize("name", ["npd", "api", "harris"])
@pytest.mark.parametrize("direction", [0.0, 60.0, 90.0, 200.0])
def test_the_gust_force_is_the_linearised_mean_wind_load(name, direction):
    speed = 18.0
    spec = EnvironmentSpec(wind_speed=speed, wind_direction=direction, wind_spectrum=name)
    sigma2 = integrate.quad(lambda f: float(spectra.wind_spectrum(name, np.array([f]), speed)[0]),
                            0.0, 6.0 / (2.0 * math.pi), limit=400)[0]
    mean = wind_load(HULL, speed, math.radians(direction))
    assert variances(spec) == pytest.approx((2.0 * mean / speed) ** 2 * sigma2, rel=0.02, abs=1.0)


@pytest.mark.parametrize(("hs", "tp"), [(2.1, 7.5), (5.7, 10.0)])
@pytest.mark.parametrize("direction", [0.0, 45.0, 135.0])
def test_the_drift_force_deviation_is_its_mean_with_newman_and_sigma_times_it_without(hs, tp, direction):
    mean = wave_drift_load(HULL, hs, tp, math.radians(direction))
    newman = EnvironmentSpec(wave_height=hs, wave_period=tp, wave_direction=direction, wave_spectrum="jonswap")
    assert np.sqrt(variances(newman, omega=COARSE)) == pytest.approx(np.abs(mean), rel=0.03, abs=1.0)
    first_order = EnvironmentSpec(wave_height=hs, wave_period=tp, wave_direction=direction,
                                  drift_variation=SlowVariation(0.3, 60.0))
    assert np.sqrt(variances(first_order, omega=COARSE)) == pytest.approx(0.3 * np.abs(mean), rel=0.01, abs=1.0)


@pytest.mark.parametrize("direction", [30.0, 90.0, 160.0])
def test_the_current_force_varies_with_its_speed_and_direction(direction):
    speed, speed_sigma, direction_sigma = 0.75, 0.02, 2.0
    spec = EnvironmentSpec(current_speed=speed, current_direction=direction,
                           current_speed_variation=SlowVariation(speed_sigma, 300.0),
                           current_direction_variation=SlowVariation(direction_sigma, 300.0))
    vessel, angle = Vessel(), math.radians(direction)
    by_speed = (rest_force(vessel, current_vector(speed + speed_sigma, angle))
                - rest_force(vessel, current_vector(speed - speed_sigma, angle))) / 2.0
    by_direction = (rest_force(vessel, current_vector(speed, angle + math.radians(direction_sigma)))
                    - rest_force(vessel, current_vector(speed, angle - math.radians(direction_sigma)))) / 2.0
    # the linearisation against one sigma off: the surge damping's blend is not quadratic
    assert variances(spec) == pytest.approx(by_speed ** 2 + by_direction ** 2, rel=0.05, abs=1.0)


def test_a_calm_environment_has_no_force_spectrum():
    assert not np.any(force_spectrum(EnvironmentSpec(), HULL, Vessel(), OMEGA[:100]))
