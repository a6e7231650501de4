"""Tables A-9 and A-10 of the DNV-ST-0111 Level 1 report: each thruster's power P_B r^(3/2) by
hand, each source the sum of its thrusters' shares, and on dp_vessel with skeg losses and a short
switchboard no source over its usable power in the balance's allocation (r over what a thruster
gives that way, the loss included)."""

import math

import pytest
import yaml
from conftest import ROOT

from allocator_pkg import read_parameters, vehicle_from_parameters
from allocator_pkg.dp.capability_result import INTACT
from allocator_pkg.dp.inputs.particulars import particulars_from_mapping
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.report.power_tables import A9_FIXED, A10_COLUMNS, a9_columns, table_a9, table_a10
from allocator_pkg.dp.report.tables import LOSS_COLUMNS, loss_sector_table

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"


@pytest.fixture(scope="module")
def lossy():
    """dp_vessel with a skeg 6.5 m forward of each azimuth, 3 m inboard (both azimuths lose thrust toward
    it, [3.11.5]), and the boards cut to 2500 and 4000 kW (2250 kW usable against 2071 + 2974.5 kW of
    thrusters, 3600 kW against 4033 + 2974.5 kW): (analysis, result, its allocations) at 30 deg. Were a rotatable
    thruster's fraction taken over its range without the loss, a board would draw up to 165 % here."""
    parameters = {**read_parameters(DP_VESSEL), "power.swbd_a.capacity": 2500.0, "power.swbd_b.capacity": 4000.0}
    data = {**yaml.safe_load(DP_PARTICULARS.read_text()), "skegs": [{"x": -35.0, "y": 4.0}, {"x": -35.0, "y": -4.0}]}
    analysis = Level1(vehicle_from_parameters(parameters), particulars_from_mapping(data))
    result = analysis.run(30.0)
    return analysis, result, result.allocations


@pytest.mark.slow
def test_the_skegs_give_loss_sectors_in_every_case(lossy):
    analysis, _, _ = lossy
    rows = [dict(zip(LOSS_COLUMNS, row)) for row in loss_sector_table(analysis)]
    assert {(row["case"], row["thruster"]) for row in rows if row["case"] == INTACT} == {
        (INTACT, "azimuth_stbd"), (INTACT, "azimuth_port")}
    for row in rows:
        profile = analysis.thrust_profiles(tuple(analysis.groups.get(row["case"], ())))[row["thruster"]]
        assert profile.factor(math.radians(row["at_deg"])) == pytest.approx(row["lowest_factor"], abs=1e-3)
        assert row["lowest_factor"] < 1.0 and row["from_deg"] < row["to_deg"] < row["from_deg"] + 360.0
        assert profile.factor(math.radians(row["from_deg"])) == pytest.approx(1.0, abs=1e-3)
        assert profile.factor(math.radians(row["to_deg"])) == pytest.approx(1.0, abs=1e-3)


def test_table_a9_is_p_b_r_to_the_three_halves_split_by_the_feeds(lossy):
    analysis, result, balanced = lossy
    columns = a9_columns(analysis)
    assert columns == (*A9_FIXED, "swbd_a_kw", "swbd_b_kw")
    feeds = {"azimuth_stbd": "swbd_a", "tunnel_fwd": "swbd_a", "azimuth_port": "swbd_b", "tunnel_aft": "swbd_b"}
    powers = {"azimuth_stbd": 2071.0, "azimuth_port": 4033.0, "tunnel_fwd": 2974.5, "tunnel_aft": 2974.5}
    rows = [dict(zip(columns, row)) for row in table_a9(analysis, result)]
    assert len(rows) == sum(len(uses) for *_, uses in balanced)
    for row in rows:
        assert 0.0 <= row["thrust_fraction"] <= 1.0 + 1e-9
        assert row["power_kw"] == pytest.approx(powers[row["thruster"]] * row["thrust_fraction"] ** 1.5)
        assert row[f"{feeds[row['thruster']]}_kw"] == row["power_kw"]


def test_table_a10_keeps_every_source_within_its_usable_power(lossy):
    analysis, result, _ = lossy
    a9 = [dict(zip(a9_columns(analysis), row)) for row in table_a9(analysis, result)]
    rows = [dict(zip(A10_COLUMNS, row)) for row in table_a10(analysis, result)]
    for row in rows:
        assert (row["reserved_kw"], row["usable_kw"]) == pytest.approx((0.1 * row["available_kw"],
                                                                         0.9 * row["available_kw"]))
        drawn = sum(line[f"{row['source']}_kw"] for line in a9
                    if (line["case"], line["heading_deg"]) == (row["case"], row["heading_deg"]))
        assert row["thrusters_kw"] == pytest.approx(drawn)
        assert row["utilisation_pct"] <= 100.0 + 1e-6          # the balance's allocation is within the power
    assert {row["source"] for row in rows if row["case"] == "switchboard_a"} == {"swbd_b"}   # a lost source: no row
    for source in ("swbd_a", "swbd_b"):                                                  # the short boards bind
        assert max(row["utilisation_pct"] for row in rows if row["source"] == source) > 95.0
