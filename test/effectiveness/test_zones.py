"""Flushing zones in force and the allocator with them: a zone lifts at the first sample after the
thruster it protects fails and returns when the fault clears, without a new solver set-up; no
thrust inside a zone in force (random requests and faults), the [3.11.4] loss onto a dead thruster,
no hunting at a zone's edge, and the keys checked. The vessel is config/dp_vessel.yaml with its
hand-made sectors replaced by the [3.11.3] zones of its geometry: azimuths 14 m apart, D 3.4 m."""

import math
from itertools import pairwise

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg import Allocator, FaultMode, parse_parameters
from allocator_pkg.configuration.params_file import read_parameters
from allocator_pkg.effectiveness.zones import potential_rotations, zones_in_force
from allocator_pkg.vehicle.config import ConfigError

STBD, PORT = 0, 1
HALF = math.atan(0.1 + 3.4 / 14.0)                     # [3.11.3] by hand: 18.9246 deg
DEAD_HALF = math.atan(0.6 * 3.4 / 14.0)                # [3.11.4] open: 8.2905 deg
BETA = 1.0 - 1.0 / (0.02 * (14.0 / 3.4) ** 2 + 0.25 * 14.0 / 3.4 + 1.2)     # 0.61067
CENTRE = (math.pi / 2, -math.pi / 2)                   # stbd flushes port pushing to starboard, and back
THRUST_MAX = (420e3, 655e3)
GAIN = (18.67, 16.375)                                 # quadratic maps F = k |u| u
METHODS = ("qp", "pseudoinverse", "nonlinear", "lp", "dynamic", "svd_filter")
STEADY = ("qp", "pseudoinverse", "nonlinear", "dynamic", "svd_filter")
"""The methods but lp, which leaves the starboard unit idle under a sway request (a vertex of its
programme), and whose idle azimuths turn back and forth by a rate step with fixed sectors as well."""
TOLERANCE = 1.0                                        # [N]


def dp_parameters(**extra):
    """dp_vessel with its sectors always in force (tied to no thruster), and ``extra``."""
    parameters = {key: value for key, value in read_parameters(ROOT / "config" / "dp_vessel.yaml").items()
                  if not key.endswith(".protects")}
    parameters.update(extra)
    return parameters


def zoned_parameters(**extra):
    parameters = dp_parameters()
    for side in ("stbd", "port"):
        del parameters[f"actuators.azimuth_{side}.forbidden_sectors"]
        parameters[f"actuators.azimuth_{side}.diameter"] = 3.4
        parameters[f"actuators.azimuth_{side}.ducted"] = False           # open, as DEAD_HALF and BETA by hand
    for tunnel in ("fwd", "aft"):
        parameters[f"actuators.tunnel_{tunnel}.diameter"] = 2.2
        parameters[f"actuators.tunnel_{tunnel}.tunnel"] = True
    parameters["flushing_zones"] = "dnv"
    parameters.update(extra)
    return parameters


def vessel(**extra):
    return parse_parameters(zoned_parameters(**extra))[0]


def pushing(angle, thrust):
    return angle if thrust >= 0.0 else angle + math.pi


def off_centre(angle, thrust, k):
    return abs(math.remainder(pushing(angle, thrust) - CENTRE[k], 2.0 * math.pi))


def in_zone(angle, thrust, k):
    return off_centre(angle, thrust, k) < HALF - 1e-9


def notch(angle, thrust, k):
    """[3.11.4] by hand: the radius along the ray of the line from beta (cos c, sin c) to the edge."""
    delta = off_centre(angle, thrust, k)
    if delta >= DEAD_HALF:
        return 1.0
    return BETA * math.sin(DEAD_HALF) / (math.sin(DEAD_HALF - delta) + BETA * math.sin(delta))


# -- zones in force --------------------------------------------------------------------------

def test_the_zones_of_the_geometry_lift_with_the_thruster_they_protect():
    vehicle = vessel()
    zones = zones_in_force(vehicle, [True] * 4)
    start, end = zones.rotations[STBD].forbidden_sectors[0]
    assert math.degrees(start) == pytest.approx(90.0 - 18.9246, abs=1e-4)
    assert math.degrees(end) == pytest.approx(90.0 + 18.9246, abs=1e-4)
    assert zones.losses == {} and zones.rotations[2] is None
    lost_port = zones_in_force(vehicle, [True, False, True, True])
    assert lost_port.rotations[STBD].forbidden_sectors == ()
    assert lost_port.rotations[PORT].forbidden_sectors == ()        # zones among working thrusters only
    (loss,) = lost_port.losses[STBD]
    assert (loss.flushed, loss.beta) == ("azimuth_port", pytest.approx(BETA))
    assert loss.half_angle == pytest.approx(DEAD_HALF)
    assert potential_rotations(vehicle) == zones.rotations


def test_a_sector_the_file_ties_to_a_thruster_lifts_with_it():
    parameters = dp_parameters(**{"actuators.azimuth_stbd.protects": ["azimuth_port"]})
    vehicle = parse_parameters(parameters)[0]
    own = vehicle.actuators[STBD].rotation.forbidden_sectors
    assert zones_in_force(vehicle, [True] * 4).rotations[STBD].forbidden_sectors == own
    assert zones_in_force(vehicle, [True, False, True, True]).rotations[STBD].forbidden_sectors == ()
    both = dp_parameters(**{"actuators.azimuth_stbd.forbidden_sectors": [1.31, 1.83, 3.0, 3.1],
                            "actuators.azimuth_stbd.protects": ["azimuth_port", ""]})
    kept = zones_in_force(parse_parameters(both)[0], [True, False, True, True]).rotations[STBD]
    assert kept.forbidden_sectors == ((3.0, 3.1),)


def test_a_fixed_thruster_may_not_push_its_race_onto_a_working_one():
    # A shaft line 10 m ahead of an azimuth (D 2 m): pushing forward throws its race aft onto it.
    parameters = {
        "dofs": ["surge", "sway", "yaw"], "flushing_zones": "dnv", "actuators.names": ["shaft", "azimuth"],
        "actuators.shaft.type": "fixed", "actuators.shaft.position": [0.0, 0.0, 0.0],
        "actuators.shaft.direction": [1.0, 0.0, 0.0], "actuators.shaft.thrust_max": 100.0,
        "actuators.shaft.diameter": 2.0, "actuators.azimuth.type": "azimuth",
        "actuators.azimuth.position": [-10.0, 0.0, 0.0], "actuators.azimuth.thrust_max": 100.0,
        "actuators.azimuth.diameter": 2.0}
    allocator = Allocator(parse_parameters(parameters)[0])
    low, high = allocator.ranges
    assert (low[0], high[0]) == (-100.0, 0.0)
    allocator.set_fault("azimuth", FaultMode.FAILED)
    assert allocator.ranges[1][0] == 100.0
    allocator.clear_faults()
    assert allocator.ranges[1][0] == 0.0


# -- the allocator with zones that lift and return -------------------------------------------

def run(allocator, tau, samples):
    return [allocator.allocate(tau) for _ in range(samples)]


@pytest.mark.parametrize("method", STEADY)
def test_a_zone_lifts_at_the_failure_and_returns_when_it_clears(method):
    allocator = Allocator(vessel(), method=method)
    sway = [0.0, 500e3, 0.0, 0.0, 0.0, 0.0]             # to starboard: the stbd unit wants to push at 90 deg
    held = run(allocator, sway, 150)
    assert all(not in_zone(r.azimuth[STBD], r.thrust[STBD], STBD) or abs(r.thrust[STBD]) <= TOLERANCE for r in held)
    assert not in_zone(held[-1].azimuth[STBD], 1.0, STBD) and held[-1].thrust[STBD] > 1e3
    assert abs(math.degrees(held[-1].azimuth[STBD]) - (90.0 + 18.9246)) < 0.1      # at the zone's edge
    setups = allocator.stats.solver_setups

    allocator.set_fault("azimuth_port", FaultMode.FAILED)
    lifted = run(allocator, sway, 150)
    assert allocator.stats.solver_setups == setups
    inside = [r for r in lifted if in_zone(r.azimuth[STBD], r.thrust[STBD], STBD) and r.thrust[STBD] > 1e3]
    assert inside, "the lifted zone is never used"
    first = lifted.index(inside[0])
    assert math.degrees(lifted[0].azimuth[STBD]) < 108.93 and first <= 30
    for r in lifted:                                  # thrust onto the dead unit costs [3.11.4]
        factor = notch(r.azimuth[STBD], r.thrust[STBD], STBD)
        assert abs(r.thrust[STBD]) <= factor * THRUST_MAX[STBD] + TOLERANCE
        nominal = abs(r.thrust[STBD]) / factor
        assert abs(r.command[STBD]) == pytest.approx(math.sqrt(nominal / GAIN[STBD]), rel=1e-9, abs=1e-9)

    allocator.clear_faults()
    returned = run(allocator, sway, 150)
    assert allocator.stats.solver_setups == setups
    assert in_zone(lifted[-1].azimuth[STBD], 1.0, STBD)     # the zone returns where the thruster is
    for before, r in zip([lifted[-1], *returned], returned):
        if in_zone(r.azimuth[STBD], r.thrust[STBD], STBD) or in_zone(r.azimuth[STBD], 1.0, STBD):
            assert abs(r.thrust[STBD]) <= TOLERANCE              # leaves it without thrusting inside
        step = abs(math.remainder(r.azimuth[STBD] - before.azimuth[STBD], 2.0 * math.pi))
        assert step <= 0.021 + 1e-9                              # at most its turning rate (0.21 rad/s, 10 Hz)
    assert not in_zone(returned[-1].azimuth[STBD], 1.0, STBD) and returned[-1].thrust[STBD] > 1e3


@pytest.mark.parametrize("method", STEADY)
def test_pushing_onto_a_dead_thruster_costs_thrust_or_goes_to_the_edge(method):
    # Port dead. Some sway to starboard: the starboard unit pushes onto the dead unit, at no more
    # than beta(theta) of its thrust, commanded for thrust / beta. More sway than beta T gives
    # there: it turns to the loss sector's edge at full thrust (cos(8.29 deg) T to starboard),
    # by rate steps without losing thrust on the way.
    allocator = Allocator(vessel(), method=method)
    allocator.set_fault("azimuth_port", FaultMode.FAILED)
    some = run(allocator, [0.0, 5e5, 0.0, 0.0, 0.0, 0.0], 150)
    more = run(allocator, [0.0, 1.2e6, 0.0, 0.0, 0.0, 0.0], 150)
    for r in some + more:
        factor = notch(r.azimuth[STBD], r.thrust[STBD], STBD)
        assert abs(r.thrust[STBD]) <= factor * THRUST_MAX[STBD] + TOLERANCE
        nominal = abs(r.thrust[STBD]) / factor
        assert abs(r.command[STBD]) == pytest.approx(math.sqrt(nominal / GAIN[STBD]), rel=1e-9, abs=1e-9)
    assert off_centre(some[-1].azimuth[STBD], 1.0, STBD) < DEAD_HALF - 0.01 and some[-1].thrust[STBD] > 1e5
    for before, r in zip([some[-1], *more], more):
        assert r.thrust[STBD] >= before.thrust[STBD] - TOLERANCE
    assert off_centre(more[-1].azimuth[STBD], 1.0, STBD) == pytest.approx(DEAD_HALF, abs=1e-6)
    assert more[-1].thrust[STBD] == pytest.approx(THRUST_MAX[STBD])
    assert more[-1].achieved[1] >= 600e3 + THRUST_MAX[STBD] * math.cos(DEAD_HALF) - TOLERANCE


@settings(derandomize=True, max_examples=12, deadline=None, database=None)
@given(method=st.sampled_from(METHODS),
       steps=st.lists(st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(-1.0, 1.0),
                                st.sampled_from(["", "port", "stbd", "clear"])), min_size=5, max_size=12))
def test_never_thrust_inside_a_zone_in_force(method, steps):
    allocator = Allocator(vessel(), method=method)
    working = [True, True]
    for x, y, n, fault in steps:
        if fault == "clear":
            allocator.clear_faults()
            working = [True, True]
        elif fault:
            allocator.set_fault(f"azimuth_{fault}", FaultMode.FAILED)
            working[STBD if fault == "stbd" else PORT] = False
        tau = [600e3 * x, 600e3 * y, 0.0, 0.0, 0.0, 2e7 * n]
        for result in run(allocator, tau, 8):
            for k in (STBD, PORT):
                other = PORT if k == STBD else STBD
                angle, thrust = result.azimuth[k], result.thrust[k]
                if working[other] and in_zone(angle, thrust, k):
                    assert abs(thrust) <= TOLERANCE, (method, k, math.degrees(angle), thrust)
                if not working[other]:
                    assert abs(thrust) <= notch(angle, thrust, k) * THRUST_MAX[k] + TOLERANCE


def significant_reversals(angles, threshold=1e-3):
    """Samples at which an angle turns back after moving by more than ``threshold`` [rad]."""
    moves = np.diff(np.unwrap(angles))
    signs = [(k, np.sign(d)) for k, d in enumerate(moves) if abs(d) > threshold]
    return [k for (_, before), (k, now) in pairwise(signs) if now != before]


@pytest.mark.parametrize("method", STEADY)
def test_no_hunting_at_a_zone_edge(method):
    # The request turns once round at 2 deg/s (10 Hz): each azimuth meets both edges of its zone.
    allocator = Allocator(vessel(), method=method)
    angles = []
    for k in range(1800):
        direction = math.radians(0.2 * k)
        angles.append(allocator.allocate([400e3 * math.cos(direction), 400e3 * math.sin(direction), 0.0, 0.0,
                                          0.0, 0.0]).azimuth[:2].copy())
    for k in (STBD, PORT):
        assert_no_hunting(np.array(angles)[:, k])


@pytest.mark.parametrize("method", STEADY)
@pytest.mark.parametrize("amplitude", [250e3, 900e3])
def test_no_hunting_at_a_loss_sectors_edge(method, amplitude):
    # Port dead: the starboard unit meets its [3.11.4] loss sector, open or closed by the request.
    allocator = Allocator(vessel(), method=method)
    allocator.set_fault("azimuth_port", FaultMode.FAILED)
    angles = []
    for k in range(1800):
        direction = math.radians(0.2 * k)
        angles.append(allocator.allocate([amplitude * math.cos(direction), amplitude * math.sin(direction), 0.0,
                                          0.0, 0.0, 0.0]).azimuth[STBD])
    assert_no_hunting(np.array(angles))


def assert_no_hunting(angles):
    """At most a few turns back in a full turn of the request, never three within ten samples."""
    reversals = significant_reversals(angles)
    assert len(reversals) <= 8, reversals
    assert all(later - first > 10 for first, later in zip(reversals, reversals[2:])), reversals


def test_without_the_new_keys_nothing_changes():
    # The same sectors tied to a thruster that works allocate bit for bit as the plain file.
    plain = Allocator(parse_parameters(dp_parameters())[0])
    tied = Allocator(parse_parameters(dp_parameters(**{"actuators.azimuth_stbd.protects": ["azimuth_port"],
                                                       "actuators.azimuth_port.protects": ["azimuth_stbd"]}))[0])
    rng = np.random.default_rng(3)
    for _ in range(300):
        tau = [*rng.uniform(-5e5, 5e5, 2), 0.0, 0.0, 0.0, rng.uniform(-2e7, 2e7)]
        a, b = plain.allocate(tau), tied.allocate(tau)
        assert np.array_equal(a.thrust, b.thrust) and np.array_equal(a.azimuth, b.azimuth)
        assert np.array_equal(a.command, b.command) and np.array_equal(a.achieved, b.achieved)


# -- the keys --------------------------------------------------------------------------------

@pytest.mark.parametrize(("extra", "key", "reason"), [
    ({"actuators.azimuth_port.diameter": 0.0}, "actuators.azimuth_port.diameter", "required"),
    ({"actuators.tunnel_aft.position": [37.0, 0.0, 3.0]}, "flushing_zones", "same horizontal position"),
])
def test_dnv_zones_need_the_geometry(extra, key, reason):
    with pytest.raises(ConfigError) as error:
        vessel(**extra)
    assert any(name == key and reason in text for name, text in error.value.problems), error.value.problems


@pytest.mark.parametrize(("protects", "reason"), [
    (["azimuth_stbd"], "not another actuator"), (["nobody"], "not another actuator"),
    (["azimuth_port", "tunnel_fwd"], "one name per forbidden sector"),
])
def test_protects_names_another_actuator_per_sector(protects, reason):
    with pytest.raises(ConfigError) as error:
        parse_parameters(dp_parameters(**{"actuators.azimuth_stbd.protects": protects}))
    assert any(name == "actuators.azimuth_stbd.protects" and reason in text for name, text in error.value.problems)
