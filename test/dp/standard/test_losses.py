"""The thrust losses of [3.11.4] (flushing a dead thruster) and [3.11.5] (skeg) against the worked
numbers of the public transcription (dead_flushing.md, skeg_loss.md), and in Level 1."""

import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg import load_vehicle
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.dp.inputs.particulars import load_particulars, particulars_from_mapping
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.standard.losses import (
    LossUnit,
    Skeg,
    dead_flushing_beta,
    dead_flushing_loss,
    direction_factor,
    skeg_loss,
    skegs_from_list,
    thrust_profile,
)
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"


def unit(name, x, y, diameter=2.0, ducted=False, tunnel=False, height=1.0):
    return LossUnit(name, x, y, diameter, ducted, tunnel, height)


def deg(angle):
    return math.radians(angle)


# -- [3.11.4] ---------------------------------------------------------------------------------

@pytest.mark.parametrize(("s_over_d", "beta", "open_deg", "ducted_deg"), [
    (1, 0.320, 31.0, 19.3), (2, 0.438, 16.7, 9.9), (3, 0.531, 11.3, 6.7), (4, 0.603, 8.5, None), (6, 0.708, 5.7, None)])
def test_the_transcription_s_table_of_beta_and_phi(s_over_d, beta, open_deg, ducted_deg):
    assert dead_flushing_beta(s_over_d) == pytest.approx(beta, abs=5e-4)
    for ducted, expected in ((False, open_deg), (True, ducted_deg)):
        loss = dead_flushing_loss(unit("a", 0.0, 0.0, ducted=ducted), unit("b", -2.0 * s_over_d, 0.0))
        if expected is None:                                     # not closer than 4 D
            assert loss is None
        else:
            assert math.degrees(loss.half_angle) == pytest.approx(expected, abs=0.05)


def test_a_dead_thruster_ten_metres_aft():
    # open D 2 m, s/D 5: phi = arctan(0.12) = 6.843 deg, beta = 1 - 1/2.95 = 0.661, centred straight
    # ahead (thrust forward sends the race aft onto it); the midpoint of the Figure 3-6 line from
    # 0.661 (1, 0) to (cos 6.843, sin 6.843) deg is (0.8270, 0.0596): 4.120 deg, radius 0.829.
    loss = dead_flushing_loss(unit("a", 0.0, 0.0), unit("b", -10.0, 0.0))
    assert math.degrees(loss.half_angle) == pytest.approx(6.843, abs=5e-4)
    assert loss.beta == pytest.approx(0.661, abs=5e-4) and loss.centre == 0.0
    midpoint = 0.5 * (np.array([loss.beta, 0.0]) + np.array([math.cos(loss.half_angle), math.sin(loss.half_angle)]))
    assert midpoint == pytest.approx([0.8270, 0.0596], abs=1e-4)
    assert math.degrees(math.atan2(midpoint[1], midpoint[0])) == pytest.approx(4.120, abs=5e-4)
    assert loss.factor(math.atan2(midpoint[1], midpoint[0])) == pytest.approx(0.829, abs=5e-4)
    assert loss.factor(0.0) == pytest.approx(loss.beta) and loss.factor(loss.half_angle) == 1.0
    assert 0.5 / loss.factor(0.0) == pytest.approx(0.756, abs=5e-4)   # 0.5 T forward needs u = 0.756


def test_a_tunnel_beside_a_dead_azimuth_loses_pushing_away_from_it():
    # a tunnel (D 2 m, counts as open) with a dead azimuth 5 m to starboard: s/D 2.5, beta 0.487
    # pushing to port (body frame -90 deg), so 0.25 T needs u = 0.513; pushing to starboard: none.
    loss = dead_flushing_loss(unit("tunnel", 0.0, 0.0, tunnel=True), unit("azimuth", 0.0, 5.0))
    assert loss.factor(deg(-90.0)) == pytest.approx(0.487, abs=5e-4)
    assert 0.25 / loss.factor(deg(-90.0)) == pytest.approx(0.513, abs=5e-4)
    assert loss.factor(deg(90.0)) == 1.0


def test_a_dead_tunnel_may_be_flushed_and_the_loss_ends_at_8_d_and_4_d():
    assert dead_flushing_loss(unit("a", 0.0, 0.0), unit("b", -3.0, 0.0, tunnel=True)) is None
    assert dead_flushing_loss(unit("a", 0.0, 0.0), unit("b", -15.9, 0.0)) is not None        # 8 D = 16 m
    assert dead_flushing_loss(unit("a", 0.0, 0.0), unit("b", -16.0, 0.0)) is None
    assert dead_flushing_loss(unit("a", 0.0, 0.0, ducted=True), unit("b", -8.0, 0.0)) is None  # 4 D = 8 m
    with pytest.raises(ValueError, match="same horizontal position"):
        dead_flushing_loss(unit("a", 1.0, 2.0), unit("b", 1.0, 2.0))


def test_the_transcription_s_test_vessel_pair():
    # ducted D 3 m, 11 m apart: phi = arctan(0.35 3 / 11) = 5.45 deg, beta = 1 - 1/2.386 = 0.581
    loss = dead_flushing_loss(unit("az2", -40.0, 5.5, 3.0, ducted=True), unit("az1", -40.0, -5.5, 3.0, ducted=True))
    assert math.degrees(loss.half_angle) == pytest.approx(5.45, abs=5e-3)
    assert loss.beta == pytest.approx(0.581, abs=5e-4)
    assert math.degrees(loss.centre) == pytest.approx(90.0)


def test_the_forward_of_two_azimuths_keeps_0_531_ahead_of_a_dead_one_6_m_aft():
    # Two azimuths on the centreline 6 m apart, open D 2 m, T 108.89 kN; the aft one dead: the
    # forward one's capacity ahead is 0.531 x 108.89 = 57.77 kN. The aft one with the forward one
    # dead keeps its whole thrust ahead (its race goes away from the dead one).
    vehicle = load_vehicle(DP_VESSEL)
    azimuth = replace(vehicle.actuator("azimuth_stbd"), position=(0.0, 0.0, 4.5), thrust_max=108.89e3,
                      rotation=replace(vehicle.actuator("azimuth_stbd").rotation, forbidden_sectors=()))
    single = replace(vehicle, actuators=(azimuth,), dofs=("surge", "sway"), redundancy_groups=(), power_sources=())
    forward, aft = unit("azimuth_stbd", 0.0, 0.0), unit("aft", -6.0, 0.0)
    ahead = Capability(single, "qp", speed=0.0,
                       profiles={"azimuth_stbd": thrust_profile([dead_flushing_loss(forward, aft)], [])})
    assert ahead.max_force(0.0) == pytest.approx(57.77e3, rel=5e-4)
    behind = dead_flushing_loss(unit("azimuth_stbd", -6.0, 0.0), unit("fwd", 0.0, 0.0))
    assert behind.factor(0.0) == 1.0 and behind.factor(math.pi) == pytest.approx(0.531, abs=5e-4)


# -- [3.11.5] ---------------------------------------------------------------------------------

def standard(x, y, **kwargs):
    """A unit at the standard's (x, y) (y to port): the body frame's (x, -y)."""
    return unit("t", x, -y, **kwargs)


def skeg_factor(loss, standard_deg):
    """The factor at a thrust angle of the standard's frame (counter-clockwise toward port)."""
    return loss.factor(-math.radians(standard_deg))


def test_the_round_skeg_case():
    # skeg end (-36, 0), open D 10 at (-30, 6) (standard's frame): s = 6, alpha_jet = 45 deg,
    # alpha_flush = 45 deg, alpha_maxloss = 90 deg (factor 0): 1 at 0, 0.5 at 45, 0 at 90, 0.5 at 135,
    # 1 from 180 deg. Its mirror at (-30, -6) dips at 270 deg.
    skeg = Skeg(-36.0, 0.0)
    loss = skeg_loss(standard(-30.0, 6.0, diameter=10.0), skeg)
    for angle, factor in ((0, 1.0), (45, 0.5), (90, 0.0), (135, 0.5), (180, 1.0), (270, 1.0), (350, 1.0)):
        assert skeg_factor(loss, angle) == pytest.approx(factor, abs=1e-12)
    mirror = skeg_loss(standard(-30.0, -6.0, diameter=10.0), skeg)
    for angle in np.arange(0.0, 360.0, 5.0):
        assert skeg_factor(mirror, 360.0 - angle) == pytest.approx(skeg_factor(loss, angle), abs=1e-12)
    assert skeg_factor(mirror, 270.0) == pytest.approx(0.0, abs=1e-12)


def test_the_round_case_s_capacity_at_45_deg():
    # 0.25 T at 45 deg (standard's frame) needs u = 0.5: the capacity there is T / 2; at 90 deg none.
    vehicle = load_vehicle(DP_VESSEL)
    azimuth = replace(vehicle.actuator("azimuth_stbd"), position=(-30.0, -6.0, 4.5), thrust_max=1000.0,
                      rotation=replace(vehicle.actuator("azimuth_stbd").rotation, forbidden_sectors=()))
    single = replace(vehicle, actuators=(azimuth,), dofs=("surge", "sway"), redundancy_groups=(), power_sources=())
    loss = skeg_loss(standard(-30.0, 6.0, diameter=10.0), Skeg(-36.0, 0.0))
    capability = Capability(single, "qp", speed=0.0, profiles={"azimuth_stbd": thrust_profile([], [loss])})
    assert capability.max_force(-deg(45.0)) == pytest.approx(500.0, rel=1e-4)
    assert capability.max_force(-deg(90.0)) == pytest.approx(0.0, abs=1e-6)


def test_the_transcription_s_test_vessel_skeg():
    # AZ1 at (-40, 5.5), ducted D 3, skeg end (-36, 0): s = 6.80, alpha_jet = 14.83 deg, alpha_flush =
    # 126.03 deg; loss from 111.20 deg, lowest 2 140.852 / 180 - 1 = 0.56503 at 140.85 deg, back to 1 at
    # 180 deg (alpha_maxloss + 4 alpha_jet = 200.2 deg capped). AZ2 at (-40, -5.5) the mirror.
    skeg = Skeg(-36.0, 0.0)
    az1 = skeg_loss(standard(-40.0, 5.5, diameter=3.0, ducted=True), skeg)
    angles = [-math.degrees(angle) % 360.0 for angle, factor in az1.points if 0.0 < factor < 1.0 or
              (factor == 1.0 and 100.0 < -math.degrees(angle) % 360.0 < 200.0)]
    assert sorted(angles) == pytest.approx([111.20, 140.85, 180.0], abs=5e-3)
    assert skeg_factor(az1, 140.852) == pytest.approx(0.56503, abs=5e-5)
    assert skeg_factor(az1, 111.0) == 1.0 and skeg_factor(az1, 180.0) == pytest.approx(1.0)
    az2 = skeg_loss(standard(-40.0, -5.5, diameter=3.0, ducted=True), skeg)
    assert skeg_factor(az2, 360.0 - 140.852) == pytest.approx(0.56503, abs=5e-5)


def test_where_the_skeg_loss_does_not_apply():
    skeg = Skeg(-36.0, 0.0)
    assert skeg_loss(standard(-30.0, 6.0, diameter=10.0, tunnel=True), skeg) is None       # tunnel
    assert skeg_loss(standard(-30.0, 6.0, diameter=10.0, height=0.0), skeg) is None       # on the base line
    assert skeg_loss(standard(-40.0, 0.0, diameter=10.0), skeg) is None                   # directly behind
    # s = 6.80: a D 0.8 propeller is out of range ducted (8 D = 6.4) but in range open (15 D = 12)
    assert skeg_loss(standard(-40.0, 5.5, diameter=0.8, ducted=True), skeg) is None
    assert skeg_loss(standard(-40.0, 5.5, diameter=0.8), skeg) is not None


def test_losses_combine_as_3_11_6():
    # the lowest dead factor times the lowest skeg factor
    flushing = standard(-30.0, 6.0, diameter=10.0)
    skeg = skeg_loss(flushing, Skeg(-36.0, 0.0))
    dead = dead_flushing_loss(flushing, unit("d", -30.0, -20.0))            # 14 m to starboard, 1.4 D
    angle = dead.centre
    assert direction_factor([dead], [skeg], angle) == pytest.approx(dead.beta * skeg.factor(angle))
    profile = thrust_profile([dead], [skeg])
    assert profile.factor(angle) == pytest.approx(dead.beta * skeg.factor(angle), abs=2e-3)


def test_the_skegs_key():
    assert skegs_from_list([{"x": -30.0, "y": 0}]) == (Skeg(-30.0, 0.0),)
    assert skegs_from_list(None) == ()
    for bad in ({"x": 1.0}, [{"x": 1.0}], [{"x": 1.0, "y": "a"}], [{"x": 1.0, "y": 2.0, "z": 0.0}],
                [{"x": True, "y": 0}]):
        with pytest.raises(ValueError, match="skegs"):
            skegs_from_list(bad)
    data = {"lpp": 2.0, "beam": 0.8, "draught": 0.3, "wind_area_frontal": 0.4, "wind_area_lateral": 1.2,
            "body_origin_x": 0.0, "body_origin_height": 0.3, "los": 2.0, "los_centre_x": 0.0, "bow_angle": 30.0,
            "waterplane_area_aft": 0.6, "current_area_lateral": 0.5,
            "thrusters": {"a": {"kind": "tunnel", "diameter": 0.3, "power": 0.13, "tunnel_inlet": "broken"}}}
    assert particulars_from_mapping(data).skegs == ()
    assert particulars_from_mapping({**data, "skegs": [{"x": -0.8, "y": 0.0}]}).skegs == (Skeg(-0.8, 0.0),)
    with pytest.raises(ValueError, match=r"skegs\[0\]"):
        particulars_from_mapping({**data, "skegs": [{"x": -0.8}]})


# -- in Level 1 -------------------------------------------------------------------------------

class WithoutLosses(Level1):
    """Level 1 without [3.11.4] and [3.11.5], for comparison."""

    def thrust_profiles(self, failed=()):
        return {}


@pytest.fixture(scope="module")
def dp_vessel():
    return load_vehicle(DP_VESSEL), load_particulars(DP_PARTICULARS)


def test_no_loss_applies_on_the_shipped_dp_vessel(dp_vessel):
    # the ducted azimuths are 14 m apart, beyond 4 D = 13.6 m; the tunnels 72 m or more from them,
    # beyond 8 D = 17.6 m; its particulars give no skeg: its numbers are those without the losses.
    analysis = Level1(*dp_vessel)
    assert all(analysis.thrust_profiles(lost) == {} for lost in ((), *analysis.groups.values()))


def test_a_skeg_lowers_numbers_only_where_a_thruster_pushes_into_its_race(dp_vessel):
    # A centreline skeg ending 11.5 m forward of the azimuths: each azimuth loses thrust pushing
    # aft and outboard (down to 0.748 at 157.3 deg from the bow on its side). With swbd_a lost,
    # azimuth_port alone holds the load from 190 deg pushing into that sector: 11 without the loss, 10 with it.
    vehicle, particulars = dp_vessel
    skegged = replace(particulars, skegs=(Skeg(-30.0, 0.0),))
    analysis, plain = Level1(vehicle, skegged), WithoutLosses(vehicle, skegged)
    profile = analysis.thrust_profiles()["azimuth_stbd"]
    assert min(f for _, f in profile.corners) == pytest.approx(0.748, abs=1e-3)
    failed = analysis.groups["switchboard_a"]
    assert plain.heading(deg(190.0), failed)[0] == 11 and analysis.heading(deg(190.0), failed)[0] == 10
    for heading in (0.0, 90.0, 190.0, 270.0):
        with_loss, without = analysis.heading(deg(heading), failed), plain.heading(deg(heading), failed)
        assert with_loss[0] <= without[0] and with_loss[1] <= without[1] + 1e-9
    assert analysis.heading(deg(0.0), failed) == plain.heading(deg(0.0), failed)     # head on: out of the sector


def test_a_fixed_thruster_flushing_a_dead_one_loses_that_way_only(dp_vessel):
    # tunnel_aft moved to (-41.5, 0): 7 m from each azimuth. Intact the [3.11.3] zones forbid it to
    # push either way (its race would hit a working azimuth). With swbd_a lost, azimuth_stbd (y = 7)
    # is dead: pushing to port the zone lifts and [3.11.4] takes s/D = 7 / 2.2 (open), beta = 0.545;
    # pushing to starboard the zone protecting azimuth_port stays.
    vehicle, particulars = dp_vessel
    moved = replace(vehicle, actuators=tuple(replace(a, position=(-41.5, 0.0, 3.5)) if a.name == "tunnel_aft" else a
                                             for a in vehicle.actuators))
    analysis = Level1(moved, particulars)
    intact = analysis.variant(WEATHER_CONDITIONS[5], 0.0).actuator("tunnel_aft")
    assert intact.thrust_min == intact.thrust_max == 0.0
    failed = analysis.groups["switchboard_a"]
    assert "azimuth_stbd" in failed and "tunnel_aft" not in failed
    low = analysis.thrust_range("tunnel_aft", WEATHER_CONDITIONS[5], 0.0, failed)[0]
    tunnel = analysis.variant(WEATHER_CONDITIONS[5], 0.0, failed).actuator("tunnel_aft")
    assert dead_flushing_beta(7.0 / 2.2) == pytest.approx(0.545, abs=5e-4)
    assert tunnel.thrust_min == pytest.approx(low * dead_flushing_beta(7.0 / 2.2)) and tunnel.thrust_max == 0.0


def test_table_a8_gives_the_thrust_available_in_the_thrust_direction(dp_vessel):
    vehicle, particulars = dp_vessel
    analysis = Level1(vehicle, replace(particulars, skegs=(Skeg(-30.0, 0.0),)))
    failed = analysis.groups["switchboard_a"]
    uses = {use.name: use for use in analysis.thruster_use(10, deg(190.0), failed)}
    port = uses["azimuth_port"]
    factor = analysis.thrust_profiles(failed)["azimuth_port"].factor(math.radians(port.angle_deg))
    assert factor < 1.0                                               # it pushes inside its skeg sector
    high = analysis.thrust_range("azimuth_port", WEATHER_CONDITIONS[10], deg(190.0), failed)[1]
    assert port.available == pytest.approx(high * factor)
    assert port.utilisation <= 1.0 + 1e-6
