"""The thrust bias keys of the vehicle file: read into BiasSettings (off unless set), refused
whole naming the key when a pair cannot push against itself, the thrust exceeds a paired
thruster's limit, the fade is upside down, or the method does not implement the bias."""

import math

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg import Allocator, ConfigError, read_parameters, vehicle_from_parameters
from allocator_pkg.effectiveness.thrust_bias import pair_direction, pair_wrench

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
PARAMETERS = read_parameters(DP_VESSEL)
BIAS_KEYS = [name for name in PARAMETERS if name.startswith("bias.")]


def problems(changes: dict) -> list[tuple[str, str]]:
    """What the configuration check says of dp_vessel's parameters with ``changes``."""
    with pytest.raises(ConfigError) as error:
        vehicle_from_parameters({**PARAMETERS, **changes})
    return error.value.problems


def test_a_file_without_the_keys_has_the_bias_off():
    vehicle = vehicle_from_parameters({k: v for k, v in PARAMETERS.items() if k not in BIAS_KEYS})
    assert BIAS_KEYS and vehicle.bias.enabled is False and vehicle.bias.pairs == ()
    bias = vehicle.bias
    assert (bias.thrust, bias.fade_start, bias.fade_end, bias.fade_time_constant) == (0.0, 0.03, 0.06, 60.0)


def test_the_keys_with_the_bias_off_do_not_change_the_allocation():
    with_keys = Allocator(vehicle_from_parameters(PARAMETERS))
    without = Allocator(vehicle_from_parameters({k: v for k, v in PARAMETERS.items() if k not in BIAS_KEYS}))
    for tau in ([1e4, 2e4, 0, 0, 0, 3e5], [1e5, 2e5, 0, 0, 0, 3e6], [-4e5, 1e5, 0, 0, 0, -1e6]):
        for _ in range(20):
            a, b = with_keys.allocate(np.array(tau, float)), without.allocate(np.array(tau, float))
            assert np.array_equal(a.thrust, b.thrust) and np.array_equal(a.azimuth, b.azimuth)


def test_dp_vessel_pairs_its_azimuths_with_the_bias_off():
    bias = vehicle_from_parameters(PARAMETERS).bias
    assert bias.pairs == (("azimuth_stbd", "azimuth_port"),) and bias.thrust == 60000.0 and not bias.enabled
    assert vehicle_from_parameters({**PARAMETERS, "bias.enabled": True}).bias.enabled


def test_each_azimuth_pushes_toward_the_other_and_the_pair_leaves_no_wrench_in_the_plane():
    vehicle = vehicle_from_parameters(PARAMETERS)
    stbd, port = vehicle.actuator("azimuth_stbd"), vehicle.actuator("azimuth_port")
    direction = pair_direction(stbd, port)
    assert direction == pytest.approx((0.0, -1.0))                  # starboard unit pushes to port
    wrench = pair_wrench(stbd, port, direction)
    assert wrench[[0, 1, 5]] == pytest.approx([0.0, 0.0, 0.0], abs=1e-12)
    assert wrench[3] == pytest.approx(0.0, abs=1e-12)               # one height: no roll either


@pytest.mark.parametrize("pairs, reason", [
    (["azimuth_stbd"], "even number"),
    (["azimuth_stbd", "bow"], "bow not in actuators.names"),
    (["azimuth_stbd", "tunnel_fwd"], "tunnel_fwd is a fixed actuator, not a rotatable thruster"),
    (["azimuth_stbd", "azimuth_stbd"], "cannot push against itself"),
    (["azimuth_stbd", "azimuth_port", "azimuth_port", "azimuth_stbd"], "in another pair already"),
])
def test_a_pair_that_cannot_push_against_itself_is_refused_naming_the_key(pairs, reason):
    found = problems({"bias.pairs": pairs})
    assert [name for name, _ in found] == ["bias.pairs"] and reason in found[0][1], found


def test_a_pair_whose_direction_lies_in_a_forbidden_sector_is_refused():
    found = problems({"actuators.azimuth_stbd.forbidden_sectors": [-1.83, -1.31]})
    assert found[0][0] == "bias.pairs" and "azimuth_stbd cannot push toward the other" in found[0][1]


def test_a_pair_at_different_heights_is_refused_when_roll_is_controlled():
    changed = {"actuators.azimuth_port.position": [-41.5, -7.0, 2.0]}
    vehicle_from_parameters({**PARAMETERS, **changed})                  # surge, sway, yaw: no wrench left
    found = problems({**changed, "dofs": ["surge", "sway", "roll", "yaw"]})
    assert found[0][0] == "bias.pairs" and "roll" in found[0][1], found


def test_pairs_of_different_planes_or_one_point_are_refused():
    found = problems({"actuators.azimuth_port.type": "azimuth_vertical"})
    assert ("bias.pairs", "pair (azimuth_stbd, azimuth_port): azimuth and azimuth_vertical thrusters turn in "
                          "different planes") in found
    found = problems({"actuators.azimuth_port.position": [-41.5, 7.0, 1.0]})
    assert found[0][0] == "bias.pairs" and "one point" in found[0][1]


@pytest.mark.parametrize("thrust", [420000.0, 5.0e5])
def test_a_thrust_beyond_a_paired_thruster_is_refused(thrust):
    found = problems({"bias.thrust": thrust})
    assert found == [("bias.thrust", f"{thrust:g} N is not below the thrust_max of azimuth_stbd (420000 N)")] + (
        [("bias.thrust", f"{thrust:g} N is not below the thrust_max of azimuth_port (655000 N)")]
        if thrust >= 655000.0 else [])


def test_enabled_needs_pairs_and_a_thrust_and_a_rising_fade():
    assert problems({"bias.enabled": True, "bias.thrust": 0.0}) == [
        ("bias.thrust", "must be above 0 with bias.enabled")]
    found = problems({"bias.enabled": True, "bias.pairs": []})
    assert [name for name, _ in found] == ["bias.enabled"]
    assert problems({"bias.fade_start": 0.3, "bias.fade_end": 0.2}) == [
        ("bias.fade_end", "0.2 must be above bias.fade_start (0.3)")]
    assert problems({"bias.thrust": -1.0})[0][0] == "bias.thrust"


def test_only_a_method_that_implements_the_bias_takes_it():
    vehicle = vehicle_from_parameters({**PARAMETERS, "bias.enabled": True})
    Allocator(vehicle)
    with pytest.raises(ConfigError) as error:
        Allocator(vehicle, method="lp")
    assert error.value.problems == [("bias.enabled", "method 'lp' does not implement thrust bias; methods that do: qp")]
    Allocator(vehicle_from_parameters(PARAMETERS), method="lp")      # configured but off: any method


def test_the_feasible_sector_bounds_the_direction():
    found = problems({"actuators.azimuth_port.azimuth_min": -math.pi / 4,
                      "actuators.azimuth_port.azimuth_max": math.pi / 4})
    assert found[0][0] == "bias.pairs" and "azimuth_port cannot push toward the other (at 90.0 deg" in found[0][1]
