"""The particulars joined with the vehicle file: each thruster's D and duct given once, in either
file, or in both alike; a disagreement refused naming both keys."""

import pytest
import yaml
from conftest import ROOT

from allocator_pkg import read_parameters, vehicle_from_parameters
from allocator_pkg.configuration.file_keys import markdown_table
from allocator_pkg.dp.inputs.particulars import PARTICULARS_KEYS, particulars_from_mapping, with_vehicle_geometry
from allocator_pkg.dp.inputs.site import SITE_KEYS
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.level3.case import CRITERIA_KEYS

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"


def files(vehicle_changes: dict | None = None, **rows: dict):
    """dp_vessel's vehicle (with ``vehicle_changes``) and particulars (thruster rows updated by ``rows``)."""
    parameters = {**read_parameters(DP_VESSEL), **(vehicle_changes or {})}
    data = yaml.safe_load(DP_PARTICULARS.read_text())
    for name, changes in rows.items():
        data["thrusters"][name] = {**data["thrusters"][name], **changes}
    return vehicle_from_parameters(parameters), particulars_from_mapping(data)


def test_the_shipped_particulars_take_d_and_the_duct_from_the_vehicle_file():
    vehicle, particulars = files()
    given = particulars.thrusters["azimuth_stbd"]
    assert given.diameter is None and given.ducted is None
    joined = Level1(vehicle, particulars).particulars.thrusters
    assert (joined["azimuth_stbd"].diameter, joined["azimuth_stbd"].ducted) == (3.4, True)
    assert (joined["tunnel_fwd"].diameter, joined["tunnel_fwd"].ducted) == (2.2, False)


def test_the_same_value_in_both_files_is_one_definition():
    joined = with_vehicle_geometry(*reversed(files(azimuth_stbd={"diameter": 3.4, "ducted": True})))
    assert (joined.thrusters["azimuth_stbd"].diameter, joined.thrusters["azimuth_stbd"].ducted) == (3.4, True)


def test_the_particulars_alone_give_what_the_vehicle_file_leaves_out():
    vehicle, particulars = files({"actuators.azimuth_stbd.diameter": 0.0, "actuators.azimuth_stbd.ducted": False},
                                 azimuth_stbd={"diameter": 3.0, "ducted": False})
    joined = with_vehicle_geometry(particulars, vehicle).thrusters["azimuth_stbd"]
    assert (joined.diameter, joined.ducted) == (3.0, False)


@pytest.mark.parametrize("changes, rows, message", [
    ({}, {"azimuth_stbd": {"diameter": 3.0}},
     r"thrusters.azimuth_stbd.diameter and actuators.azimuth_stbd.diameter differ \(3 and 3.4 m\)"),
    ({}, {"azimuth_port": {"ducted": False}},
     "thrusters.azimuth_port.ducted and actuators.azimuth_port.ducted differ"),
    ({"actuators.azimuth_stbd.diameter": 0.0}, {},
     "thrusters.azimuth_stbd.diameter: missing, and the vehicle file gives no actuators.azimuth_stbd.diameter"),
    ({}, {"tunnel_fwd": {"kind": "shaft_line", "tunnel_inlet": None}},
     "thrusters.tunnel_fwd.kind: shaft_line, but the vehicle file's actuators.tunnel_fwd.tunnel is true"),
])
def test_a_disagreement_is_refused_naming_both_keys(changes, rows, message):
    vehicle, particulars = files(changes, **rows)
    with pytest.raises(ValueError, match=message):
        Level1(vehicle, particulars)


def test_dp_capability_doc_lists_the_particulars_and_site_keys():
    text = (ROOT / "docs" / "dp_capability.md").read_text()
    for keys in (PARTICULARS_KEYS, SITE_KEYS, CRITERIA_KEYS):
        assert markdown_table(keys) in text, "docs/dp_capability.md is out of date: run `make docs`"
