"""DNV-ST-0111 Level 1 forbidden zones [3.11.3]: half-angles by hand, the transcription's layouts
(mirrored into the body frame, y to starboard), the 15 D limit, tunnels, failures lifting zones."""

import math

import pytest

from allocator_pkg.dp.standard.interaction_zones import Unit, Zone, flushing_zones, half_angle

HALF_D2_S10 = math.atan(0.3)                 # arctan(0.1 + 2 / 10) = 16.699 deg


def unit(name="t", x=0.0, y=0.0, diameter=2.0, tunnel=False):
    return Unit(name, x, y, diameter, tunnel)


def test_half_angles_by_hand():
    assert math.degrees(half_angle(2.0, 10.0)) == pytest.approx(16.6992, abs=1e-4)
    # The transcription's test vessel: D 3 m, s 11 m: arctan(0.37273) = 20.4418 deg.
    assert math.degrees(half_angle(3.0, 11.0)) == pytest.approx(20.4418, abs=1e-4)


def test_side_by_side_azimuths_may_not_push_toward_each_other():
    # Starboard unit at y = +5, port unit at y = -5 (FRD): the vector from the port unit to the
    # starboard one points to starboard (+90 deg): pushing that way throws the race onto it.
    zones = flushing_zones([unit("stbd", y=5.0), unit("port", y=-5.0)])
    assert [(z.thruster, z.flushed) for z in zones] == [("stbd", "port"), ("port", "stbd")]
    assert zones[0].centre == pytest.approx(math.pi / 2) and zones[0].half_angle == pytest.approx(HALF_D2_S10)
    assert zones[1].centre == pytest.approx(-math.pi / 2)
    assert zones[0].sector == pytest.approx((math.pi / 2 - HALF_D2_S10, math.pi / 2 + HALF_D2_S10))


def test_transcription_test_vessel_azimuths():
    # AZ1 / AZ2 of the transcription (x -40, y +-5.5 m, D 3 m): 69.56-110.44 deg around the
    # side of the other unit (Table A-6 there, mirrored here).
    zones = flushing_zones([unit("AZ1", -40.0, -5.5, 3.0), unit("AZ2", -40.0, 5.5, 3.0),
                            unit("BT1", 31.0, 0.0, 2.0, tunnel=True), unit("BT2", 28.0, 0.0, 2.0, tunnel=True)])
    assert [(z.thruster, z.flushed) for z in zones] == [("AZ1", "AZ2"), ("AZ2", "AZ1")]
    assert [math.degrees(a) for a in zones[0].sector] == pytest.approx([-110.44, -69.56], abs=0.01)


def test_in_line_the_aft_unit_may_not_push_aft():
    zones = flushing_zones([unit("aft", x=-10.0), unit("fwd", x=0.0)])
    assert abs(zones[0].centre) == pytest.approx(math.pi) and zones[1].centre == pytest.approx(0.0)


def test_only_closer_than_15_diameters_of_the_flushing_unit():
    assert flushing_zones([unit("a"), unit("b", y=29.9)]) != []
    assert flushing_zones([unit("a"), unit("b", y=30.0)]) == []
    # s 25 m: D 2 m (30 m) flushes D 1 m (15 m), not the other way round.
    zones = flushing_zones([unit("big"), unit("small", y=25.0, diameter=1.0)])
    assert [(z.thruster, z.half_angle) for z in zones] == [("big", pytest.approx(math.atan(0.1 + 2 / 25)))]


def test_tunnels_may_be_flushed_but_flush_others():
    zones = flushing_zones([unit("tunnel", tunnel=True), unit("azimuth", y=10.0)])
    assert [(z.thruster, z.flushed) for z in zones] == [("tunnel", "azimuth")]
    assert zones[0].centre == pytest.approx(-math.pi / 2)           # away from the azimuth: to port


def test_a_zone_lifts_with_the_unit_it_protects():
    units = [unit("stbd", y=5.0), unit("port", y=-5.0)]
    assert flushing_zones(units[:1]) == []


def test_forbids_the_open_sector_only():
    zone = Zone("a", "b", math.pi, 0.2)
    assert zone.forbids(-math.pi + 0.1) and zone.forbids(math.pi - 0.19)
    assert not zone.forbids(math.pi - 0.2) and not zone.forbids(0.0)
    assert zone.sector[0] == pytest.approx(math.pi - 0.2) and zone.sector[1] == pytest.approx(math.pi + 0.2)


def test_same_position_is_refused_naming_both():
    with pytest.raises(ValueError, match="a and b are at the same horizontal position"):
        flushing_zones([unit("a"), unit("b")])
