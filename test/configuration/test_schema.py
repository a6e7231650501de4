"""The schema is the single source of the configuration reference."""

from conftest import ROOT

from allocator_pkg import METHODS
from allocator_pkg.configuration import schema
from allocator_pkg.vehicle.config import METHOD_NAMES


def test_configuration_doc_is_generated_from_the_schema():
    text = (ROOT / "docs" / "configuration.md").read_text()
    assert schema.markdown_reference() in text, "docs/configuration.md is out of date: run `make docs`"


def test_every_actuator_type_has_its_keys():
    for kind in schema.ACTUATOR_TYPES:
        names = {key.name for key in schema.keys_for_type(kind)}
        assert {"type", "position", "weight", "power_coefficient"} <= names
    assert "azimuth_rate_max" in {k.name for k in schema.keys_for_type("azimuth_vertical")}
    assert "thrust_max" not in {k.name for k in schema.keys_for_type("fin")}
    assert "direction" not in {k.name for k in schema.keys_for_type("azimuth")}


def test_read_only_keys():
    read_only = {key.name for key in schema.VEHICLE_KEYS + schema.NODE_KEYS + schema.ACTUATOR_KEYS if key.read_only}
    assert read_only == {"actuators.names", "type", "link", "frame", "base_frame", "wrench_type", "geometry_source",
                         "robot_description_file", "executor", "power.sources", "power.bus_ties",
                         "redundancy_groups.names", "feeds", "feed_shares"}
    assert all(key.read_only for key in schema.SOURCE_KEYS + schema.GROUP_KEYS + schema.TIE_KEYS)


def test_every_key_says_what_it_accepts():
    """The text of ROS descriptors' additional_constraints: every key has one, dofs and forbidden_sectors too."""
    for key in schema.VEHICLE_KEYS + schema.NODE_KEYS + schema.ACTUATOR_KEYS + schema.SOURCE_KEYS + schema.GROUP_KEYS:
        assert key.documented_range(), key.name
    assert "each at most once" in schema.VEHICLE_KEY_BY_NAME["dofs"].documented_range()
    assert "[start, end] pairs" in schema.ACTUATOR_KEY_BY_NAME["forbidden_sectors"].documented_range()


def test_the_method_names_are_the_registered_methods():
    """The schema offers METHOD_NAMES without loading a method; they name the registry's entries."""
    assert schema.VEHICLE_KEY_BY_NAME["method"].choices == METHOD_NAMES
    assert tuple(METHODS) == METHOD_NAMES


def test_a_default_by_type_is_for_a_type_the_key_applies_to():
    keyed = [key for key in schema.ACTUATOR_KEYS if key.type_defaults]
    assert {key.name for key in keyed} == {"direction", "weight", "power_coefficient"}
    for key in keyed:
        assert set(key.type_defaults) <= set(key.applies_to), key.name
        assert key.default_for("no such type") is key.default is None
