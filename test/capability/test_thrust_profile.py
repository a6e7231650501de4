"""Direction-dependent thrust limits: the profile's geometry, and the capability linear programme
over its convex pieces against an independent search over the thrusters' angles."""

import itertools
import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg import load_vehicle
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.capability.thrust_profile import ThrustProfile
from allocator_pkg.dp.standard.losses import DeadLoss, SkegLoss, direction_factor, thrust_profile

NOTCH = DeadLoss("a", "b", 0.3, math.radians(8.0), 0.55)
"""A Figure 3-6 notch: down to 0.55 at 0.3 rad, +-8 deg wide."""
RAMP = SkegLoss("a", ((-2 * math.pi, 1.0), (-2.6, 1.0), (-2.2, 0.4), (-1.4, 1.0), (0.0, 1.0)))
"""A skeg dip, linear in the angle: 1 at -2.6 rad, 0.4 at -2.2 rad, 1 again from -1.4 rad."""


def test_a_notch_is_its_three_corners_and_its_centre_is_reflex():
    profile = thrust_profile([NOTCH], [])
    assert sorted(math.remainder(angle, 2 * math.pi) for angle, _ in profile.corners) == pytest.approx(
        [NOTCH.centre - NOTCH.half_angle, NOTCH.centre, NOTCH.centre + NOTCH.half_angle], abs=1e-11)
    assert profile.reflex() == pytest.approx([NOTCH.centre])
    for angle in np.linspace(-math.pi, math.pi, 721):
        assert profile.factor(angle) == pytest.approx(NOTCH.factor(angle), abs=1e-9)


def test_a_polar_ramp_is_drawn_by_chords_inside_it():
    profile = thrust_profile([], [RAMP])
    assert [math.remainder(a, 2 * math.pi) for a in profile.reflex()] == pytest.approx([-2.2])   # the dip's bottom
    gaps = np.diff([angle for angle, factor in profile.corners if factor < 1.0])
    assert np.all(gaps <= math.radians(1.0) + 1e-12)
    angles = np.linspace(-math.pi, math.pi, 2001)
    drawn = np.array([profile.factor(a) for a in angles])
    exact = np.array([RAMP.factor(a) for a in angles])
    assert np.all(drawn <= exact + 1e-9)                         # chords of a curve bent like a circle
    assert np.max(exact - drawn) < 1e-3


def test_pieces_are_convex_and_cover_the_arc():
    profile = thrust_profile([NOTCH], [RAMP])
    pieces = profile.pieces(-math.pi, math.pi)
    assert min(abs(math.remainder(pieces[0][0] - angle, 2 * math.pi)) for angle in profile.reflex()) < 1e-9
    assert pieces[-1][1] == pytest.approx(pieces[0][0] + 2 * math.pi)            # a whole turn, begun at a cut
    for (_, end, _), (start, _, _) in itertools.pairwise(pieces):
        assert end == pytest.approx(start)
    for start, end, planes in pieces:
        assert 0.0 < end - start <= math.pi + 1e-12
        # the boundary r(theta) of a convex piece: every chord point inside every half-plane
        points = [profile.factor(a) * np.array([math.cos(a), math.sin(a)]) for a in np.linspace(start, end, 200)]
        for nx, ny, offset in planes:
            assert max(nx * p[0] + ny * p[1] for p in points) <= offset + 1e-9


def test_bad_corners_are_refused():
    with pytest.raises(ValueError, match="increasing"):
        ThrustProfile(((0.0, 1.0), (0.0, 0.5)))
    with pytest.raises(ValueError, match=r"\[0, 1\]"):
        ThrustProfile(((0.0, 1.0), (0.1, 1.5)))
    with pytest.raises(ValueError, match="at least two"):
        ThrustProfile(((0.0, 0.5),))


# -- the capability linear programme against a search over the thrusters' angles -------------------

AZIMUTHS = ("azimuth_stbd", "azimuth_port")


def _two_azimuths():
    """dp_vessel's two azimuths alone, without forbidden sectors, 420 and 655 kN."""
    vehicle = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
    actuators = tuple(replace(a, rotation=replace(a.rotation, forbidden_sectors=()))
                      for a in vehicle.actuators if a.name in AZIMUTHS)
    return replace(vehicle, actuators=actuators, redundancy_groups=(), power_sources=())


def _search(vehicle, factors, direction: float, step_deg: float = 0.01) -> float:
    """The largest F along ``direction`` (surge-sway plane, yaw moment 0) by a search over the first
    azimuth's angle a1: with a1 fixed, surge, sway and yaw leave one ray of (r1, f2, F) (the null
    space of a 3 x 4 matrix); along it F grows until r1 = T1 beta1(a1) or |f2| = T2 beta2(angle of
    f2), the exact factors (no pieces, no chords)."""
    first, second = vehicle.actuators
    (x1, y1, _), (x2, y2, _) = first.position, second.position
    angles = np.radians(np.arange(-180.0, 180.0, step_deg))
    matrix = np.zeros((angles.size, 3, 4))
    matrix[:, :, 0] = np.stack([np.cos(angles), np.sin(angles), x1 * np.sin(angles) - y1 * np.cos(angles)], axis=-1)
    matrix[:, :, 1] = [1.0, 0.0, -y2]
    matrix[:, :, 2] = [0.0, 1.0, x2]
    matrix[:, :, 3] = [-math.cos(direction), -math.sin(direction), 0.0]
    ray = np.linalg.svd(matrix)[2][:, -1, :]                    # (r1, f2x, f2y, F) up to scale
    ray *= np.sign(ray[:, 3])[:, None]
    best = 0.0
    for a1, (r1, f2x, f2y, force) in zip(angles, ray):
        if force <= 1e-12 or r1 < -1e-12:
            continue
        size = math.hypot(f2x, f2y)
        scales = [second.thrust_max * factors[1](math.atan2(f2y, f2x)) / size] if size > 1e-12 else []
        if r1 > 1e-12:
            scales.append(first.thrust_max * factors[0](a1) / r1)
        if scales:
            best = max(best, min(scales) * force)
    return best


LOSSES = {
    "notch and dip": (([DeadLoss("azimuth_stbd", "x", math.radians(175.0), math.radians(25.0), 0.3)], []),
                      ([], [SkegLoss("azimuth_port", ((-2 * math.pi, 1.0), (math.radians(-175.0), 1.0),
                                                      (math.radians(-160.0), 0.4), (math.radians(-130.0), 1.0),
                                                      (0.0, 1.0)))])),
    "two notches": (([DeadLoss("azimuth_stbd", "x", math.radians(170.0), math.radians(20.0), 0.3),
                      DeadLoss("azimuth_stbd", "y", math.radians(-150.0), math.radians(9.0), 0.6)], []),
                    ([DeadLoss("azimuth_port", "x", math.radians(80.0), math.radians(15.0), 0.5)], [])),
}
"""Per case, (dead losses, skeg losses) of each azimuth."""


def _exact(losses):
    """The exact factor of (dead losses, skeg losses): Figure 3-6 and the polar ramps, no chords."""
    return lambda angle: direction_factor(*losses, angle)


@pytest.mark.slow
@pytest.mark.parametrize("case", sorted(LOSSES))
def test_capability_with_profiles_matches_a_search_over_angles(case):
    vehicle = _two_azimuths()
    parts = LOSSES[case]
    capability = Capability(vehicle, "qp", speed=0.0,
                            profiles={name: thrust_profile(*losses) for name, losses in zip(AZIMUTHS, parts)})
    plain = Capability(vehicle, "qp", speed=0.0)
    lowered = 0
    for degrees in range(0, 360, 15):
        direction = math.radians(degrees)
        found = capability.max_force(direction)
        reference = _search(vehicle, [_exact(p) for p in parts], direction)
        assert found == pytest.approx(reference, rel=2e-3, abs=1.0)
        assert found <= plain.max_force(direction) * (1.0 + 1e-9)
        lowered += found < 0.99 * plain.max_force(direction)
    assert lowered > 0                                           # the losses bite somewhere


def test_a_profile_on_a_fixed_thruster_is_refused():
    vehicle = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
    with pytest.raises(ValueError, match="tunnel_fwd is fixed"):
        Capability(vehicle, profiles={"tunnel_fwd": thrust_profile([NOTCH], [])})
    with pytest.raises(ValueError, match="'pseudoinverse' cannot redistribute force"):
        Capability(vehicle, "pseudoinverse", profiles={"azimuth_stbd": thrust_profile([NOTCH], [])})


@settings(max_examples=25, deadline=None)
@given(st.floats(-math.pi, math.pi), st.floats(0.02, 0.6), st.floats(0.0, 0.99), st.floats(-math.pi, math.pi))
def test_a_single_azimuth_reaches_its_profile(centre, half_angle, beta, direction):
    """One azimuth at the origin (no yaw lever): its reach along a direction is T beta(direction)."""
    vehicle = _two_azimuths()
    single = replace(vehicle, actuators=(replace(vehicle.actuators[0], position=(0.0, 0.0, 4.5)),),
                     dofs=("surge", "sway"))
    loss = DeadLoss("azimuth_stbd", "x", centre, half_angle, beta)
    capability = Capability(single, "qp", speed=0.0, profiles={"azimuth_stbd": thrust_profile([loss], [])})
    expected = single.actuators[0].thrust_max * direction_factor([loss], [], direction)
    assert capability.max_force(direction) == pytest.approx(expected, rel=1e-4, abs=1.0)
