"""DNV-ST-0111 Level 1 thrust [3.9]: Tables 3-1 to 3-4 row by row, the transcription's worked
examples of nominal thrust and ventilation, limits and refusals naming the key."""

import math
from dataclasses import replace

import pytest

from allocator_pkg.dp.standard.thrust import (
    BETA_MISC,
    ThrusterData,
    eta1,
    eta2,
    eta_m,
    nominal_thrust,
    normal_cdf,
    ventilation_factor,
)


def unit(kind="azimuth", **changes):
    """A round thruster (D 2 m, P_B 1000 kW); a tunnel gets a broken inlet."""
    data = {"name": "t", "kind": kind, "diameter": 2.0, "power": 1000.0}
    if kind == "tunnel":
        data["tunnel_inlet"] = "broken"
    return ThrusterData(**{**data, **changes})


@pytest.mark.parametrize(("kind", "changes", "expected"), [
    ("azimuth", {}, 800.0), ("pod", {}, 800.0), ("shaft_line", {}, 800.0), ("cycloidal", {}, 900.0),
    ("tunnel", {}, 900.0), ("azimuth", {"contra_rotating": True}, 950.0), ("pod", {"ducted": True}, 1200.0),
    ("tunnel", {"ducted": True, "contra_rotating": True}, 900.0),
])
def test_table_3_1(kind, changes, expected):
    assert eta1(unit(kind, **changes)) == expected


@pytest.mark.parametrize(("inlet", "expected"), [("broken", 1.0), ("rounded", 1.07), ("other", 0.93)])
def test_table_3_2_tunnel_inlets_both_ways(inlet, expected):
    tunnel = unit("tunnel", tunnel_inlet=inlet)
    assert eta2(tunnel) == expected and eta2(tunnel, reverse=True) == expected


@pytest.mark.parametrize(("pitch", "ducted", "expected"),
                         [("FPP", False, 0.9), ("FPP", True, 0.7), ("CPP", False, 0.65), ("CPP", True, 0.5)])
def test_table_3_3_reversed_rows(pitch, ducted, expected):
    propeller = unit(pitch=pitch, ducted=ducted)
    assert eta2(propeller) == 1.0 and eta2(propeller, reverse=True) == expected
    assert eta2(unit("cycloidal", pitch=pitch), reverse=True) == 1.0           # not reversed


@pytest.mark.parametrize(("kind", "magnet", "expected"), [
    ("cycloidal", False, 0.91), ("cycloidal", True, 0.97), ("tunnel", False, 0.93), ("azimuth", False, 0.93),
    ("tunnel", True, 0.995), ("shaft_line", False, 0.97), ("pod", False, 0.98),
])
def test_table_3_4(kind, magnet, expected):
    assert eta_m(unit(kind, permanent_magnet=magnet)) == expected


@pytest.mark.parametrize(("data", "reverse", "expected"), [
    # The transcription's worked examples (Descriptions/thrust.md, tests/models/test_thrust.py):
    # AZ1: ducted FPP azimuth, D 3 m, 2000 kW: P = 1860 kW, (3 1860)^(2/3) = 314.598127,
    # 1200 314.598127 = 377517.75 N forward, 0.7 of it reversed.
    (unit(diameter=3.0, power=2000.0, ducted=True), False, 377517.7524),
    (unit(diameter=3.0, power=2000.0, ducted=True), True, 264262.4267),
    # BT1 / BT2: tunnels D 2 m, 900 kW: (2 837)^(2/3) = 140.984; 900 1.07 = 135.77 kN, 900 1.0 = 126.89 kN.
    (unit("tunnel", power=900.0, tunnel_inlet="rounded", pitch="CPP"), True, 135770.0),
    (unit("tunnel", power=900.0, tunnel_inlet="broken", pitch="CPP"), False, 126890.0),
    # Tunnel, rounded, 1000 kW: (2 930)^(2/3) = 151.243004; 900 1.07 151.243004 = 145647.0133 N.
    (unit("tunnel", tunnel_inlet="rounded"), False, 145647.0133),
    # Pod D 2.5, CPP reversed: (2.5 980)^(2/3) = 181.737294; 800 0.65 = 94503.3927 N.
    (unit("pod", diameter=2.5, pitch="CPP"), True, 94503.3927),
    (unit("cycloidal"), False, 134160.1190),                                  # 900 (2 910)^(2/3)
    (unit("shaft_line", diameter=2.5, contra_rotating=True), False, 171473.9296),  # 950 (2.5 970)^(2/3)
])
def test_nominal_thrust_worked_examples(data, reverse, expected):
    assert nominal_thrust(data, reverse) == pytest.approx(expected, rel=5e-5)


def test_nominal_thrust_scales_as_d_p_to_two_thirds():
    assert nominal_thrust(unit(diameter=4.0, power=4000.0)) == pytest.approx(4.0 * nominal_thrust(unit()))


AZ1 = unit(diameter=3.0, power=2000.0, ducted=True)
BT1 = unit("tunnel", power=900.0, tunnel_inlet="rounded", pitch="CPP")
BT2 = unit("tunnel", power=900.0, tunnel_inlet="broken", pitch="CPP")


@pytest.mark.parametrize(("data", "x", "xi", "expected"), [
    # The transcription's worked example (thrust.md section 6): Lpp 80 m, T 6 m; AZ1 at x -40,
    # z 1.8 m above the keel (xi 4.2 m); BT1, BT2 at x 31, 28, z 2.5 m (xi 3.5 m).
    # Columns: BF 6 (Hs 3.1, Tp 8.5) at 0 and 90 deg, BF 11 (Hs 12.1, Tp 12.0) at 0 and 90 deg.
    (AZ1, -40.0, 4.2, (0.9896, 0.9849, 0.8389, 0.7248)),
    (BT1, 31.0, 3.5, (0.9994, 0.9989, 0.9425, 0.8611)),
    (BT2, 28.0, 3.5, (0.9996, 0.9992, 0.9538, 0.8834)),
])
def test_ventilation_worked_example(data, x, xi, expected):
    got = [ventilation_factor(data, x, xi, 80.0, hs, tp, math.radians(heading))
           for hs, tp in ((3.1, 8.5), (12.1, 12.0)) for heading in (0.0, 90.0)]
    assert got == pytest.approx(expected, abs=5e-5)


def test_ventilation_by_hand():
    # AZ1, BF 6, beam: A = 0.85 1.19 0.8 = 0.8092; T0 = 0.64 sqrt(80) / (8.5 / 1.4049) = 0.94608;
    # load factor sqrt(377517.75 / 27) / 15.2 = 7.7793; sigma = 0.25 (0.8092 3.1 0.94608 + 6.7793)
    # = 2.28814; Phi(2 2 4.2 / 3 - 1.5 2.28814) = Phi(2.16779) = 0.98491.
    sigma = 0.25 * (0.8092 * 3.1 * 0.64 * math.sqrt(80.0) / (8.5 / 1.4049)
                    + math.sqrt(377517.7524 / 27.0) / 15.2 - 1.0)
    assert ventilation_factor(AZ1, -40.0, 4.2, 80.0, 3.1, 8.5, math.pi / 2) == pytest.approx(
        normal_cdf(5.6 - 1.5 * sigma), rel=1e-6)
    assert normal_cdf(2.16779) == pytest.approx(0.98491, abs=1e-5)


def test_ventilation_limits_and_mirror():
    light = unit(diameter=2.0, power=1.0)                         # load factor below 1: sigma 0 in calm water
    assert ventilation_factor(light, 0.0, 0.0, 80.0, 0.0, math.nan, 0.0) == pytest.approx(0.5)   # centre at the surface
    assert ventilation_factor(light, 0.0, 20.0, 80.0, 0.0, math.nan, 0.0) == pytest.approx(1.0)
    assert ventilation_factor(AZ1, -40.0, 4.2, 80.0, 5.0, 9.0, math.radians(70)) == pytest.approx(
        ventilation_factor(AZ1, -40.0, 4.2, 80.0, 5.0, 9.0, math.radians(290)))
    # Reversed thrust loads the propeller less, so it ventilates less.
    assert ventilation_factor(AZ1, -40.0, 4.2, 80.0, 5.0, 9.0, 0.0, reverse=True) > ventilation_factor(
        AZ1, -40.0, 4.2, 80.0, 5.0, 9.0, 0.0)
    assert BETA_MISC == 0.9


@pytest.mark.parametrize(("changes", "key"), [
    ({"kind": "water_jet"}, "thrusters.t.kind: water jets"), ({"kind": "jet"}, "thrusters.t.kind"),
    ({"kind": "tunnel"}, "thrusters.t.tunnel_inlet"), ({"tunnel_inlet": "rounded"}, "thrusters.t.tunnel_inlet"),
    ({"pitch": "VPP"}, "thrusters.t.pitch"), ({"diameter": -1.0}, "thrusters.t.diameter"),
    ({"power": "big"}, "thrusters.t.power"), ({"ducted": "yes"}, "thrusters.t.ducted"),
    ({"ducted": True, "contra_rotating": True}, "ducted contra-rotating"),
])
def test_data_outside_the_tables_is_refused_by_key(changes, key):
    with pytest.raises(ValueError, match=key):
        replace(unit(), **changes)
