"""The DNV-ST-0111 Level 1 report: tables A-1, A-6, A-7, A-8 and the loads against the Level 1
result and the load formulas, the thrusters' forces against the load they hold, the plots'
artists and the summary."""

import csv
import math

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg import load_vehicle
from allocator_pkg.cli.allocator_capability import dnv_report
from allocator_pkg.dp.capability_result import INTACT, SCOPE_L1, WORST
from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.report.capability_plots import Outline, polar_figure
from allocator_pkg.dp.report.tables import (
    A7_COLUMNS,
    A8_COLUMNS,
    LOAD_COLUMNS,
    table_a1,
    table_a6,
    table_a7,
    table_a8,
    worst_groups,
)
from allocator_pkg.dp.standard.loads import current_load, wave_drift_load, wind_load
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"
GROUPS = ["switchboard_a", "switchboard_b"]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """dp_vessel's report at 30 deg: (analysis, result, folder)."""
    out = tmp_path_factory.mktemp("dp_report")
    result, paths = dnv_report(DP_VESSEL, DP_PARTICULARS, out, 30.0)
    analysis = Level1(load_vehicle(DP_VESSEL), load_particulars(DP_PARTICULARS))
    return analysis, result, out, paths


def read(path):
    with path.open() as handle:
        comments = [handle.readline(), handle.readline()]
        return comments, list(csv.reader(handle))


@pytest.mark.slow
def test_table_a1_is_the_result_per_heading(report):
    _, result, out, _ = report
    comments, rows = read(out / "dp_vessel_dp_l1_table_a1.csv")
    assert comments[1] == f"# {SCOPE_L1}\n" and comments[0].startswith("# Table A-1")
    assert rows[0] == ["heading_deg", INTACT, *GROUPS, "combined", "worst_group"]
    assert len(rows) - 1 == len(result.headings_deg) == 12
    for k, row in enumerate(rows[1:]):
        numbers = [int(v) for v in row[1:5]]
        assert numbers == [result.numbers[c][k] for c in (INTACT, *GROUPS, WORST)]
        assert numbers[3] == min(numbers[1:3]) == result.numbers[row[5]][k]
    assert table_a1(result)[1][0][0] == 0.0


def test_worst_group_breaks_ties_by_wind_speed(report):
    _, result, _, _ = report
    for k, group in enumerate(worst_groups(result)):
        assert result.numbers[group][k] == result.numbers[WORST][k]
        assert result.wind_limits[group][k] == result.wind_limits[WORST][k]


def test_table_a6_lists_the_zones_of_each_case(report):
    analysis, _, out, _ = report
    _, rows = read(out / "dp_vessel_dp_l1_table_a6.csv")
    assert rows[0] == ["case", "thruster", "from_deg", "to_deg", "flushing"]
    assert rows[1:] == [["intact", "azimuth_stbd", "71.08", "108.92", "azimuth_port"],
                        ["intact", "azimuth_port", "-108.92", "-71.08", "azimuth_stbd"]]
    assert len(table_a6(analysis)) == len(analysis.zones()) == 2      # a group's loss lifts both zones


def test_table_a7_loads_are_the_formulas_in_the_standards_frame(report):
    analysis, result, _, _ = report
    rows = table_a7(analysis, result)
    assert len(rows) == 4 * 12 and len(rows[0]) == len(A7_COLUMNS)
    hull = analysis.particulars.hull
    for case, heading, number, wind, *loads in rows:
        k = list(result.headings_deg).index(heading)
        assert number == result.numbers[case][k] and wind == result.wind_limits[case][k]
        c, d = WEATHER_CONDITIONS[number], math.radians(heading)
        expected = np.concatenate([wind_load(hull, c.wind, d), current_load(hull, c.current, d),
                                   wave_drift_load(hull, c.hs, c.tp, d)]) / 1e3
        np.testing.assert_allclose(loads, expected, rtol=1e-12, atol=1e-12)
    beam = next(r for r in rows if r[0] == INTACT and r[1] == 90.0)
    assert beam[5] > 0.0 and beam[4] == pytest.approx(0.0, abs=1e-9)   # from starboard: pushed to port (+y)


def test_loads_table_sums_to_the_factored_load(report):
    out = report[2]
    comments, rows = read(out / "dp_vessel_dp_l1_loads.csv")
    assert rows[0] == list(LOAD_COLUMNS) and "Fx, Fy [kN], Mz [kN m]" in comments[0]
    body = rows[1:]
    assert len(body) == 12 * 11 * 4
    for start in range(0, len(body), 4):
        parts = np.array([[float(v) for v in row[7:]] for row in body[start:start + 4]])
        assert [row[6] for row in body[start:start + 4]] == ["wind", "current", "waves", "total x 1.25"]
        np.testing.assert_allclose(parts[3], 1.25 * parts[:3].sum(axis=0), rtol=1e-5, atol=1e-3)


def test_thrusters_of_table_a8_give_the_load_to_balance(report):
    analysis, result, _, _ = report
    positions = {a.name: a.position for a in analysis.vehicle.actuators}
    for case, failed in {INTACT: (), "switchboard_a": ("azimuth_stbd", "tunnel_fwd")}.items():
        for k in (1, 3, 7):
            number, direction = int(result.numbers[case][k]), math.radians(result.headings_deg[k])
            uses = analysis.thruster_use(number, direction, failed)
            assert {u.name for u in uses} == set(positions) - set(failed)
            wrench = np.zeros(3)
            for use in uses:
                fx, fy = use.thrust * math.cos(math.radians(use.angle_deg)), use.thrust * math.sin(
                    math.radians(use.angle_deg))
                x, y, _ = positions[use.name]
                wrench += [fx, fy, x * fy - y * fx]
            required = analysis.required(WEATHER_CONDITIONS[number], direction)[[0, 1, 5]]
            np.testing.assert_allclose(wrench, required, rtol=1e-6, atol=1e-3 * np.max(np.abs(required)))
            assert max(u.utilisation for u in uses) <= 1.0 + 1e-6


def test_table_a8_rows(report):
    _, result, out, _ = report
    _, rows = read(out / "dp_vessel_dp_l1_table_a8.csv")
    assert rows[0] == list(A8_COLUMNS)
    assert len(rows) - 1 == len(table_a8(result)) == 12 * (4 + 2 + 2)
    lost = [r for r in rows[1:] if r[0] == "switchboard_b"]
    assert {r[3] for r in lost} == {"azimuth_stbd", "tunnel_fwd"}
    assert all(0.0 <= float(r[7]) <= 100.0 + 1e-4 for r in rows[1:])


def test_plots_show_the_cases_and_the_outline(report):
    analysis, result, _, _ = report
    outline = Outline.of(analysis)
    figure = polar_figure(result, "dp", "intact and worst single failure", False, [INTACT, WORST], outline,
                          mark_worst=True)
    polar = figure.axes[0]
    inset = polar.child_axes[0]
    assert result.summary_line() in polar.get_title() and "DP capability number" in polar.get_title()
    assert [line.get_label() for line in polar.get_lines()] == [INTACT, WORST]
    assert {c.get_label() for c in polar.collections if c.get_label().startswith("worst here")} == {
        f"worst here: {g}" for g in set(worst_groups(result))}
    assert inset.get_label() == "vessel outline" and len(inset.patches) == 1
    assert len(inset.get_lines()) == 4                                     # one marker per thruster
    figure = polar_figure(result, "dp", "loss of switchboard_a", True, ["switchboard_a"], outline,
                          failed=("azimuth_stbd", "tunnel_fwd"))
    polar = figure.axes[0]
    inset = polar.child_axes[0]
    assert "limiting wind speed [m/s]" in polar.get_title() and len(polar.get_lines()) == 1
    assert sorted(line.get_marker() for line in inset.get_lines()) == ["o", "o", "x", "x"]
    hull_x = inset.patches[0].get_xy()
    assert np.ptp(hull_x[:, 1]) == pytest.approx(83.0) and np.ptp(hull_x[:, 0]) == pytest.approx(18.0)


def test_the_report_files_and_summary(report):
    _, result, out, paths = report
    names = {p.name for p in paths}
    for suffix in ("number", "wind"):
        for figure in ("", "_groups", *(f"_{g}" for g in GROUPS)):
            assert f"dp_vessel_dp_l1{figure}_{suffix}.png" in names
    summary = (out / "dp_vessel_dp_l1_report.md").read_text()
    assert f"**{result.summary_line()}**" in summary and "Not verified by DNV" in summary
    assert "| `lpp` | 83.0 | m, osv.m |" in summary and "| loss of switchboard_a | 6 |" in summary
    assert SCOPE_L1 in summary and "dp_vessel_dp_l1_table_a8.csv" in summary
    assert "Power sources: swbd_a 5600 kW, swbd_b 7800 kW; feeds: azimuth_stbd swbd_a 100 %" in summary
    assert "switchboard_a: azimuth_stbd, tunnel_fwd, swbd_a" in summary
    for table in ("table_a6_losses", "table_a9", "table_a10"):
        assert f"dp_vessel_dp_l1_{table}.csv" in names and f"`dp_vessel_dp_l1_{table}.csv`" in summary
    assert "## Power per switchboard (Tables A-9, A-10)" in summary and "| intact | swbd_a |" in summary
