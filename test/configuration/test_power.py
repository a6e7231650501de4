"""Power sources, feeds and redundancy groups of the vehicle file: read into PowerSource and
RedundancyGroup, refused naming the key when they do not fit together; at their capacities
(which exceed what dp_vessel's thrusters can draw) the allocation is that of the vehicle without
them (allocation/power_budget.py and test_power_budget.py for the rest)."""

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg import Allocator, ConfigError, read_parameters, vehicle_from_parameters
from allocator_pkg.configuration import schema
from allocator_pkg.vehicle.config import PowerSource, RedundancyGroup

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
PARAMETERS = read_parameters(DP_VESSEL)
POWER_KEYS = [name for name in PARAMETERS if name.startswith(("power.", "redundancy_groups."))
              or name.endswith((".feeds", ".feed_shares"))]


def test_dp_vessel_has_two_switchboards_and_two_groups():
    vehicle = vehicle_from_parameters(PARAMETERS)
    assert vehicle.power_sources == (PowerSource("swbd_a", 5600.0), PowerSource("swbd_b", 7800.0))
    assert vehicle.redundancy_groups == (
        RedundancyGroup("switchboard_a", ("swbd_a",), ("azimuth_stbd", "tunnel_fwd")),
        RedundancyGroup("switchboard_b", ("swbd_b",), ("azimuth_port", "tunnel_aft")))
    assert {a.name: (a.feeds, a.feed_shares) for a in vehicle.actuators} == {
        "azimuth_stbd": (("swbd_a",), (1.0,)), "azimuth_port": (("swbd_b",), (1.0,)),
        "tunnel_fwd": (("swbd_a",), (1.0,)), "tunnel_aft": (("swbd_b",), (1.0,))}


def test_at_their_capacities_the_keys_do_not_change_the_allocation():
    with_power = Allocator(vehicle_from_parameters(PARAMETERS))
    without = Allocator(vehicle_from_parameters({k: v for k, v in PARAMETERS.items() if k not in POWER_KEYS}))
    assert POWER_KEYS and without.vehicle.power_sources == ()
    for tau in ([1e5, 2e5, 0, 0, 0, 3e6], [-4e5, 1e5, 0, 0, 0, -1e6]):
        a, b = with_power.allocate(np.array(tau, float)), without.allocate(np.array(tau, float))
        assert np.array_equal(a.thrust, b.thrust) and np.array_equal(a.azimuth, b.azimuth)


def test_the_schema_knows_every_instance_key():
    vehicle = vehicle_from_parameters(PARAMETERS)
    names = {name for name, _ in schema.instance_keys(vehicle)}
    assert {"power.swbd_a.capacity", "redundancy_groups.switchboard_b.sources",
            "redundancy_groups.switchboard_b.actuators", "actuators.tunnel_fwd.feeds",
            "actuators.tunnel_fwd.feed_shares"} <= names
    assert schema.key_for("power.swbd_a.capacity").unit == "kW"
    assert schema.key_for("redundancy_groups.x.actuators") is schema.GROUP_KEY_BY_NAME["actuators"]
    assert schema.key_for("power.sources") is schema.VEHICLE_KEY_BY_NAME["power.sources"]


SPLIT = {"actuators.tunnel_fwd.feeds": ["swbd_a", "swbd_b"], "actuators.tunnel_fwd.feed_shares": [0.4, 0.6]}


def test_a_split_feed_is_read_in_feeds_order():
    vehicle = vehicle_from_parameters({**PARAMETERS, **SPLIT})
    tunnel = vehicle.actuator("tunnel_fwd")
    assert tunnel.feeds == ("swbd_a", "swbd_b") and tunnel.feed_shares == (0.4, 0.6)


@pytest.mark.parametrize(("changes", "key", "reason"), [
    ({"redundancy_groups.switchboard_a.actuators": ["azimuth_stbd", "tunnel_fwd", "tunnel_bow"]},
     "redundancy_groups.switchboard_a.actuators", "tunnel_bow not in actuators.names"),
    ({"redundancy_groups.switchboard_a.sources": ["swbd_c"]}, "redundancy_groups.switchboard_a.sources",
     "swbd_c not in power.sources"),
    ({"actuators.tunnel_fwd.feeds": None}, "actuators.tunnel_fwd.feeds", "required with power.sources"),
    ({"actuators.tunnel_fwd.feeds": ["swbd_c"]}, "actuators.tunnel_fwd.feeds", "swbd_c not in power.sources"),
    ({**SPLIT, "actuators.tunnel_fwd.feed_shares": [0.4, 0.5]}, "actuators.tunnel_fwd.feed_shares",
     "the shares sum to 0.9, not 1"),
    ({**SPLIT, "actuators.tunnel_fwd.feed_shares": None}, "actuators.tunnel_fwd.feed_shares",
     "one share per feed (2: swbd_a, swbd_b); got 0"),
    ({"redundancy_groups.switchboard_a.actuators": ["azimuth_stbd"]}, "redundancy_groups.switchboard_a.actuators",
     "the group loses every feed of tunnel_fwd (swbd_a): list it"),
    ({"power.sources": ["swbd_a", "swbd_b", "tunnel_fwd"]}, "power.sources", "'tunnel_fwd' is an actuator's name"),
    ({"power.swbd_a.capacity": None}, "power.swbd_a.capacity", "required key is missing"),
    ({"power.swbd_a.capacity": 0.0}, "power.swbd_a.capacity", "> 0"),
    ({"power.swbd_c.capacity": 100.0}, "power.swbd_c.capacity", "'swbd_c' is not in power.sources"),
    ({"redundancy_groups.engine_room.actuators": ["tunnel_fwd"]}, "redundancy_groups.engine_room.actuators",
     "'engine_room' is not in redundancy_groups.names"),
    ({"redundancy_groups.names": ["switchboard_a", "switchboard_b", "empty"]}, "redundancy_groups.empty.actuators",
     "a group loses at least one actuator or source"),
])
def test_power_keys_that_do_not_fit_are_refused_naming_the_key(changes, key, reason):
    with pytest.raises(ConfigError) as error:
        vehicle_from_parameters({**PARAMETERS, **changes})
    assert [name for name, _ in error.value.problems] == [key], error.value.problems
    assert reason in error.value.problems[0][1]


def test_the_node_declares_the_keys_of_each_source_and_group(ros_context):
    from rclpy.node import Node

    from allocator_pkg.ros.ros_parameters import declare

    vehicle = vehicle_from_parameters(PARAMETERS)
    node = Node("power_keys", context=ros_context)
    try:
        declare(node, vehicle)
        for name in ("power.sources", "power.swbd_b.capacity", "redundancy_groups.switchboard_a.actuators",
                     "redundancy_groups.switchboard_a.sources", "actuators.azimuth_port.feeds"):
            assert node.has_parameter(name), name
            description = node.describe_parameter(name)
            assert description.read_only and description.description, name
        assert "[kW]" in node.describe_parameter("power.swbd_b.capacity").description
    finally:
        node.destroy_node()
