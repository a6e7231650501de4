"""DP capability Level 2 as read here: the vessel's coefficient tables give the loads (the
standard's formulas when sampled from them), the vehicle file's thrust limits and sectors replace
[3.9] and [3.11.3], a sector lifts with the thruster it protects, and --dnv-level2 writes the
report with Level 1 against Level 2."""

import math
from dataclasses import replace

import numpy as np
import pytest
import yaml
from conftest import ROOT

from allocator_pkg import load_vehicle, read_parameters, vehicle_from_parameters
from allocator_pkg.cli.allocator_capability import main
from allocator_pkg.dp.capability_result import SCOPE_L2, WORST
from allocator_pkg.dp.inputs.coefficients import coefficient_table
from allocator_pkg.dp.inputs.particulars import load_particulars, particulars_from_mapping
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.level2 import Level2
from allocator_pkg.dp.standard.loads import current_load, wave_drift_load, wind_load
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"
PARTICULARS = load_particulars(DP_PARTICULARS)
HEADINGS = list(range(0, 360, 30))


def sampled(load, area_x, area_y, lpp):
    """The coefficients of a formula of the standard at HEADINGS (unit speed, unit pressure)."""
    rows = [load(math.radians(h)) for h in HEADINGS]
    return coefficient_table({"heading_deg": HEADINGS, "cx": [r[0] / area_x for r in rows],
                              "cy": [r[1] / area_y for r in rows], "cn": [r[2] / (area_y * lpp) for r in rows]}, "t")


def test_coefficients_sampled_from_the_formulas_give_level_1_loads_at_their_rows():
    hull = PARTICULARS.hull
    wind = sampled(lambda d: wind_load(hull, math.sqrt(2 / 1.226), d), hull.wind_area_frontal,
                   hull.wind_area_lateral, hull.lpp)
    current = sampled(lambda d: current_load(hull, math.sqrt(2 / 1026.0), d), hull.beam * hull.draught,
                      hull.current_area_lateral, hull.lpp)
    particulars = replace(PARTICULARS, wind_coefficients=wind, current_coefficients=current)
    level2 = Level2(load_vehicle(DP_VESSEL), particulars)
    level1 = Level1(load_vehicle(DP_VESSEL), PARTICULARS)
    for heading in HEADINGS:
        for condition in WEATHER_CONDITIONS[1::3]:
            d = math.radians(heading)
            two, one = level2.standard_loads(condition, d), level1.standard_loads(condition, d)
            for source in ("wind", "current"):
                np.testing.assert_allclose(two[source], one[source], rtol=1e-9, atol=1e-6)
            waves = wave_drift_load(PARTICULARS.hull, condition.hs, condition.tp, d)
            np.testing.assert_array_equal(two["waves"], waves)
            np.testing.assert_allclose(level2.loads(condition, d).total, level1.loads(condition, d).total,
                                       rtol=1e-9, atol=1e-6)


def test_without_tables_the_loads_are_level_1s():
    level2, level1 = Level2(load_vehicle(DP_VESSEL), PARTICULARS), Level1(load_vehicle(DP_VESSEL), PARTICULARS)
    for key, value in level1.standard_loads(WEATHER_CONDITIONS[6], 1.0).items():
        np.testing.assert_array_equal(level2.standard_loads(WEATHER_CONDITIONS[6], 1.0)[key], value)


def test_thrust_is_the_vehicle_files_and_a_lost_feed_share_derates_it():
    level2 = Level2(load_vehicle(DP_VESSEL), PARTICULARS)
    assert level2.thrust_range("azimuth_port", WEATHER_CONDITIONS[9], 1.0) == (0.0, 655000.0)
    assert level2.thrust_range("tunnel_aft", WEATHER_CONDITIONS[9], 1.0) == (-300000.0, 300000.0)
    # swbd_a (5040 kW usable) is short of the 5045.5 kW its thrusters draw at full thrust: that is the
    # balance's power row [3.12]; the range stays the vehicle file's.
    assert level2.thrust_range("tunnel_fwd", WEATHER_CONDITIONS[9], 1.0) == (-300000.0, 300000.0)
    assert level2.power_limits().sources == ("swbd_a",)
    split = {**read_parameters(DP_VESSEL), "actuators.tunnel_fwd.feeds": ["swbd_a", "swbd_b"],
             "actuators.tunnel_fwd.feed_shares": [0.25, 0.75],
             "redundancy_groups.switchboard_a.actuators": ["azimuth_stbd"]}
    level2 = Level2(vehicle_from_parameters(split), PARTICULARS)
    low, high = level2.thrust_range("tunnel_fwd", WEATHER_CONDITIONS[9], 1.0, level2.groups["switchboard_a"])
    # It keeps the 0.75 share of swbd_b: 0.75^(2/3) = 0.82548 of its thrust. swbd_b now feeds
    # 4033 + 2974.5 + 0.75 2974.5 = 9238.375 kW at full thrust from 7020 kW usable [3.12.3]: a power row.
    assert high == pytest.approx(300000.0 * 0.75 ** (2 / 3), rel=1e-12) and low == pytest.approx(-high)
    limits = level2.power_limits(level2.groups["switchboard_a"])
    assert limits.sources == ("swbd_b",) and level2.source_demand("swbd_b", level2.groups["switchboard_a"]) == \
        pytest.approx(9238.375, rel=1e-12)


def test_the_vehicle_files_sectors_lift_with_the_thruster_they_protect():
    level2 = Level2(load_vehicle(DP_VESSEL), PARTICULARS)
    intact = {(z.thruster, round(z.sector[0], 6), round(z.sector[1], 6)) for z in level2.zones()}
    assert intact == {("azimuth_stbd", 1.31, 1.83), ("azimuth_port", -1.83, -1.31)}
    assert [z.thruster for z in level2.zones(("tunnel_fwd",))] == ["azimuth_stbd", "azimuth_port"]
    assert [z.thruster for z in level2.zones(("azimuth_port", "tunnel_aft", "swbd_b"))] == []   # its own and the
    assert [z.thruster for z in level2.zones(("azimuth_stbd",))] == []                        # protected one gone


@pytest.mark.slow
def test_cli_writes_the_level_2_report_with_level_1_against_it(tmp_path, capsys):
    assert main(["--dnv-level2", str(DP_VESSEL), str(DP_PARTICULARS), "--out", str(tmp_path),
                 "--heading-step", "45"]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert printed[0].startswith("DP capability-L2(") and printed[1] == SCOPE_L2
    assert "no Level 2 text" in SCOPE_L2 and SCOPE_L2.endswith("Not verified by DNV.")
    for suffix in ("_number.png", "_vs_l1_number.png", "_vs_l1_wind.png", "_table_a1.csv", "_report.md", ".csv"):
        assert (tmp_path / f"dp_vessel_dp_l2{suffix}").stat().st_size > 0, suffix
    summary = (tmp_path / "dp_vessel_dp_l2_report.md").read_text()
    assert summary.startswith("# DP capability Level 2") and "as read here" in summary
    assert (tmp_path / "dp_vessel_dp_l2_table_a8.csv").read_text().splitlines()[1] == f"# {SCOPE_L2}"


def test_bad_level2_data_is_refused_naming_the_key():

    data = yaml.safe_load(DP_PARTICULARS.read_text())
    with pytest.raises(ValueError, match=r"level2: a mapping with wind_coefficients, current_coefficients, site"):
        particulars_from_mapping({**data, "level2": {"waves": {}}})
    with pytest.raises(ValueError, match=r"level2\.current_coefficients\.cx"):
        particulars_from_mapping({**data, "level2": {"current_coefficients": {
            "heading_deg": [0, 180], "cx": [1], "cy": [0, 0], "cn": [0, 0]}}})


# -- a site environment in place of Table 2-1 ---------------------------------------------------

TABLE_2_1 = {"wind": [c.wind for c in WEATHER_CONDITIONS[1:]], "hs": [c.hs for c in WEATHER_CONDITIONS[1:]],
             "tp": [c.tp for c in WEATHER_CONDITIONS[1:]], "current": [c.current for c in WEATHER_CONDITIONS[1:]]}


def with_site(site: dict):
    return particulars_from_mapping({**yaml.safe_load(DP_PARTICULARS.read_text()), "level2": {"site": site}})


def test_a_site_equal_to_table_2_1_changes_nothing_and_says_so():
    plain = Level2(load_vehicle(DP_VESSEL), PARTICULARS).run(45.0)
    same = Level2(load_vehicle(DP_VESSEL), with_site({"name": "as Table 2-1", **TABLE_2_1})).run(45.0)
    for case in plain.numbers:
        assert np.array_equal(plain.numbers[case], same.numbers[case])
        assert np.array_equal(plain.wind_limits[case], same.wind_limits[case])
    assert "Environment: Table 2-1 (no site environment given)." in plain.notes
    assert any(note.startswith("Environment: the site 'as Table 2-1' (the particulars' level2.site)")
               for note in same.notes)


def test_level_2_keeps_a_sites_sea_collinear_and_says_so():
    """The site's peak factor, spreading and directions are Level 3's: Level 2's numbers and
    limiting winds are those of the same conditions without them, its notes name them."""
    plain = Level2(load_vehicle(DP_VESSEL), with_site({"current": 0.8})).run(45.0)
    sea = Level2(load_vehicle(DP_VESSEL), with_site({"current": 0.8, "peak_factor": 3.3, "spreading": 2,
                                                     "wave_direction": 45, "current_direction": -90})).run(45.0)
    for case in plain.numbers:
        assert np.array_equal(plain.numbers[case], sea.numbers[case])
        assert np.array_equal(plain.wind_limits[case], sea.wind_limits[case])
    assert any("Level 3: JONSWAP sea with peak factor 3.3" in note and "Level 2 collinear." in note
               for note in sea.notes)
    assert not any("Level 3" in note for note in plain.notes if note.startswith("Environment"))


@pytest.mark.slow
def test_a_sites_conditions_are_the_numbers():
    """Four site conditions: numbers 0 to 4, the top held at the site's 20 m/s. A stronger current
    at every number holds less somewhere."""
    site = {"wind": [5.0, 10.0, 15.0, 20.0], "hs": [0.5, 1.0, 1.5, 2.0], "tp": 7.0, "current": 0.2}
    small = Level2(load_vehicle(DP_VESSEL), with_site(site)).run(45.0)
    assert small.conditions[-1].wind == 20.0 and np.max(small.numbers["intact"]) == 4
    assert np.all(small.wind_limits["intact"][small.numbers["intact"] == 4] == 20.0)
    plain = Level2(load_vehicle(DP_VESSEL), PARTICULARS).run(45.0)
    strong = Level2(load_vehicle(DP_VESSEL), with_site({"current": 1.5})).run(45.0)
    assert np.any(strong.wind_limits[WORST] < plain.wind_limits[WORST])


@pytest.mark.slow
def test_cli_takes_a_site_file_over_the_particulars_site(tmp_path, capsys):
    site = tmp_path / "bank.yaml"
    site.write_text("name: bank\ncurrent: 1.0\n")
    assert main(["--dnv-level2", str(DP_VESSEL), str(DP_PARTICULARS), "--out", str(tmp_path),
                 "--heading-step", "90", "--site", str(site)]) == 0
    capsys.readouterr()
    notes = (tmp_path / "dp_vessel_dp_l2.txt").read_text()
    assert f"Environment: the site 'bank' ({site}) in place of Table 2-1" in notes
    assert "given: current; Table 2-1's wind, hs, tp" in notes
    site.write_text("current: [1.0, 2.0]\nwind: [3.0]\n")
    assert main(["--dnv-level2", str(DP_VESSEL), str(DP_PARTICULARS), "--out", str(tmp_path), "--site",
                 str(site)]) == 2
    assert "site.current: 2 entries" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["--dnv-level1", str(DP_VESSEL), str(DP_PARTICULARS), "--site", str(site)])
