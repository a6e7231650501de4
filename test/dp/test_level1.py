"""DP capability Level 1: the balance against an independent linear programme, the standard's
thrust and zones per case, symmetry, failures, particulars files and the --dnv-level1 command line."""

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
from allocator_pkg.cli.allocator_capability import dnv_report, main
from allocator_pkg.dp.capability_result import SCOPE_L1, WORST
from allocator_pkg.dp.inputs.particulars import load_particulars, particulars_from_mapping
from allocator_pkg.dp.level1 import Level1, level1
from allocator_pkg.dp.standard.thrust import ThrusterData, nominal_thrust, ventilation_factor
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS, condition_at
from allocator_pkg.hull.environment_loads import LoadCoefficients

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"
BOX_NAMES = ["surge_port", "surge_stbd", "sway_aft", "sway_fwd"]

# Four fixed thrusters, reversible: surge at y = -+1 m, sway at x = -+1 m; port-starboard symmetric.
BOX = {
    "dofs": ["surge", "sway", "yaw"],
    "actuators.names": BOX_NAMES,
    **{f"actuators.{name}.{key}": value
       for name, position, direction in (("surge_port", [0.0, -1.0, 0.2], [1.0, 0.0, 0.0]),
                                         ("surge_stbd", [0.0, 1.0, 0.2], [1.0, 0.0, 0.0]),
                                         ("sway_aft", [-1.0, 0.0, 0.2], [0.0, 1.0, 0.0]),
                                         ("sway_fwd", [1.0, 0.0, 0.2], [0.0, 1.0, 0.0]))
       for key, value in (("type", "fixed"), ("position", position), ("direction", direction),
                          ("thrust_max", 100.0), ("thrust_min", -100.0))},
}
# Rows X, Y, N (N = x Fy - y Fx) of the four thrusters, written out by hand.
BOX_T = np.array([[1.0, 1.0, 0.0, 0.0],
                  [0.0, 0.0, 1.0, 1.0],
                  [1.0, -1.0, -1.0, 1.0]])
# Tunnels (flushed tunnels are exempt from [3.11.3]: no zones) of D 0.3 m, 0.13 kW: about 98 N.
TUNNEL = {"kind": "tunnel", "diameter": 0.3, "power": 0.13, "tunnel_inlet": "broken"}
HULL = {"lpp": 2.0, "beam": 0.8, "draught": 0.3, "wind_area_frontal": 0.4, "wind_area_lateral": 1.2,
        "body_origin_x": 0.0, "body_origin_height": 0.3, "los": 2.0, "los_centre_x": 0.0, "bow_angle": 25.0,
        "waterplane_area_aft": 0.7, "current_area_lateral": 0.5}
SMALL = particulars_from_mapping({**HULL, "thrusters": dict.fromkeys(BOX_NAMES, TUNNEL)})


def groups(**members: list[str]) -> dict:
    """The vehicle keys of redundancy groups that lose actuators."""
    return {"redundancy_groups.names": list(members),
            **{f"redundancy_groups.{name}.actuators": lost for name, lost in members.items()}}


BOX_LEVEL1 = Level1(vehicle_from_parameters({**BOX, **groups(surge_port=["surge_port"], sway_fwd=["sway_fwd"])}),
                    SMALL)
# Two buses: sway_aft on bus_a, surge_stbd and sway_fwd on bus_b, surge_port split 50/50; losing bus_a
# fails sway_aft and leaves surge_port half its P_B.
SPLIT = {**BOX, "power.sources": ["bus_a", "bus_b"], "power.bus_a.capacity": 1.0, "power.bus_b.capacity": 1.0,
         "actuators.surge_port.feeds": ["bus_a", "bus_b"], "actuators.surge_port.feed_shares": [0.5, 0.5],
         "actuators.sway_aft.feeds": ["bus_a"], "actuators.surge_stbd.feeds": ["bus_b"],
         "actuators.sway_fwd.feeds": ["bus_b"], "redundancy_groups.names": ["bus_a"],
         "redundancy_groups.bus_a.sources": ["bus_a"], "redundancy_groups.bus_a.actuators": ["sway_aft"]}


def test_conditions_and_their_interpolation():
    five, eight = WEATHER_CONDITIONS[5], WEATHER_CONDITIONS[8]
    assert five.wind == 10.7 and five.hs == 2.1 and five.tp == 7.5
    assert eight.wind == 20.7 and eight.hs == 5.7 and eight.current == 0.75
    # Halfway between 5 and 6: wind (10.7 + 13.8) / 2 = 12.25, Hs 2.6, Tp 8.0; 2.5: current 0.625.
    middle = condition_at(5.5)
    assert (middle.wind, middle.hs, middle.tp, middle.current) == pytest.approx((12.25, 2.6, 8.0, 0.75))
    assert condition_at(2.5).current == pytest.approx(0.625)
    with pytest.raises(ValueError, match="between 0 and 11"):
        condition_at(11.5)


# -- the balance ----------------------------------------------------------------------------

def _holds(level: float, direction: float) -> bool:
    """Independent check: thrusts within the standard's ranges (nominal x 0.9 x beta_vent of each
    thruster, x [m] from Lpp/2 as in the body frame, submergence 0.3 - (0.3 - 0.2) = 0.2 m) give
    minus 1.25 times the loads (scipy linprog)."""
    condition = condition_at(level)
    unit = ThrusterData(name="t", **TUNNEL)
    bounds = []
    for x in (0.0, 0.0, -1.0, 1.0):
        limit = nominal_thrust(unit) * 0.9 * ventilation_factor(unit, x, 0.2, 2.0, condition.hs, condition.tp,
                                                                 direction)
        bounds.append((-limit, limit))
    load = 1.25 * BOX_LEVEL1.loads(condition, direction).total
    return linprog(np.zeros(4), A_eq=BOX_T, b_eq=-load, bounds=bounds, method="highs").status == 0


def test_numbers_and_wind_limits_match_an_independent_balance():
    result = BOX_LEVEL1.run(30.0)
    assert len(set(result.numbers["intact"])) > 2                       # the example spans several numbers
    for k, heading in enumerate(result.headings_deg):
        direction = math.radians(heading)
        expected = 0
        while expected < 11 and _holds(expected + 1, direction):
            expected += 1
        assert result.numbers["intact"][k] == expected, heading
        wind = result.wind_limits["intact"][k]
        if expected < 11:
            low, high = WEATHER_CONDITIONS[expected].wind, WEATHER_CONDITIONS[expected + 1].wind
            level = expected + (wind - low) / (high - low)
            assert _holds(max(level - 1e-3, 0.0), direction)
            assert not _holds(level + 1e-3, direction)


def test_symmetric_vessel_gives_symmetric_polars():
    result = BOX_LEVEL1.run(30.0)
    mirrored = (-np.arange(len(result.headings_deg))) % len(result.headings_deg)
    for case in ("intact", WORST):
        np.testing.assert_array_equal(result.numbers[case], result.numbers[case][mirrored])
    np.testing.assert_allclose(result.wind_limits["intact"], result.wind_limits["intact"][mirrored], atol=0.01)


@settings(deadline=None)                  # a linear programme per example: no timing asserted
@given(level=st.floats(0.0, 11.0), heading=st.floats(-360.0, 360.0), failed=st.sets(st.sampled_from(BOX_NAMES)))
def test_a_condition_held_with_failures_is_held_intact(level, heading, failed):
    # No zones on this vessel (flushed tunnels are exempt), so a failure only takes thrust away.
    if BOX_LEVEL1.balanced(level, math.radians(heading), tuple(failed)):
        assert BOX_LEVEL1.balanced(level, math.radians(heading))


def test_every_thruster_failed_gives_zero():
    result = level1(vehicle_from_parameters({**BOX, **groups(all=BOX_NAMES)}), SMALL, 30.0)
    assert np.all(result.numbers["all"] == 0) and np.all(result.wind_limits["all"] == 0.0)
    assert result.summary()[2:] == (0, 0)
    assert [a.uses for a in result.allocations if a.case == "all"] == [()] * len(result.headings_deg)


# -- the standard's thrust, zones and loads on dp_vessel ---------------------------------------

@pytest.fixture(scope="module")
def dp_level1():
    return Level1(load_vehicle(DP_VESSEL), load_particulars(DP_PARTICULARS))


def test_thrust_ranges_by_hand(dp_level1):
    # azimuth_stbd: ducted FPP, D 3.4 m, P_B 2071 kW: 1200 (3.4 2071 0.93)^(2/3) = 420.03 kN forward,
    # no reverse (the vehicle file's azimuth does not reverse). Its swbd_a (5040 kW usable) is short of
    # the 5045.5 kW it and tunnel_fwd draw at full thrust, but that is the balance's power rows, not its
    # range. Condition 6 head on: Tz = 8.5 / 1.4049 = 6.05025 s, T0 = 0.64 sqrt(83) / 6.05025 = 0.963708;
    # A = 0.85 1 (1 - 0.4 41.5 / 83) = 0.68; load factor sqrt(420025.7 / 3.4^3) / 15.2 = 6.80105;
    # sigma = 0.25 (0.68 3.1 0.963708 + 5.80105) = 1.958137; beta_vent = Phi(2 2 4.5 / 3.4 - 1.5 1.958137)
    # = Phi(2.356913) = 0.990786.
    nominal = 1200.0 * (3.4 * 2071.0 * 0.93) ** (2.0 / 3.0)
    assert nominal == pytest.approx(420025.7, rel=1e-6)
    low, high = dp_level1.thrust_range("azimuth_stbd", WEATHER_CONDITIONS[6], 0.0)
    assert low == 0.0 and high == pytest.approx(nominal * 0.9 * 0.990786, rel=1e-6)
    # The tunnels push either way with the same nominal thrust (Table 3-2).
    low, high = dp_level1.thrust_range("tunnel_fwd", WEATHER_CONDITIONS[6], 0.0)
    assert low == pytest.approx(-high) and high < 0.9 * 300000.5


def test_zones_replace_the_static_sectors_and_lift_with_a_failure(dp_level1):
    # The azimuths 14 m apart, D 3.4 m (15 D = 51 m): half-angle arctan(0.1 + 3.4 / 14) = 18.94 deg
    # around +90 deg (starboard unit) and -90 deg (port unit); the tunnels are exempt as flushed units
    # and 72 m or more from the azimuths (more than 15 x 2.2 m).
    intact = dp_level1.variant(WEATHER_CONDITIONS[6], 0.0)
    sectors = {a.name: a.rotation.forbidden_sectors for a in intact.actuators if a.rotatable}
    half = math.atan(0.1 + 3.4 / 14.0)
    assert len(sectors["azimuth_stbd"]) == len(sectors["azimuth_port"]) == 1
    assert sectors["azimuth_stbd"][0] == pytest.approx((math.pi / 2 - half, math.pi / 2 + half))
    assert sectors["azimuth_port"][0] == pytest.approx((-math.pi / 2 - half, -math.pi / 2 + half))
    lost_port = dp_level1.variant(WEATHER_CONDITIONS[6], 0.0, ("azimuth_port", "tunnel_aft"))
    assert [a.rotation.forbidden_sectors for a in lost_port.actuators if a.name == "azimuth_stbd"] == [()]


def test_body_frame_loads_by_hand(dp_level1):
    # Wind 10.7 m/s from starboard: Fy = 1/2 1.226 10.7^2 650 0.9 = 70.18237 585 = 41056.69 N to port (Y < 0 in FRD),
    # acting at x_L,air = 8 m (the lever's shift vanishes abeam): N = 8 Y.
    wind = dp_level1.loads(WEATHER_CONDITIONS[5], math.pi / 2).wind
    assert wind == pytest.approx([0.0, -41056.686, -328453.49], rel=1e-6, abs=1e-6)


@pytest.mark.slow
def test_a_failure_never_raises_a_number_here(dp_vessel):
    result = dp_vessel[0]
    for group in ("switchboard_a", "switchboard_b"):
        assert np.all(result.numbers[group] <= result.numbers["intact"])
        assert np.all(result.numbers[WORST] <= result.numbers[group])
    assert result.summary()[3] > 0                    # no beam heading lost to a protected sector


def test_symmetric_azimuths_give_mirrored_numbers():
    particulars = load_particulars(DP_PARTICULARS)
    same = dict(particulars.thrusters, azimuth_port=replace(particulars.thrusters["azimuth_stbd"], name="azimuth_port"))
    hull = replace(particulars.hull, wind_centre_x=0.0)
    analysis = Level1(load_vehicle(DP_VESSEL), replace(particulars, thrusters=same, hull=hull), method="lp")
    for heading in (30.0, 90.0, 150.0):
        number, wind = analysis.heading(math.radians(heading))
        mirrored = analysis.heading(math.radians(360.0 - heading))
        assert number == mirrored[0]
        assert wind == pytest.approx(mirrored[1], rel=5e-3)


def test_a_load_in_an_uncontrolled_dof_is_not_held():
    otter = Level1(load_vehicle(ROOT / "config" / "otter_usv.yaml"),
                   load_particulars(ROOT / "config" / "particulars" / "otter_usv.yaml"))
    assert otter.heading(0.0)[0] > 0                   # head on: surge only
    assert otter.heading(math.radians(90))[0] == 0     # beam: a sway load, and sway is not controlled


# -- particulars files and refusals -------------------------------------------------------------

@pytest.mark.parametrize(("data", "message"), [
    ({key: value for key, value in HULL.items() if key != "lpp"}, "missing key.*lpp"),
    ({key: value for key, value in HULL.items() if key != "los"}, "missing key.*los"),
    ({**HULL, "beam": -1.0}, "beam"),
    ({**HULL, "bow_angle": 95.0}, "bow_angle"),
    ({**HULL, "body_origin_height": "keel"}, "body_origin_height"),
    ({**HULL, "coefficients": {"wind_surge": -0.1}}, "coefficients.wind_surge"),
    ({**HULL, "coefficients": {"wind_drag": 1.0}}, "coefficients: unknown key.*wind_drag"),
    ({**HULL, "lenght": 3.0}, "unknown key.*lenght"),
    ({**HULL, "thrust_loss_factor": 0.9}, "unknown key.*thrust_loss_factor"),
    ({**HULL, "failure_groups": {"a": ["b"]}}, r"failure_groups: the redundancy groups are in the vehicle params "
                                               r"file: redundancy_groups\.names"),
    ({**HULL, "thrusters": {"a": {"kind": "tunnel", "diameter": 1.0}}}, r"thrusters\.a: missing key.*power"),
    ({**HULL, "thrusters": {"a": {**TUNNEL, "rpm": 100}}}, r"thrusters\.a: unknown key.*rpm"),
    ({**HULL, "thrusters": {"a": {**TUNNEL, "kind": "water_jet"}}}, r"thrusters\.a\.kind: water jets"),
])
def test_bad_particulars_are_refused_by_key(data, message):
    data = {"thrusters": dict.fromkeys(BOX_NAMES, TUNNEL), **data}
    with pytest.raises(ValueError, match=message):
        particulars_from_mapping(data)


@pytest.mark.parametrize(("thrusters", "message"), [
    (dict.fromkeys(BOX_NAMES[:3], TUNNEL), r"thrusters\.sway_fwd: missing"),
    ({**dict.fromkeys(BOX_NAMES, TUNNEL), "bow": TUNNEL}, r"thrusters\.bow: no actuator of that name"),
    ({**dict.fromkeys(BOX_NAMES, TUNNEL), "sway_fwd": {"kind": "azimuth", "diameter": 0.3, "power": 1.0}},
     r"thrusters\.sway_fwd\.kind: azimuth, but the vehicle file's actuator is fixed"),
])
def test_thruster_data_that_does_not_fit_the_vehicle_is_refused(thrusters, message):
    with pytest.raises(ValueError, match=message):
        Level1(vehicle_from_parameters(BOX), particulars_from_mapping({**HULL, "thrusters": thrusters}))


def test_a_tunnel_on_a_rotatable_actuator_is_refused():
    particulars = load_particulars(DP_PARTICULARS)
    tunnel = ThrusterData("azimuth_stbd", **{**TUNNEL, "diameter": 3.4, "ducted": None})
    thrusters = dict(particulars.thrusters, azimuth_stbd=tunnel)
    with pytest.raises(ValueError, match=r"thrusters\.azimuth_stbd\.kind: tunnel, but .* rotates"):
        Level1(load_vehicle(DP_VESSEL), replace(particulars, thrusters=thrusters))


def test_shipped_particulars_load():
    for path in sorted((ROOT / "config" / "particulars").glob("*.yaml")):
        Level1(load_vehicle(ROOT / "config" / path.name), load_particulars(path))    # every name is real
    assert load_particulars(DP_PARTICULARS).vessel.coefficients == LoadCoefficients()


def test_groups_come_from_the_vehicle_file_without_them_each_actuator_alone():
    assert BOX_LEVEL1.groups == {"surge_port": ("surge_port",), "sway_fwd": ("sway_fwd",)}
    assert Level1(vehicle_from_parameters(BOX), SMALL).groups == {name: (name,) for name in BOX_NAMES}
    split = Level1(vehicle_from_parameters(SPLIT), SMALL)
    assert split.groups == {"bus_a": ("sway_aft", "bus_a")}


def test_a_split_fed_thruster_keeps_its_remaining_share():
    """[3.12] as transcribed: 1000 kW open azimuth of D 2 m fed 50/50 keeps 500 kW after one
    source is lost: T_nominal 120.99 kN becomes 120.99 0.5^(2/3) = 76.22 kN."""
    azimuth = ThrusterData("az", kind="azimuth", diameter=2.0, power=1000.0)
    assert nominal_thrust(azimuth) == pytest.approx(120.99e3, abs=10.0)
    assert nominal_thrust(replace(azimuth, power=500.0)) == pytest.approx(76.22e3, abs=10.0)
    split = Level1(vehicle_from_parameters(SPLIT), SMALL)
    assert split.power_share("surge_port", ("bus_a",)) == 0.5 and split.power_share("surge_stbd", ("bus_a",)) == 1.0
    assert split.power_share("surge_port") == 1.0
    condition, direction = WEATHER_CONDITIONS[5], math.radians(60.0)
    half = replace(SMALL.thrusters["surge_port"], power=0.5 * SMALL.thrusters["surge_port"].power)
    unit = split.actuators["surge_port"]
    expected = 0.9 * nominal_thrust(half) * ventilation_factor(half, unit.x, unit.submergence, 2.0, condition.hs,
                                                                condition.tp, direction, False)
    low, high = split.thrust_range("surge_port", condition, direction, split.groups["bus_a"])
    assert high == pytest.approx(expected, rel=1e-12) and low == pytest.approx(-expected, rel=1e-12)
    intact = split.thrust_range("surge_port", condition, direction)[1]
    assert 0.5 ** (2 / 3) * intact < high < intact               # beta_vent rises as T_nominal falls
    variant = split.variant(condition, direction, split.groups["bus_a"])
    assert variant.names == ("surge_port", "surge_stbd", "sway_fwd") and variant.actuators[0].thrust_max == high


def test_feeds_do_not_change_the_intact_numbers_and_a_derated_group_holds_less():
    split = Level1(vehicle_from_parameters(SPLIT), SMALL).run(30.0)
    plain = Level1(vehicle_from_parameters({**BOX, **groups(bus_a=["sway_aft"])}), SMALL).run(30.0)
    assert np.array_equal(split.numbers["intact"], plain.numbers["intact"])
    assert np.all(split.wind_limits["bus_a"] <= plain.wind_limits["bus_a"])
    assert np.any(split.wind_limits["bus_a"] < plain.wind_limits["bus_a"])


def test_a_board_short_of_power_limits_the_balance_not_the_thrust_ranges():
    """[3.12.3]-[3.12.4]: bus (0.2 kW) feeds both surge tunnels (P_B 0.13 kW each): usable
    0.9 0.2 = 0.18 kW < 0.26 kW at full thrust, so the balance has its row, each tunnel drawing
    0.13 / 0.18 = 0.7222 of it at full thrust; aux (1 kW, usable 0.9 kW) cannot bind. The thrust
    ranges stay the full ones; the holdable loads shrink."""
    board = Level1(vehicle_from_parameters({
        **BOX, "power.sources": ["bus", "aux"], "power.bus.capacity": 0.2, "power.aux.capacity": 1.0,
        "actuators.surge_port.feeds": ["bus"], "actuators.surge_stbd.feeds": ["bus"],
        "actuators.sway_aft.feeds": ["aux"], "actuators.sway_fwd.feeds": ["aux"]}), SMALL)
    limits = board.power_limits()
    assert limits.sources == ("bus",) and limits.thrusters == ("surge_port", "surge_stbd")
    np.testing.assert_allclose(limits.load, [[0.13 / 0.18, 0.13 / 0.18]], rtol=1e-12)
    assert board.source_demand("bus") == pytest.approx(0.26, rel=1e-12)
    assert board.power_limits(("surge_port",)) is None                 # 0.13 kW fits in 0.18 kW
    plain = Level1(vehicle_from_parameters(BOX), SMALL)
    condition = WEATHER_CONDITIONS[5]
    assert board.thrust_range("surge_stbd", condition, 0.0) == plain.thrust_range("surge_stbd", condition, 0.0)
    full, short = plain.run(30.0), board.run(30.0)
    assert np.all(short.wind_limits["intact"] <= full.wind_limits["intact"])
    assert np.any(short.wind_limits["intact"] < full.wind_limits["intact"])
    assert any("bus 0.2 kW, 0.18 kW usable: intact 0.3 kW at full thrust (can limit the balance)" in note
               for note in short.notes)


def test_a_split_fed_thruster_draws_its_shares_from_each_board():
    """SPLIT with bus_a at 0.2 kW: bus_a feeds sway_aft (0.13 kW) and half of surge_port
    (0.065 kW), 0.195 kW > 0.18 kW usable: a row with 0.065 / 0.18 and 0.13 / 0.18. bus_b (0.9 kW
    usable, 0.325 kW at full thrust) cannot bind. Losing bus_a with sway_aft leaves no row, and
    surge_port 0.5 of its P_B (bus_b's half)."""
    split = Level1(vehicle_from_parameters({**SPLIT, "power.bus_a.capacity": 0.2}), SMALL)
    limits = split.power_limits()
    assert limits.sources == ("bus_a",) and limits.thrusters == ("surge_port", "sway_aft")
    np.testing.assert_allclose(limits.load, [[0.065 / 0.18, 0.13 / 0.18]], rtol=1e-12)
    assert split.source_demand("bus_b") == pytest.approx(0.325, rel=1e-12)
    assert split.power_share("surge_port") == 1.0 and split.power_share("surge_stbd") == 1.0
    assert split.power_share("surge_port", split.groups["bus_a"]) == 0.5
    assert split.power_limits(split.groups["bus_a"]) is None


def test_a_thruster_left_without_any_feed_is_refused():
    split = Level1(vehicle_from_parameters(SPLIT), SMALL)
    with pytest.raises(ValueError, match="surge_stbd: every feed lost"):
        split.thrust_range("surge_stbd", WEATHER_CONDITIONS[3], 0.0, ("bus_b",))


# -- the command line -------------------------------------------------------------------------

@pytest.fixture(scope="module")
def dp_vessel(tmp_path_factory):
    """dp_vessel's Level 1 at 30 deg through the library's file writer: (result, output folder)."""
    out = tmp_path_factory.mktemp("dp_l1")
    return dnv_report(DP_VESSEL, DP_PARTICULARS, out, 30.0)[0], out


def test_cli_writes_the_files(tmp_path, capsys):
    assert main(["--dnv-level1", str(ROOT / "config" / "otter_usv.yaml"),
                 str(ROOT / "config" / "particulars" / "otter_usv.yaml"), "--out", str(tmp_path),
                 "--heading-step", "30"]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert printed[0] == "DP capability-L1(0, 0, 0, 0)"
    assert printed[1] == SCOPE_L1 and "Not verified by DNV." in SCOPE_L1 and "[3.11.4]" in SCOPE_L1
    for suffix in ("_dp_l1_number.png", "_dp_l1_wind.png", "_dp_l1.csv", "_dp_l1.txt"):
        assert (tmp_path / f"otter_usv{suffix}").stat().st_size > 0
        assert str(tmp_path / f"otter_usv{suffix}") in printed
    text = (tmp_path / "otter_usv_dp_l1.txt").read_text()
    assert "Not controlled: sway" in text and "coarser than the standard's 10 deg" in text
    assert "clipped to [0.85, 1.15] by [3.7]" in text


def test_summary_follows_from_the_csv(dp_vessel):
    result, out = dp_vessel
    with (out / "dp_vessel_dp_l1.csv").open() as handle:
        assert handle.readline() == f"# {SCOPE_L1}\n"
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
    text = (out / "dp_vessel_dp_l1.txt").read_text()
    assert line in text and SCOPE_L1 in text and "azimuth_stbd 71.1 to 108.9 deg (flushing azimuth_port)" in text


def test_cli_refuses_a_bad_particulars_file(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("lpp: 80\nbeam: 20\n")
    assert main(["--dnv-level1", str(DP_VESSEL), str(bad), "--out", str(tmp_path)]) == 2
    assert "missing key(s): draught" in capsys.readouterr().err


def test_a_balance_is_the_largest_multiple_at_least_one(dp_level1):
    """balanced() stops at the first convex pieces that hold, starting with those that held last;
    the answer is that of the largest multiple over every combination."""
    for failed in ((), dp_level1.groups["switchboard_a"]):
        for level, heading in ((3.5, 0.0), (6.0, 70.0), (8.2, 200.0), (9.7, 300.0), (10.5, 30.0)):
            condition, direction = condition_at(level), math.radians(heading)
            tau = dp_level1.required(condition, direction)
            capability = dp_level1.capability(dp_level1.variant(condition, direction, failed))
            scale = float(np.max(np.abs(tau[capability.model.dof_index]) / capability.model.authority))
            expected = capability.reach(tau / scale)[0] >= scale * (1.0 - 1e-9)
            assert dp_level1.balanced(level, direction, failed) == expected, (failed, level, heading)
