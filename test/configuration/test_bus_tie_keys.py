"""Bus-tie breakers of the vehicle file (configuration/bus_tie_keys.py): read into BusTie,
refused whole naming the key when they do not fit the sources; the reverse power coefficient and
the drive limit of a thruster read and checked (allocation/ for what they do)."""

import pytest
from conftest import ROOT

from allocator_pkg import ConfigError, read_parameters, vehicle_from_parameters
from allocator_pkg.configuration import schema
from allocator_pkg.vehicle.config import BusTie

PARAMETERS = read_parameters(ROOT / "config" / "dp_vessel.yaml")
TIE = {"power.bus_ties": ["bt_ab"], "power.bus_tie.bt_ab.sources": ["swbd_a", "swbd_b"]}


def test_a_tie_is_read_closed_unless_the_file_opens_it():
    assert vehicle_from_parameters({**PARAMETERS, **TIE}).bus_ties == (BusTie("bt_ab", ("swbd_a", "swbd_b"), True),)
    opened = vehicle_from_parameters({**PARAMETERS, **TIE, "power.bus_tie.bt_ab.closed": False})
    assert opened.bus_ties == (BusTie("bt_ab", ("swbd_a", "swbd_b"), False),)
    assert vehicle_from_parameters(PARAMETERS).bus_ties == ()


def test_the_schema_knows_the_tie_keys_beside_the_sources():
    vehicle = vehicle_from_parameters({**PARAMETERS, **TIE})
    names = {name for name, _ in schema.instance_keys(vehicle)}
    assert {"power.bus_tie.bt_ab.sources", "power.bus_tie.bt_ab.closed", "power.swbd_a.capacity"} <= names
    assert schema.key_for("power.bus_tie.bt_ab.closed") is schema.TIE_KEY_BY_NAME["closed"]
    assert schema.key_for("power.swbd_a.capacity") is schema.SOURCE_KEY_BY_NAME["capacity"]
    assert schema.key_for("power.bus_ties") is schema.VEHICLE_KEY_BY_NAME["power.bus_ties"]


def test_the_drive_keys_are_read():
    vehicle = vehicle_from_parameters({**PARAMETERS, "actuators.tunnel_fwd.reverse_power_coefficient": 0.015,
                                       "actuators.tunnel_fwd.drive_limit": 900.0})
    tunnel, azimuth = vehicle.actuator("tunnel_fwd"), vehicle.actuator("azimuth_stbd")
    assert (tunnel.reverse_power_coefficient, tunnel.drive_limit) == (0.015, 900.0)
    assert (azimuth.reverse_power_coefficient, azimuth.drive_limit) == (None, None)


WITHOUT_SOURCES = {k: v for k, v in PARAMETERS.items()
                   if not k.startswith(("power.", "redundancy_groups.")) and not k.endswith((".feeds", ".feed_shares"))}


@pytest.mark.parametrize(("changes", "key", "reason"), [
    ({**TIE, "power.bus_tie.bt_ab.sources": ["swbd_a", "swbd_c"]}, "power.bus_tie.bt_ab.sources",
     "swbd_c not in power.sources (swbd_a, swbd_b)"),
    ({**TIE, "power.bus_tie.bt_ab.sources": ["swbd_a", "swbd_a"]}, "power.bus_tie.bt_ab.sources",
     "joins swbd_a to itself"),
    ({**TIE, "power.bus_tie.bt_ab.sources": ["swbd_a"]}, "power.bus_tie.bt_ab.sources", "needs 2 elements, got 1"),
    ({"power.bus_ties": ["bt_ab"]}, "power.bus_tie.bt_ab.sources", "required key is missing"),
    ({**TIE, "power.bus_tie.bt_ab.closed": "yes"}, "power.bus_tie.bt_ab.closed", "expected true or false"),
    ({**TIE, "power.bus_ties": ["bt_ab", "bt_ba"], "power.bus_tie.bt_ba.sources": ["swbd_b", "swbd_a"]},
     "power.bus_tie.bt_ba.sources", "swbd_b and swbd_a are joined by bt_ab already"),
    ({**TIE, "power.bus_ties": ["bt_ab", "bt_ab"]}, "power.bus_ties", "duplicate name 'bt_ab'"),
    ({"power.bus_ties": ["swbd_a"]}, "power.bus_ties", "'swbd_a' is a power source's name"),
    ({"power.bus_ties": ["2ab"]}, "power.bus_ties", "'2ab' is not a valid name"),
    ({**TIE, "power.bus_tie.bt_cd.closed": True}, "power.bus_tie.bt_cd.closed", "'bt_cd' is not in power.bus_ties"),
    ({**TIE, "power.bus_tie.bt_ab.rating": 3.0}, "power.bus_tie.bt_ab.rating", "unknown key"),
    ({"actuators.tunnel_fwd.reverse_power_coefficient": -0.01}, "actuators.tunnel_fwd.reverse_power_coefficient",
     ">= 0"),
    ({"actuators.tunnel_fwd.drive_limit": 0.0}, "actuators.tunnel_fwd.drive_limit", "> 0"),
])
def test_tie_and_drive_keys_that_do_not_fit_are_refused_naming_the_key(changes, key, reason):
    with pytest.raises(ConfigError) as error:
        vehicle_from_parameters({**PARAMETERS, **changes})
    assert [name for name, _ in error.value.problems] == [key], error.value.problems
    assert reason in error.value.problems[0][1]


def test_ties_without_sources_are_refused():
    with pytest.raises(ConfigError) as error:
        vehicle_from_parameters({**WITHOUT_SOURCES, "power.bus_ties": ["bt_ab"]})
    assert error.value.problems == [("power.bus_ties", "a bus tie joins two of power.sources; there are none")]
