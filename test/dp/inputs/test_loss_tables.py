"""A vessel's own thrust-loss tables at Level 2: a direction table worked by hand on one azimuth
and against an independent search over the angles of two, the speed factor on a fixed thruster,
refusals naming the key, and the DP vessel without tables unchanged."""

import math
from dataclasses import replace

import numpy as np
import pytest
import yaml
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st
from test_thrust_profile import _search, _two_azimuths

from allocator_pkg import load_vehicle
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.dp.inputs.loss_tables import loss_tables
from allocator_pkg.dp.inputs.particulars import load_particulars, particulars_from_mapping
from allocator_pkg.dp.level2 import Level2
from allocator_pkg.dp.report.tables import loss_sector_table
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"
DIP = {"angle_deg": [-30.0, 60.0, 90.0, 120.0], "factor": [1.0, 1.0, 0.4, 1.0]}
"""A dip to 0.4 pushing to starboard, 1 outside 60-120 deg."""
ASTERN = {"angle_deg": [-170.0, 130.0, 175.0], "factor": [1.0, 1.0, 0.3]}
"""A dip to 0.3 pushing astern (175 deg), 1 outside 130-190 deg."""


def with_tables(tables: dict):
    return particulars_from_mapping({**yaml.safe_load(DP_PARTICULARS.read_text()),
                                     "level2": {"thrust_loss": tables}})


def test_the_direction_factor_is_linear_in_the_angle_and_periodic():
    table = loss_tables({"a": {"angle_deg": [10.0, 100.0, 250.0], "factor": [0.5, 1.0, 0.8]}})["a"]
    by_degrees = {10.0: 0.5, 55.0: 0.75, 100.0: 1.0, 175.0: 0.9, 250.0: 0.8,
                  310.0: 0.8 + (0.5 - 0.8) * 60.0 / 120.0, -50.0: 0.8 + (0.5 - 0.8) * 60.0 / 120.0, 370.0: 0.5}
    for degrees, expected in by_degrees.items():
        assert table.factor(math.radians(degrees)) == pytest.approx(expected, abs=1e-12)
    profile = table.profile()
    for angle, factor in profile.corners:                          # every corner on the linear table
        assert factor == pytest.approx(table.factor(angle), abs=1e-12)


@settings(max_examples=20, deadline=None)
@given(st.lists(st.tuples(st.floats(-180.0, 179.0), st.floats(0.05, 1.0)), min_size=2, max_size=8,
                unique_by=lambda row: round(row[0])),
       st.floats(-math.pi, math.pi))
def test_the_profile_follows_the_table_and_is_exact_at_the_rows_and_through(rows, through):
    rows = sorted((round(angle), factor) for angle, factor in rows)
    table = loss_tables({"a": {"angle_deg": [a for a, _ in rows], "factor": [f for _, f in rows]}})["a"]
    profile = table.profile((through,))
    if profile is None:
        assert all(factor == 1.0 for _, factor in rows)
        return
    for angle, factor in rows:
        assert profile.factor(math.radians(angle)) == pytest.approx(factor, abs=1e-9)
    assert profile.factor(through) == pytest.approx(table.factor(through), abs=1e-9)
    drawn, linear = zip(*((profile.factor(a), table.factor(a)) for a in np.linspace(-math.pi, math.pi, 241)))
    assert max(np.subtract(drawn, linear)) < 1e-9                 # chords inside the convex spiral
    assert max(np.subtract(linear, drawn)) < 5e-3


def test_one_azimuth_reaches_the_table_worked_by_hand():
    """azimuth_stbd (420 kN) alone at the origin, surge and sway: along 90 deg the dip's 0.4, so
    168 kN; along 75 deg halfway down the 60-90 deg ramp, 0.7, so 294 kN (a corner of the chords
    drawn every 1 deg); along 0 deg the full 420 kN."""
    vehicle = _two_azimuths()
    single = replace(vehicle, actuators=(replace(vehicle.actuators[0], position=(0.0, 0.0, 4.5)),),
                     dofs=("surge", "sway"))
    profile = loss_tables({"azimuth_stbd": DIP})["azimuth_stbd"].profile()
    capability = Capability(single, "qp", speed=0.0, profiles={"azimuth_stbd": profile})
    assert capability.max_force(math.radians(90.0)) == pytest.approx(168e3, rel=1e-6)
    assert capability.max_force(math.radians(75.0)) == pytest.approx(294e3, rel=1e-4)
    assert capability.max_force(0.0) == pytest.approx(420e3, rel=1e-4)      # the circle: the programme's polygon


def test_two_azimuths_with_a_table_match_a_search_over_angles():
    vehicle = _two_azimuths()
    table = loss_tables({"azimuth_stbd": ASTERN})["azimuth_stbd"]
    capability = Capability(vehicle, "qp", speed=0.0, profiles={"azimuth_stbd": table.profile()})
    plain = Capability(vehicle, "qp", speed=0.0)
    lowered = 0
    for degrees in range(0, 360, 15):
        direction = math.radians(degrees)
        found = capability.max_force(direction)
        assert found == pytest.approx(_search(vehicle, [table.factor, lambda _: 1.0], direction), rel=2e-3, abs=1.0)
        lowered += found < 0.99 * plain.max_force(direction)
    assert lowered > 0                                             # the dip bites somewhere


def test_level_2_takes_a_fixed_thrusters_direction_and_speed_tables():
    """tunnel_fwd pushes along 90 deg (and reversed along 270 deg): factors 0.8 and 0.6 there; in
    a current of 0.75 m/s halfway between 1 at 0.5 m/s and 0.5 at 1 m/s, 0.75; held at 0.5 above."""
    particulars = with_tables({"tunnel_fwd": {"angle_deg": [0.0, 90.0, 180.0, 270.0], "factor": [1.0, 0.8, 1.0, 0.6],
                                              "speed": [0.5, 1.0], "speed_factor": [1.0, 0.5]}})
    level2 = Level2(load_vehicle(DP_VESSEL), particulars)
    condition = replace(WEATHER_CONDITIONS[6], current=0.75)
    assert level2.thrust_range("tunnel_fwd", condition, 1.0) == pytest.approx((-225e3, 225e3), rel=1e-12)
    assert level2.thrust_range("tunnel_fwd", replace(condition, current=2.0), 1.0) == pytest.approx((-150e3, 150e3))
    assert level2.thrust_range("tunnel_fwd", replace(condition, current=0.2), 1.0) == (-300e3, 300e3)
    assert level2.thrust_range("tunnel_aft", condition, 1.0) == (-300e3, 300e3)
    tunnel = {a.name: a for a in level2.variant(condition, 1.0).actuators}["tunnel_fwd"]
    assert (tunnel.thrust_min, tunnel.thrust_max) == pytest.approx((-225e3 * 0.6, 225e3 * 0.8), rel=1e-12)
    assert "tunnel_fwd" not in level2.thrust_profiles(("tunnel_fwd",))
    rows = [row for row in loss_sector_table(level2) if row[1] == "tunnel_fwd"]
    assert [(round(r[2]), round(r[3]), r[4], round(r[5])) for r in rows[:2]] == [(0, 180, 0.8, 90),
                                                                                 (180, 360, 0.6, -90)]
    notes = "\n".join(level2.notes())
    assert "tunnel_fwd over the thrust direction (4 rows, lowest 0.600 at 270.0 deg) and over the current speed" \
        in notes


def test_an_azimuths_table_is_its_profile_in_the_balance():
    level2 = Level2(load_vehicle(DP_VESSEL), with_tables({"azimuth_stbd": DIP}))
    profile = level2.thrust_profiles()["azimuth_stbd"]
    assert profile.factor(math.radians(90.0)) == pytest.approx(0.4)
    variant = level2.variant(WEATHER_CONDITIONS[6], 1.0)
    assert level2.capability(variant).profiles["azimuth_stbd"] is profile


@pytest.mark.parametrize(("tables", "message"), [
    ({"bow_thruster": DIP}, r"level2\.thrust_loss\.bow_thruster: no thruster of that name"),
])
def test_a_table_of_an_unknown_thruster_is_refused(tables, message):
    with pytest.raises(ValueError, match=message):
        Level2(load_vehicle(DP_VESSEL), with_tables(tables))


@pytest.mark.parametrize(("row", "message"), [
    ({"angle_deg": [0, 90], "factor": [1.0, 1.2]}, r"thrust_loss\.t\.factor: each in \[0, 1\]"),
    ({"angle_deg": [0, 90, 180], "factor": [1.0, 0.5]}, r"thrust_loss\.t: angle_deg and factor need one value per row"),
    ({"angle_deg": [0, 360], "factor": [1.0, 0.5]}, r"thrust_loss\.t\.angle_deg: spanning less than 360"),
    ({"angle_deg": [90, 0], "factor": [1.0, 0.5]}, r"thrust_loss\.t\.angle_deg: strictly increasing"),
    ({"angle_deg": [0, 90, 180], "factor": [0.0, 0.0, 1.0]}, r"thrust_loss\.t\.factor: no two neighbouring rows at 0"),
    ({"angle_deg": [0, 90]}, r"thrust_loss\.t: angle_deg and factor go together"),
    ({"speed": [-1, 1], "speed_factor": [1, 0.5]}, r"thrust_loss\.t\.speed: at least 0"),
    ({"speed": [0, 1], "speed_factor": [1, "x"]}, r"thrust_loss\.t\.speed_factor: a list of at least two"),
    ({"speed": [0, 1], "speed_factor": [1, 0.5], "rpm": [1]}, r"thrust_loss\.t: a mapping with angle_deg"),
])
def test_bad_tables_are_refused_naming_the_key(row, message):
    with pytest.raises(ValueError, match=message):
        with_tables({"t": row})


@pytest.mark.slow
def test_the_dp_vessel_without_tables_is_unchanged():
    particulars = load_particulars(DP_PARTICULARS)
    assert particulars.thrust_loss == {}
    level2 = Level2(load_vehicle(DP_VESSEL), particulars)
    assert level2.thrust_profiles() == {} and loss_sector_table(level2) == []
    assert "(level2.thrust_loss): none; every thruster the vehicle file's thrust limits" in "\n".join(level2.notes())
    assert level2.run().summary_line() == "DP capability-L2(11, 10, 8, 7)"
