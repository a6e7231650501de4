"""Rudders behind shaft lines [3.10]: the transcription's worked numbers (rudders.md), the fan in
the capability linear programme, and a twin-screw vessel in Level 1."""

import math
from dataclasses import replace

import numpy as np
import pytest
import yaml
from conftest import ROOT

from allocator_pkg import vehicle_from_parameters
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.dp.inputs.particulars import load_particulars, particulars_from_mapping
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.standard.rudders import RudderData, RudderFan, rudder_coefficients, rudder_force
from allocator_pkg.dp.standard.thrust import ThrusterData, nominal_thrust
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS

NACA = RudderData("r", "p", "naca", 4.0)
"""A_r = D^2 behind a D 2 m propeller."""


def test_coefficients_and_forces_of_the_round_case():
    # A_r = D^2, NACA (k1 1.1): C_Y = 0.0126 1.1 = 0.01386, C_x = 0.0002772; T = 1000 N: (1000, 0) at
    # 0 deg, (750.52, 415.8) N at 30 deg, -30 deg mirrors the sway; 35 deg gives the 30 deg values;
    # a rudder that turns 20 deg at most: (889.12, 277.2) N. The 30 deg force points 28.99 deg off the
    # shaft and is 0.858 T.
    c_x, c_y = rudder_coefficients(NACA, 2.0)
    assert (c_x, c_y) == pytest.approx((0.0002772, 0.01386))
    assert rudder_force(c_x, c_y, 1000.0, 0.0, 35.0) == pytest.approx((1000.0, 0.0))
    assert rudder_force(c_x, c_y, 1000.0, 30.0, 35.0) == pytest.approx((750.52, 415.8))
    assert rudder_force(c_x, c_y, 1000.0, -30.0, 35.0) == pytest.approx((750.52, -415.8))
    assert rudder_force(c_x, c_y, 1000.0, 35.0, 35.0) == pytest.approx((750.52, 415.8))
    assert rudder_force(c_x, c_y, 1000.0, 35.0, 20.0) == pytest.approx((889.12, 277.2))
    surge, sway = rudder_force(c_x, c_y, 1.0, 30.0, 35.0)
    assert math.degrees(math.atan2(sway, surge)) == pytest.approx(28.99, abs=5e-3)
    assert math.hypot(surge, sway) == pytest.approx(0.858, abs=5e-4)
    assert rudder_coefficients(replace(NACA, behind_fixed_nozzle=True, profile="nozzle"), 2.0)[1] == \
        pytest.approx(0.0126 * 1.9 * 1.15)


def single_shaft_line(thrust: float = 1000.0, reverse: float = 900.0):
    """One propeller at the origin (as the variant turns it), surge and sway controlled."""
    return vehicle_from_parameters({
        "dofs": ["surge", "sway"], "actuators.names": ["p"], "actuators.p.type": "azimuth",
        "actuators.p.position": [0.0, 0.0, 1.0], "actuators.p.thrust_max": thrust,
        "actuators.p.thrust_min": -reverse, "actuators.p.reversible": True})


def test_one_shaft_line_with_its_rudder():
    # Half the 30 deg force needs u = 0.5 at 28.99 deg (a fan corner): the reach there is 0.858 T.
    # Pure sway, or any direction beyond 28.99 deg, cannot be given; backing with a side force neither
    # ([3.10.2]); pure backing 0.9 T (0.45 T needs u = 0.5).
    fan = RudderFan(*rudder_coefficients(NACA, 2.0), 35.0)
    capability = Capability(single_shaft_line(), "qp", speed=0.0, profiles={"p": fan})
    edge = math.atan2(415.8, 750.52)
    assert capability.max_force(edge) == pytest.approx(858.0, rel=5e-4)
    assert capability.max_force(-edge) == pytest.approx(858.0, rel=5e-4)
    assert capability.max_force(0.0) == pytest.approx(1000.0, rel=1e-4)       # qp: the 256-gon
    for direction in (math.pi / 2, edge + 0.01, math.pi - 0.1, -math.pi / 2):
        assert capability.max_force(direction) == pytest.approx(0.0, abs=1e-6)
    assert capability.max_force(math.pi) == pytest.approx(900.0, rel=1e-4)
    # what Table A-8 calls the thrust available that way
    assert capability.available("p", edge) == pytest.approx(858.0, rel=5e-4)
    assert capability.available("p", math.pi) == 900.0 and capability.available("p", math.pi / 2) == 0.0


def test_the_fan_s_factor_is_its_chords_and_the_reach_follows_it():
    fan = RudderFan(*rudder_coefficients(NACA, 2.0), 30.0)
    capability = Capability(single_shaft_line(), "qp", speed=0.0, profiles={"p": fan})
    c_x, c_y = fan.c_x, fan.c_y
    for alpha in np.linspace(-30.0, 30.0, 13):                    # the corners: on the curve of [3.10.1]
        surge, sway = rudder_force(c_x, c_y, 1.0, alpha, 30.0)
        angle = math.atan2(sway, surge)
        assert fan.factor(angle) == pytest.approx(math.hypot(surge, sway), abs=1e-9)
        assert capability.max_force(angle) == pytest.approx(1000.0 * math.hypot(surge, sway), rel=1e-4)
    assert fan.factor(math.pi) == 1.0 and fan.factor(math.pi / 2) == 0.0


# -- a twin-screw vessel in Level 1 ----------------------------------------------------------

DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"
SHAFT = {"kind": "shaft_line", "diameter": 3.0, "power": 2000.0}
TUNNEL = {"kind": "tunnel", "diameter": 2.2, "power": 2974.5, "tunnel_inlet": "broken"}


def twin_screw(rudders: bool = True):
    """The transcription's twin-screw layout on dp_vessel's hull: open FPP shaft lines (D 3 m,
    2000 kW) at (-38, -+5), NACA rudders (A_r = D^2 = 9 m^2, 35 deg) 2 m aft, two bow tunnels."""
    names = ["shaft_port", "shaft_stbd", "tunnel_fwd", "tunnel_aft"]
    parameters = {"dofs": ["surge", "sway", "yaw"], "method": "qp"}
    for name, position, direction in (("shaft_port", [-38.0, -5.0, 4.0], [1.0, 0.0, 0.0]),
                                      ("shaft_stbd", [-38.0, 5.0, 4.0], [1.0, 0.0, 0.0]),
                                      ("tunnel_fwd", [37.0, 0.0, 3.5], [0.0, 1.0, 0.0]),
                                      ("tunnel_aft", [35.0, 0.0, 3.5], [0.0, 1.0, 0.0])):
        parameters.update({f"actuators.{name}.type": "fixed", f"actuators.{name}.position": position,
                           f"actuators.{name}.direction": direction, f"actuators.{name}.thrust_max": 300e3,
                           f"actuators.{name}.thrust_min": -300e3})
    if rudders:
        for side, y in (("port", -5.0), ("stbd", 5.0)):
            names.append(f"rudder_{side}")
            parameters.update({f"actuators.rudder_{side}.type": "rudder",
                               f"actuators.rudder_{side}.position": [-40.0, y, 4.0],
                               f"actuators.rudder_{side}.area": 9.0, f"actuators.rudder_{side}.lift_coefficient": 3.0,
                               f"actuators.rudder_{side}.deflection_max": math.radians(35.0)})
    parameters["actuators.names"] = names
    data = {key: value for key, value in load_yaml_particulars().items() if key not in ("thrusters", "name")}
    data["thrusters"] = {"shaft_port": SHAFT, "shaft_stbd": SHAFT, "tunnel_fwd": TUNNEL, "tunnel_aft": TUNNEL}
    if rudders:
        data["rudders"] = {f"rudder_{side}": {"propeller": f"shaft_{side}", "profile": "naca", "area": 9.0}
                           for side in ("port", "stbd")}
    return vehicle_from_parameters(parameters), particulars_from_mapping(data)


def load_yaml_particulars() -> dict:
    return yaml.safe_load(DP_PARTICULARS.read_text())


def test_the_shaft_line_s_thrust():
    # open FPP shaft line, D 3 m, 2000 kW: 800 (3 2000 0.97)^(2/3) 0.9 = 232.96 kN ahead, 0.9 of it reversed
    data = ThrusterData("s", **SHAFT)
    assert 0.9 * nominal_thrust(data) == pytest.approx(232.96e3, rel=1e-4)
    assert 0.9 * nominal_thrust(data, reverse=True) == pytest.approx(209.66e3, rel=1e-4)


def test_rudders_turn_the_shaft_lines_and_never_lower_a_number():
    vehicle, particulars = twin_screw()
    analysis = Level1(vehicle, particulars)
    variant = analysis.variant(WEATHER_CONDITIONS[5], math.pi / 2)
    turned = {a.name: a for a in variant.actuators}
    assert set(turned) == {"shaft_port", "shaft_stbd", "tunnel_fwd", "tunnel_aft"}   # rudders folded in
    assert turned["shaft_stbd"].rotatable and turned["shaft_stbd"].position == (-40.0, 5.0, 4.0)   # [3.8.3]
    low, high = analysis.thrust_range("shaft_stbd", WEATHER_CONDITIONS[5], math.pi / 2)
    assert (turned["shaft_stbd"].thrust_min, turned["shaft_stbd"].thrust_max) == (low, high)
    assert "rudder_stbd behind shaft_stbd: C_Y 0.01386/deg" in " ".join(analysis.notes())
    plain = Level1(*twin_screw(rudders=False))
    raised = 0
    for heading in (0.0, 60.0, 90.0, 120.0, 180.0):
        with_rudders, without = analysis.heading(math.radians(heading)), plain.heading(math.radians(heading))
        assert with_rudders[0] >= without[0] and with_rudders[1] >= without[1] - 1e-9
        raised += with_rudders[0] > without[0]
    assert raised > 0
    assert analysis.heading(0.0) == plain.heading(0.0)                   # head on the rudders add nothing


def test_a_lost_rudder_leaves_its_propeller_pushing_along_its_shaft():
    vehicle, particulars = twin_screw()
    analysis = Level1(vehicle, particulars)
    variant = analysis.variant(WEATHER_CONDITIONS[5], 0.0, ("rudder_stbd",))
    shafts = {a.name: a for a in variant.actuators if a.name.startswith("shaft")}
    assert not shafts["shaft_stbd"].rotatable and shafts["shaft_port"].rotatable


@pytest.mark.parametrize(("change", "message"), [
    (lambda data: data.pop("rudders"), "rudders.rudder_port: missing"),
    (lambda data: data["rudders"].update(ghost={"propeller": "shaft_port", "profile": "naca", "area": 9.0}),
     "rudders.ghost: no rudder"),
    (lambda data: data["rudders"]["rudder_port"].update(propeller="tunnel_fwd"), "rudders.rudder_port.propeller"),
    (lambda data: data["rudders"]["rudder_port"].update(profile="spade"), "rudders.rudder_port.profile"),
    (lambda data: data["rudders"]["rudder_port"].update(area=0.0), "rudders.rudder_port.area"),
    (lambda data: data["rudders"]["rudder_port"].update(chord=1.0), "rudders.rudder_port: unknown key"),
    (lambda data: data["rudders"]["rudder_port"].pop("area"), "rudders.rudder_port: missing key"),
])
def test_bad_rudder_rows_are_refused_by_key(change, message):
    vehicle, _ = twin_screw()
    data = {key: value for key, value in load_yaml_particulars().items() if key not in ("thrusters", "name")}
    data["thrusters"] = {"shaft_port": SHAFT, "shaft_stbd": SHAFT, "tunnel_fwd": TUNNEL, "tunnel_aft": TUNNEL}
    data["rudders"] = {f"rudder_{side}": {"propeller": f"shaft_{side}", "profile": "naca", "area": 9.0}
                       for side in ("port", "stbd")}
    change(data)
    with pytest.raises(ValueError, match=message):
        Level1(vehicle, particulars_from_mapping(data))


def test_a_rudder_ahead_of_its_propeller_is_refused():
    vehicle, particulars = twin_screw()
    ahead = replace(vehicle, actuators=tuple(replace(a, position=(-30.0, 5.0, 4.0)) if a.name == "rudder_stbd" else a
                                             for a in vehicle.actuators))
    with pytest.raises(ValueError, match=r"rudders\.rudder_stbd\.propeller: the rudder is not behind shaft_stbd"):
        Level1(ahead, particulars)


def test_the_shipped_vessels_have_no_rudders():
    assert load_particulars(DP_PARTICULARS).rudders == {}
