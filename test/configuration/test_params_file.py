"""ROS 2 params files: read as rcl reads them, sections matched as rcl matches them, and
flat parameters written back."""

import textwrap

import pytest
from conftest import ROOT

from allocator_pkg import ConfigError, load_vehicle, read_parameters
from allocator_pkg.configuration.params_file import params_text, section_matches, write_parameters


def write(tmp_path, text):
    path = tmp_path / "vehicle.yaml"
    path.write_text(textwrap.dedent(text))
    return path


def test_params_file_reads_like_rcl(tmp_path):
    path = write(tmp_path, """
        /robot/thrust_allocator:
          ros__parameters:
            weights:
              slack: [1e6, 1.0e+6]
            dofs: [surge, yaw]
            actuators:
              names: [a]
              a: {type: fixed, position: [0.0, 0.5, 0.0], direction: [1.0, 0.0, 0.0], thrust_max: 1.0,
                  command_max: 1e3}
              b: {}
        """)
    parameters = read_parameters(path)
    assert parameters["weights.slack"] == [1e6, 1e6]            # 1e6 is a float, as rcl reads it
    assert "actuators.b" not in parameters
    vehicle = load_vehicle(path, node_name="thrust_allocator")
    assert vehicle.weights.slack == (1e6, 1e6)


def test_params_file_errors(tmp_path):
    with pytest.raises(ConfigError, match="a ROS parameter list holds one type"):
        load_vehicle(write(tmp_path, """
            n:
              ros__parameters:
                actuators:
                  names: [a]
                  a: {type: fixed, position: [1, 0.5, 0], direction: [1.0, 0.0, 0.0], thrust_max: 1.0}
            """))
    with pytest.raises(ConfigError, match="not valid YAML"):
        load_vehicle(write(tmp_path, "n: [unclosed"))
    with pytest.raises(ConfigError, match="ros__parameters"):
        load_vehicle(write(tmp_path, "n: {rate_hz: 5}"))
    with pytest.raises(ConfigError, match="cannot read"):
        load_vehicle(tmp_path / "missing.yaml")
    with pytest.raises(ConfigError, match="no section for node 'other'"):
        load_vehicle(write(tmp_path, "/rov1/thrust_allocator: {ros__parameters: {rate_hz: 5}}"), node_name="other")


@pytest.mark.parametrize(("section", "node", "applies"), [
    ("/**", "/rov1/thrust_allocator", True),
    ("/**/thrust_allocator", "/rov1/thrust_allocator", True),
    ("/**/thrust_allocator", "/thrust_allocator", True),
    ("/**/thrust_allocator", "/rov1/alloc", False),
    ("thrust_allocator", "/thrust_allocator", True),
    ("thrust_allocator", "/rov1/thrust_allocator", False),          # a namespace the pattern does not cover
    ("/rov*/thrust_allocator", "/rov1/thrust_allocator", True),
    ("/rov*/thrust_allocator", "/fleet/rov1/thrust_allocator", False),
    ("/robot/thrust_allocator", "thrust_allocator", True),            # a name alone: any namespace
])
def test_sections_apply_to_nodes_as_rcl_matches_them(section, node, applies):
    assert section_matches(section, node) == applies


def test_shipped_files_apply_to_any_node_name():
    for path in (ROOT / "config").glob("*.yaml"):
        assert read_parameters(path, "/rov1/alloc") == read_parameters(path), path


def test_empty_list_means_not_set(tmp_path):
    # rcl reads [] as "not set": the required key is then missing.
    with pytest.raises(ConfigError, match=r"actuators\.names: required"):
        load_vehicle(write(tmp_path, """
            n:
              ros__parameters:
                actuators:
                  names: []
            """))


def test_flat_parameters_written_read_back_the_same(tmp_path):
    for path in (ROOT / "config").glob("*.yaml"):
        flat = read_parameters(path)
        assert read_parameters(write_parameters(tmp_path / path.name, flat)) == flat, path
    assert params_text({"dofs": ["surge"], "actuators.a.gain": 2.0}) == \
        "/**:\n  ros__parameters:\n    dofs:\n    - surge\n    actuators:\n      a:\n        gain: 2.0\n"
