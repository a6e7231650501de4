"""allocator_pkg.simulation.scenario_values: the environment's spectrum keys read with their
defaults, a choice the key does not offer refused with the key."""

import pytest

from allocator_pkg.simulation.scenario_values import ScenarioError, environment
from allocator_pkg.simulation.spectra import WAVE_SPECTRA, WIND_SPECTRA


@pytest.mark.parametrize("wind", WIND_SPECTRA)
@pytest.mark.parametrize("waves", WAVE_SPECTRA)
def test_the_spectra_keys_are_read(wind, waves):
    spec = environment({"wind": {"speed": 10.0, "spectrum": wind, "direction_sigma": 4.0,
                                 "direction_time_constant": 30.0},
                        "waves": {"hs": 2.0, "spectrum": waves, "peak_factor": 2.5}})
    assert (spec.wind_spectrum, spec.wave_spectrum, spec.peak_factor) == (wind, waves, 2.5)
    assert (spec.wind_direction_variation.sigma, spec.wind_direction_variation.time_constant) == (4.0, 30.0)


def test_without_the_keys_the_first_order_environment_is_kept():
    spec = environment({"wind": {"speed": 10.0}, "waves": {"hs": 2.0}})
    assert (spec.wind_spectrum, spec.wave_spectrum, spec.peak_factor) == ("first_order", "none", 0.0)


@pytest.mark.parametrize(("section", "value"), [("wind", "kaimal"), ("waves", "bretschneider")])
def test_an_unknown_spectrum_is_refused_with_its_key(section, value):
    with pytest.raises(ScenarioError, match=rf"environment\.{section}\.spectrum: one of"):
        environment({section: {"spectrum": value}})
