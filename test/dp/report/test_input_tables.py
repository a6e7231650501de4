"""Tables A-2 to A-5 of the report: the particulars and the vehicle file in the standard's layout
and frame, by hand for dp_vessel, and as the CLI writes them."""

import csv

import pytest
import yaml
from conftest import ROOT
from test_rudders import twin_screw

from allocator_pkg import load_vehicle, read_parameters, vehicle_from_parameters
from allocator_pkg.cli.allocator_capability import dnv_report
from allocator_pkg.dp.inputs.particulars import load_particulars, particulars_from_mapping
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.report.input_tables import (
    A2_COLUMNS,
    A3_COLUMNS,
    A4_COLUMNS,
    AVAILABLE,
    USABLE,
    a5_columns,
    table_a2,
    table_a3,
    table_a4,
    table_a5,
)

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"


@pytest.fixture(scope="module")
def dp_level1():
    return Level1(load_vehicle(DP_VESSEL), load_particulars(DP_PARTICULARS))


def test_table_a2_is_the_particulars_hull(dp_level1):
    rows = {symbol: (value, unit) for _, symbol, value, unit in table_a2(dp_level1)}
    assert rows["Lpp"] == (83.0, "m") and rows["B"] == (18.0, "m") and rows["T"] == (5.0, "m")
    assert rows["bow angle"] == (pytest.approx(30.0), "deg") and rows["A_L,wind"] == (650.0, "m^2")
    assert rows["x_L,air"] == (8.0, "m")                  # body origin midships: the body x is Lpp/2's
    assert rows["Loa"][0].startswith("not given") and rows["skegs"][0].startswith("none given")


def test_table_a2_gives_each_skeg_in_the_standards_frame():
    """A skeg's aft most point at body (-40, 3) FRD, body origin 2 m forward of Lpp/2: x -38 m, y -3 m."""
    data = {**yaml.safe_load(DP_PARTICULARS.read_text()), "body_origin_x": 2.0,
            "skegs": [{"x": -40.0, "y": 3.0}, {"x": -40.0, "y": -3.0}]}
    analysis = Level1(load_vehicle(DP_VESSEL), particulars_from_mapping(data))
    rows = {symbol: (value, unit) for _, symbol, value, unit in table_a2(analysis)}
    assert rows["x_skeg,1"] == (-38.0, "m") and rows["y_skeg,1"] == (-3.0, "m") and rows["y_skeg,2"] == (3.0, "m")
    assert "skegs" not in rows


def test_table_a4_is_each_rudder_behind_its_shaft_line():
    """twin_screw: NACA rudders (k1 1.1, k2 1.0), A_r 9 m^2 behind D 3 m: C_Y = 0.0126 1.1 = 0.01386/deg; 35 deg
    in the vehicle file, 30 used; T_nominal 800 (3 2000 0.97)^(2/3) N, so the side force T_nominal 0.01386 30."""
    analysis = Level1(*twin_screw())
    rows = {row[0]: dict(zip(A4_COLUMNS, row)) for row in table_a4(analysis)}
    assert set(rows) == {"rudder_port", "rudder_stbd"}
    port = rows["rudder_port"]
    assert (port["propeller"], port["profile"], port["a_r_m2"], port["k1"], port["k2"], port["max_angle_deg"]) == (
        "shaft_port", "naca", 9.0, 1.1, 1.0, 30.0)
    nominal = 800.0 * (3.0 * 2000.0 * 0.97) ** (2.0 / 3.0)
    assert port["max_side_force_kn"] == pytest.approx(nominal * 0.01386 * 30.0 / 1e3, rel=1e-9)
    assert table_a4(Level1(*twin_screw(rudders=False))) == []


def test_table_a3_positions_are_in_the_standards_frame(dp_level1):
    """azimuth_stbd at body (-41.5, 7, 4.5) FRD, origin midships 5 m above the keel: x -41.5 m from
    Lpp/2, y -7 m (to port positive), z 5 - 4.5 = 0.5 m above the keel; 420.03 kN ahead, none astern."""
    rows = {row[0]: dict(zip(A3_COLUMNS, row)) for row in table_a3(dp_level1)}
    stbd = rows["azimuth_stbd"]
    assert (stbd["x_m"], stbd["y_m"], stbd["z_m"]) == (-41.5, -7.0, 0.5)
    assert (stbd["type"], stbd["diameter_m"], stbd["p_b_kw"], stbd["ducted"]) == ("azimuth", 3.4, 2071.0, True)
    assert stbd["t_nominal_kn"] == pytest.approx(420.026, abs=1e-3) and stbd["t_nominal_reversed_kn"] == 0.0
    tunnel = rows["tunnel_fwd"]
    assert (tunnel["x_m"], tunnel["y_m"], tunnel["z_m"], tunnel["tunnel_inlet"]) == (37.0, 0.0, 1.5, "broken")
    assert tunnel["t_nominal_reversed_kn"] == tunnel["t_nominal_kn"]


def test_table_a5_is_the_feeds_and_capacities():
    parameters = {**read_parameters(DP_VESSEL), "actuators.tunnel_fwd.feeds": ["swbd_a", "swbd_b"],
                  "actuators.tunnel_fwd.feed_shares": [0.25, 0.75]}
    analysis = Level1(vehicle_from_parameters(parameters), load_particulars(DP_PARTICULARS))
    columns = a5_columns(analysis)
    assert columns == ("thruster", "p_b_kw", "swbd_a_share_pct", "swbd_a_kw", "swbd_b_share_pct", "swbd_b_kw")
    rows = {row[0]: dict(zip(columns, row)) for row in table_a5(analysis)}
    tunnel = rows["tunnel_fwd"]
    assert (tunnel["swbd_a_share_pct"], tunnel["swbd_b_share_pct"]) == (25.0, 75.0)
    assert (tunnel["swbd_a_kw"], tunnel["swbd_b_kw"]) == (0.25 * 2974.5, 0.75 * 2974.5)
    assert (rows[AVAILABLE]["swbd_a_kw"], rows[AVAILABLE]["swbd_b_kw"]) == (5600.0, 7800.0)
    assert (rows[USABLE]["swbd_a_kw"], rows[USABLE]["swbd_b_kw"]) == (5040.0, 7020.0)


def test_the_report_writes_tables_a2_to_a5(tmp_path):
    _, paths = dnv_report(DP_VESSEL, DP_PARTICULARS, tmp_path, step_deg=90.0)
    expected = {"a2": A2_COLUMNS, "a3": A3_COLUMNS, "a4": A4_COLUMNS, "a5": None}
    for table, columns in expected.items():
        path = tmp_path / f"dp_vessel_dp_l1_table_{table}.csv"
        assert path in paths
        lines = path.read_text().splitlines()
        assert lines[0].startswith(f"# Table A-{table[1]}:") and lines[1].endswith("Not verified by DNV.")
        header = next(csv.reader([lines[2]]))
        assert columns is None or tuple(header) == columns
    assert len((tmp_path / "dp_vessel_dp_l1_table_a3.csv").read_text().splitlines()) == 3 + 4
    assert len((tmp_path / "dp_vessel_dp_l1_table_a4.csv").read_text().splitlines()) == 3
    summary = (tmp_path / "dp_vessel_dp_l1_report.md").read_text()
    for title in ("## Table A-2", "## Table A-3", "## Table A-4", "## Table A-5"):
        assert title in summary
    assert "| azimuth_stbd | azimuth | -41.5 | -7 | 0.5 |" in summary
