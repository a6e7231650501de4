"""allocator_pkg.configuration.declared: the parameters a node holds, without ROS, are those
the running node holds (read from a node on each shipped vehicle, with an integer given for a
float key), and values are retyped as the node retypes them."""

import pytest
from conftest import ROOT

from allocator_pkg.configuration.declared import declared, declared_keys, typed_value
from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.configuration.params_file import read_parameters
from allocator_pkg.configuration.schema import VEHICLE_KEYS
from allocator_pkg.ros.ros_parameters import allocator_parameters


@pytest.mark.parametrize("vehicle", ["dp_vessel", "bluerov2_heavy", "example1_rov"])
def test_the_declared_parameters_are_those_the_node_holds(vehicle, allocator_harness):
    path = ROOT / "config" / f"{vehicle}.yaml"
    given = {**read_parameters(path), "weights.minimax": 3}
    harness = allocator_harness(path, parameters={"weights.minimax": 3})
    held = allocator_parameters(harness.node)
    assert declared(given, load_vehicle(path)) == held
    assert isinstance(held["weights.minimax"], float)


def test_every_key_of_the_vehicle_and_its_actuators_is_declared():
    vehicle = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
    names = [name for name, _ in declared_keys(vehicle)]
    assert len(names) == len(set(names))
    assert {key.name for key in VEHICLE_KEYS} <= set(names)
    assert "actuators.azimuth_port.thrust_rate_max" in names and "actuators.tunnel_fwd.thrust_max" in names


def test_a_value_is_retyped_as_the_node_retypes_it():
    assert typed_value("rate_hz", 25) == 25.0 and isinstance(typed_value("rate_hz", 25), float)
    assert typed_value("weights.slack", [1, 2, 3]) == [1.0, 2.0, 3.0]
    assert all(isinstance(v, float) for v in typed_value("weights.slack", [1, 2, 3]))
    assert typed_value("weights.slack", (1.0, 2.5)) == [1.0, 2.5]
    assert typed_value("solver.max_iter", 50) == 50 and isinstance(typed_value("solver.max_iter", 50), int)
    assert typed_value("per_actuator_topics", True) is True          # a bool is not an integer here
    assert typed_value("no_such_key", 3) == 3
