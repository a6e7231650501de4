"""DP capability Level 1: the load formulas against hand calculations, the balance against an
independent linear programme, symmetry, failures, and the --dnv-level1 command line."""

import csv
import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog

from allocator_pkg import load_vehicle, vehicle_from_parameters
from allocator_pkg.analysis.dp_capability import (
    CONDITIONS,
    WORST,
    Level1,
    Particulars,
    condition_at,
    environment_load,
    level1,
    load_particulars,
    particulars_from_mapping,
)
from allocator_pkg.analysis.environment_loads import (
    LoadCoefficients,
    VesselParticulars,
    current_load,
    lever,
    reflection_factor,
    wave_drift_load,
    wind_load,
)
from allocator_pkg.cli.capability import main
from allocator_pkg.cli.dp_capability import write_level1

SHIP = VesselParticulars(lpp=80.0, beam=20.0, draught=6.0, wind_area_frontal=200.0, wind_area_lateral=600.0,
                         wind_centre_x=5.0, underwater_centre_x=0.0)
DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"

# Four fixed thrusters, +-100 N each: surge at y = -+1 m, sway at x = -+1 m; port-starboard symmetric.
BOX = {
    "dofs": ["surge", "sway", "yaw"],
    "actuators.names": ["surge_port", "surge_stbd", "sway_aft", "sway_fwd"],
    **{f"actuators.{name}.{key}": value
       for name, position, direction in (("surge_port", [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]),
                                         ("surge_stbd", [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
                                         ("sway_aft", [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
                                         ("sway_fwd", [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]))
       for key, value in (("type", "fixed"), ("position", position), ("direction", direction),
                          ("thrust_max", 100.0), ("thrust_min", -100.0))},
}
# Rows X, Y, N (N = x Fy - y Fx) of the four thrusters, written out by hand.
BOX_T = np.array([[1.0, 1.0, 0.0, 0.0],
                  [0.0, 0.0, 1.0, 1.0],
                  [1.0, -1.0, -1.0, 1.0]])
SMALL = Particulars(vessel=VesselParticulars(lpp=2.0, beam=0.8, draught=0.2, wind_area_frontal=0.4,
                                             wind_area_lateral=1.2),
                    failure_groups={"surge_port": ("surge_port",), "sway_fwd": ("sway_fwd",)})


# -- the formulas -------------------------------------------------------------------------

def test_wind_load_by_hand():
    # 1/2 rho V^2 = 0.5 * 1.226 * 10^2 = 61.3 Pa; head on: 61.3 * 0.7 * 200 = 8582 N aft.
    assert wind_load(SHIP, 10.0, 0.0) == pytest.approx([-8582.0, 0.0, 0.0], abs=1e-9)
    # From starboard: 61.3 * 0.9 * 600 = 33102 N to port, acting at the area's centre x = 5 m.
    assert wind_load(SHIP, 10.0, math.pi / 2) == pytest.approx([0.0, -33102.0, -165510.0], abs=1e-6)
    # From 60 deg: X = -8582 cos 60 = -4291; Y = -33102 sin 60 = -28667.17; lever
    # 5 + 0.25 * 80 * (1 - 2/3) = 11.667 m; N = -334450.35.
    assert wind_load(SHIP, 10.0, math.radians(60)) == pytest.approx([-4291.0, -28667.173, -334450.35], rel=1e-6)
    # From -120 deg (port quarter): X = +4291, Y = +28667.17, lever 5 + 20 (1 - 4/3) = -1.667 m.
    assert wind_load(SHIP, 10.0, math.radians(-120)) == pytest.approx([4291.0, 28667.173, -47778.62], rel=1e-6)


def test_current_load_by_hand():
    # 1/2 rho V^2 = 0.5 * 1026 * 0.75^2 = 288.5625 Pa.
    # Head on: 288.5625 * 0.6 * (20 * 6) = 20776.5 N; beam: 288.5625 * 0.7 * (80 * 6) = 96957 N.
    assert current_load(SHIP, 0.75, 0.0) == pytest.approx([-20776.5, 0.0, 0.0], abs=1e-6)
    assert current_load(SHIP, 0.75, math.pi / 2) == pytest.approx([0.0, -96957.0, 0.0], abs=1e-6)
    # From 30 deg: X = -20776.5 cos 30 = -17992.98; Y = -48478.5; lever 0.25 * 80 * (1 - 1/3) = 13.333 m.
    assert current_load(SHIP, 0.75, math.radians(30)) == pytest.approx([-17992.977, -48478.5, -646380.0], rel=1e-6)


def test_reflection_factor_by_hand():
    # Tp 7.5 s: k = (2 pi / 7.5)^2 / 9.81 = 0.0715432 1/m; 2 k T = 0.858518 for T = 6 m;
    # 1 - exp(-0.858518) = 0.576210.
    assert reflection_factor(7.5, 6.0) == pytest.approx(0.576210, abs=1e-6)
    assert reflection_factor(0.0, 6.0) == 1.0
    assert reflection_factor(1e-200, 6.0) == 1.0                                # shorter waves: a wall


def test_wave_drift_load_by_hand():
    # rho g Hs^2 / 16 = 1026 * 9.81 * 2.1^2 / 16 = 2774.182 N/m; times 0.576210 = 1598.513 N/m.
    # Beam sea: 1598.513 * 1.0 * 80 = 127881.0 N to port; head sea from astern: 1598.513 * 0.5 * 20
    # = 15985.13 N forward.
    assert wave_drift_load(SHIP, 2.1, 7.5, math.pi / 2) == pytest.approx([0.0, -127881.0, 0.0], abs=1e-2)
    assert wave_drift_load(SHIP, 2.1, 7.5, math.pi) == pytest.approx([15985.125, 0.0, 0.0], abs=1e-2)
    assert wave_drift_load(SHIP, 0.0, 0.0, 1.0) == pytest.approx([0.0, 0.0, 0.0])


def test_lever_by_hand():
    assert lever(0.0, 5.0, 80.0, 0.25) == pytest.approx(25.0)                  # 5 + 20
    assert lever(math.pi, 5.0, 80.0, 0.25) == pytest.approx(-15.0)             # 5 - 20
    assert lever(math.radians(270), 5.0, 80.0, 0.25) == pytest.approx(5.0)     # wrapped to -90 deg


def test_conditions_and_their_interpolation():
    assert CONDITIONS[5].wind == 10.7 and CONDITIONS[5].hs == 2.1 and CONDITIONS[5].tp == 7.5
    assert CONDITIONS[8].wind == 20.7 and CONDITIONS[8].hs == 5.7 and CONDITIONS[8].current == 0.75
    # Halfway between 5 and 6: wind (10.7 + 13.8) / 2 = 12.25, Hs 2.6, Tp 8.0; 2.5: current 0.625.
    middle = condition_at(5.5)
    assert (middle.wind, middle.hs, middle.tp, middle.current) == pytest.approx((12.25, 2.6, 8.0, 0.75))
    assert condition_at(2.5).current == pytest.approx(0.625)
    with pytest.raises(ValueError, match="between 0 and 11"):
        condition_at(11.5)


def test_environment_load_by_hand():
    # Number 5 head on: wind 0.5 * 1.226 * 10.7^2 * 0.7 * 200 = 9825.53, current 20776.5 and drift
    # 15985.13 N aft; times 1.25 = 58233.95 N.
    assert environment_load(SHIP, CONDITIONS[5], 0.0) == pytest.approx([-58233.946, 0.0, 0.0], abs=1e-2)


# -- the balance ----------------------------------------------------------------------------

def _holds(load: np.ndarray) -> bool:
    """Independent check: some thrusts within +-100 N give -load / 0.9 (scipy linprog)."""
    result = linprog(np.zeros(4), A_eq=BOX_T, b_eq=-load / 0.9, bounds=[(-100.0, 100.0)] * 4, method="highs")
    return result.status == 0


def test_numbers_and_wind_limits_match_an_independent_balance():
    result = level1(vehicle_from_parameters(BOX), SMALL, 30.0)
    assert len(set(result.numbers["intact"])) > 2                       # the example spans several numbers
    for k, heading in enumerate(result.headings_deg):
        direction = math.radians(heading)
        expected = 0
        while expected < 11 and _holds(environment_load(SMALL.vessel, CONDITIONS[expected + 1], direction)):
            expected += 1
        assert result.numbers["intact"][k] == expected, heading
        wind = result.wind_limits["intact"][k]
        if expected < 11:
            low, high = CONDITIONS[expected].wind, CONDITIONS[expected + 1].wind
            level = expected + (wind - low) / (high - low)
            assert _holds(environment_load(SMALL.vessel, condition_at(max(level - 1e-3, 0.0)), direction))
            assert not _holds(environment_load(SMALL.vessel, condition_at(level + 1e-3), direction))


def test_symmetric_vessel_gives_symmetric_polars():
    result = level1(vehicle_from_parameters(BOX), SMALL, 30.0)
    mirrored = (-np.arange(len(result.headings_deg))) % len(result.headings_deg)
    for case in ("intact", WORST):
        np.testing.assert_array_equal(result.numbers[case], result.numbers[case][mirrored])
    np.testing.assert_allclose(result.wind_limits["intact"], result.wind_limits["intact"][mirrored], atol=0.01)


def test_symmetric_azimuth_vessel_with_sectors():
    # dp_vessel with both azimuths at 420 kN: the sectors mirror each other. The capability
    # linear programme (forces in newtons, moments near 1e7 N m) is solved by HiGHS to within
    # about 0.5 % here, so the limiting wind speeds agree to that, the numbers exactly.
    vehicle = load_vehicle(DP_VESSEL)
    vehicle = replace(vehicle, actuators=tuple(replace(a, thrust_max=420000.0) if a.name.startswith("azimuth")
                                               else a for a in vehicle.actuators))
    particulars = load_particulars(DP_PARTICULARS)
    analysis = Level1(vehicle, Particulars(vessel=replace(particulars.vessel, wind_centre_x=0.0)), method="lp")
    for heading in (30.0, 90.0, 150.0):
        number, wind = analysis.heading(math.radians(heading))
        mirrored = analysis.heading(math.radians(360.0 - heading))
        assert number == mirrored[0]
        assert wind == pytest.approx(mirrored[1], rel=5e-3)


@pytest.fixture(scope="module")
def dp_vessel(tmp_path_factory):
    """dp_vessel's Level 1 at 30 deg through the library's file writer: (result, output folder)."""
    out = tmp_path_factory.mktemp("dp_l1")
    return write_level1(DP_VESSEL, DP_PARTICULARS, out, 30.0)[0], out


def test_a_failure_never_raises_a_number(dp_vessel):
    result = dp_vessel[0]
    for group in ("switchboard_a", "switchboard_b"):
        assert np.all(result.numbers[group] <= result.numbers["intact"])
        assert np.all(result.wind_limits[group] <= result.wind_limits["intact"] + 1e-9)
        assert np.all(result.numbers[WORST] <= result.numbers[group])


BOX_LEVEL1 = Level1(vehicle_from_parameters(BOX), SMALL)


@settings(deadline=None)                  # a linear programme per example: no timing asserted
@given(level=st.floats(0.0, 11.0), heading=st.floats(-360.0, 360.0),
       failed=st.sets(st.sampled_from(["surge_port", "surge_stbd", "sway_aft", "sway_fwd"])))
def test_a_condition_held_with_failures_is_held_intact(level, heading, failed):
    if BOX_LEVEL1.balanced(level, math.radians(heading), tuple(failed)):
        assert BOX_LEVEL1.balanced(level, math.radians(heading))


def test_every_thruster_failed_gives_zero():
    everything = Particulars(vessel=SMALL.vessel, failure_groups={"all": tuple(vehicle_from_parameters(BOX).names)})
    result = level1(vehicle_from_parameters(BOX), everything, 30.0)
    assert np.all(result.numbers["all"] == 0) and np.all(result.wind_limits["all"] == 0.0)
    assert result.summary()[2:] == (0, 0)


def test_a_load_in_an_uncontrolled_dof_is_not_held():
    otter = Level1(load_vehicle(ROOT / "config" / "otter_usv.yaml"),
                   load_particulars(ROOT / "config" / "particulars" / "otter_usv.yaml"))
    assert otter.heading(0.0)[0] > 0                   # head on: surge only
    assert otter.heading(math.radians(90))[0] == 0     # beam: a sway load, and sway is not controlled


# -- particulars files ------------------------------------------------------------------------

HULL = {"lpp": 2.0, "beam": 0.8, "draught": 0.2, "wind_area_frontal": 0.4, "wind_area_lateral": 1.2}


@pytest.mark.parametrize(("data", "message"), [
    ({key: value for key, value in HULL.items() if key != "lpp"}, "missing key.*lpp"),
    ({**HULL, "beam": -1.0}, "beam"),
    ({**HULL, "coefficients": {"wind_surge": -0.1}}, "coefficients.wind_surge"),
    ({**HULL, "coefficients": {"wind_drag": 1.0}}, "coefficients: unknown key.*wind_drag"),
    ({**HULL, "lenght": 3.0}, "unknown key.*lenght"),
    ({**HULL, "thrust_loss_factor": 1.5}, "thrust_loss_factor"),
    ({**HULL, "failure_groups": {"a": []}}, "failure_groups"),
])
def test_bad_particulars_are_refused_by_key(data, message):
    with pytest.raises(ValueError, match=message):
        particulars_from_mapping(data)


def test_shipped_particulars_load():
    for path in sorted((ROOT / "config" / "particulars").glob("*.yaml")):
        particulars = load_particulars(path)
        Level1(load_vehicle(ROOT / "config" / path.name), particulars)     # every group names real actuators
    assert load_particulars(DP_PARTICULARS).vessel.coefficients == LoadCoefficients()


def test_failure_group_naming_no_actuator_is_refused():
    bad = Particulars(vessel=SMALL.vessel, failure_groups={"bow": ("tunnel_bow",)})
    with pytest.raises(ValueError, match=r"failure_groups\.bow: no actuator named tunnel_bow"):
        Level1(vehicle_from_parameters(BOX), bad)


# -- the command line -------------------------------------------------------------------------

def test_cli_writes_the_files(tmp_path, capsys):
    assert main(["--dnv-level1", str(ROOT / "config" / "otter_usv.yaml"),
                 str(ROOT / "config" / "particulars" / "otter_usv.yaml"), "--out", str(tmp_path),
                 "--heading-step", "30"]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert printed[0] == "DP capability-L1(0, 0, 0, 0)"
    for suffix in ("_dp_l1_number.png", "_dp_l1_wind.png", "_dp_l1.csv", "_dp_l1.txt"):
        assert (tmp_path / f"otter_usv{suffix}").stat().st_size > 0
        assert str(tmp_path / f"otter_usv{suffix}") in printed
    text = (tmp_path / "otter_usv_dp_l1.txt").read_text()
    assert "Not controlled: sway" in text and "coarser than the standard's 10 deg" in text


def test_summary_follows_from_the_csv(dp_vessel):
    result, out = dp_vessel
    with (out / "dp_vessel_dp_l1.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    assert list(rows[0]) == ["case", "heading_deg", "capability_number", "wind_speed_limit"]
    table: dict[str, dict[float, int]] = {}
    for row in rows:
        table.setdefault(row["case"], {})[float(row["heading_deg"])] = int(row["capability_number"])
    assert set(table) == {"intact", "switchboard_a", "switchboard_b", WORST}
    headings = sorted(table["intact"])
    assert headings == [30.0 * k for k in range(12)]
    worst = {h: min(table["switchboard_a"][h], table["switchboard_b"][h]) for h in headings}
    assert worst == table[WORST]
    bow = [0.0, 30.0, 330.0]
    a, b = min(table["intact"][h] for h in bow), min(table["intact"].values())
    c, d = min(worst[h] for h in bow), min(worst.values())
    line = f"DP capability-L1({a}, {b}, {c}, {d})"
    assert result.summary_line() == line
    assert line in (out / "dp_vessel_dp_l1.txt").read_text()
    assert "thrust ranges" in (out / "dp_vessel_dp_l1.txt").read_text()


def test_cli_refuses_a_bad_particulars_file(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("lpp: 80\nbeam: 20\n")
    assert main(["--dnv-level1", str(DP_VESSEL), str(bad), "--out", str(tmp_path)]) == 2
    assert "missing key(s): draught" in capsys.readouterr().err
