"""Rotatable thrusters through every method: rate limits, sectors, the polygon, crossing
forbidden sectors at zero thrust, stuck thrusters, reversible and vertical ones."""

import dataclasses
import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from

from allocator_pkg import METHODS, Allocator, FaultMode, vehicle_from_parameters
from allocator_pkg.allocation.azimuth import AzimuthState, piece_in_question, plan
from allocator_pkg.effectiveness.model import AzimuthLimits
from allocator_pkg.effectiveness.resolve import resolve
from allocator_pkg.effectiveness.sectors import in_feasible_sector, in_forbidden_sector
from allocator_pkg.vehicle.angles import wrap

DP = ROOT / "config" / "dp_vessel.yaml"
EXAMPLE = ROOT / "config" / "example1_rov.yaml"


SINGLE = {"dofs": ["surge", "sway"], "actuators.names": ["a"], "actuators.a.type": "azimuth",
          "actuators.a.position": [0.0, 0.0, 0.0], "actuators.a.thrust_max": 100.0}


def single_azimuth(**keys):
    return vehicle_from_parameters({**SINGLE, **{f"actuators.a.{k}": v for k, v in keys.items()}})


ROTATING = [name for name, method in METHODS.items() if not method.problems(single_azimuth())]
"""The methods that serve rotatable thrusters (explicit needs fixed directions)."""


def check_limits(vehicle, previous, result, dt):
    for i, actuator in enumerate(vehicle.actuators):
        assert math.isfinite(result.thrust[i]) and math.isfinite(result.azimuth[i])
        if actuator.rotatable:
            rotation = actuator.rotation
            step = abs(wrap(result.azimuth[i] - previous.azimuth[i]))
            if rotation.rate_max > 0:
                assert step <= rotation.rate_max * dt + 1e-9, f"{actuator.name} turned {step} rad"
            assert in_feasible_sector(rotation, result.azimuth[i])
            if abs(result.thrust[i]) > 1e-9:
                assert not in_forbidden_sector(rotation, result.azimuth[i]), f"{actuator.name} thrusts in a sector"
            assert actuator.thrust_min - 1e-9 <= result.thrust[i] <= actuator.thrust_max + 1e-9
        if actuator.thrust_rate_max > 0:
            assert abs(result.thrust[i] - previous.thrust[i]) <= actuator.thrust_rate_max * dt + 1e-6


@pytest.mark.parametrize("method", ROTATING)
def test_rotating_force_respects_rates_and_sectors_and_converges(method):
    vehicle = vehicle_from(DP)
    alloc = Allocator(vehicle, method=method)
    previous = alloc.stop()
    force = 200000.0
    for k in range(900):                                     # 1.5 turns of the requested force
        heading = 2 * math.pi * k / 600
        tau = [force * math.cos(heading), force * math.sin(heading), 0.0, 0.0, 0.0, 0.0]
        result = alloc.allocate(tau)
        check_limits(vehicle, previous, result, alloc.dt)
        previous = result
    tau = [force * math.cos(heading), force * math.sin(heading), 0.0, 0.0, 0.0, 0.0]
    for _ in range(300):                                     # hold the last request: angles settle
        result = alloc.allocate(tau)
        check_limits(vehicle, previous, result, alloc.dt)
        previous = result
    assert not result.saturated
    assert result.achieved[[0, 1, 5]] == pytest.approx(np.array(tau)[[0, 1, 5]], abs=1e-3 * force)


@pytest.mark.parametrize("sides", [8, 16, 32])
def test_polygon_never_exceeds_the_limit_and_loses_at_most_one_minus_cos(sides):
    vehicle = vehicle_from_parameters({**SINGLE, "azimuth_polygon_sides": sides})
    worst = 1.0
    for k in range(72):
        alloc = Allocator(vehicle)
        heading = math.radians(5 * k)
        for _ in range(3):
            result = alloc.allocate([500 * math.cos(heading), 500 * math.sin(heading), 0, 0, 0, 0])
        magnitude = math.hypot(result.achieved[0], result.achieved[1])
        assert magnitude <= 100.0 + 1e-6
        worst = min(worst, magnitude / 100.0)
    assert worst >= math.cos(math.pi / sides) - 1e-4


def test_pseudo_inverse_angle_moves_at_rate_and_never_pushes_the_wrong_way():
    vehicle = single_azimuth(azimuth_rate_max=1.0)
    alloc = Allocator(vehicle, method="pseudoinverse", dt=0.1)
    for k in range(40):
        result = alloc.allocate([-50.0, 1.0, 0, 0, 0, 0])            # behind: the angle must turn ~pi
        assert result.thrust[0] >= 0.0
        expected = min(0.1 * (k + 1), math.atan2(1.0, -50.0))
        assert result.azimuth[0] == pytest.approx(expected, abs=1e-9)
        direction = np.array([math.cos(result.azimuth[0]), math.sin(result.azimuth[0])])
        assert result.thrust[0] == pytest.approx(max(0.0, direction @ [-50.0, 1.0]), abs=1e-9)
    assert result.achieved[:2] == pytest.approx([-50.0, 1.0])


@pytest.mark.parametrize("method", ROTATING)
def test_forbidden_sector_is_crossed_at_zero_thrust(method):
    # Free rotation, forbidden sector (1.0, 2.0): from 0.8 to a wanted direction of 2.3 rad the
    # short way crosses it.
    vehicle = single_azimuth(azimuth_rate_max=0.5, forbidden_sectors=[1.0, 2.0], azimuth_initial=0.8,
                             thrust_rate_max=100.0)
    alloc = Allocator(vehicle, method=method, dt=0.1)
    target = [50 * math.cos(2.3), 50 * math.sin(2.3), 0, 0, 0, 0]
    previous = alloc.stop()
    crossed = False
    for _ in range(80):
        result = alloc.allocate(target)
        check_limits(vehicle, previous, result, 0.1)
        if in_forbidden_sector(vehicle.actuators[0].rotation, result.azimuth[0]):
            crossed = True
            assert result.thrust[0] == 0.0
        previous = result
    assert crossed
    assert result.azimuth[0] == pytest.approx(2.3, abs=1e-3)
    assert result.achieved[:2] == pytest.approx(target[:2], abs=0.1)


def test_azimuth_failing_mid_crossing_stops_turning_and_resumes_when_cleared():
    vehicle = single_azimuth(azimuth_rate_max=0.5, forbidden_sectors=[1.0, 2.0], azimuth_initial=0.8,
                             thrust_rate_max=100.0)
    alloc = Allocator(vehicle, dt=0.1)
    target = [50 * math.cos(2.3), 50 * math.sin(2.3), 0, 0, 0, 0]
    rotation = vehicle.actuators[0].rotation
    while not in_forbidden_sector(rotation, alloc.allocate(target).azimuth[0]):
        pass
    alloc.set_fault("a", FaultMode.FAILED)
    stopped = alloc.allocate(target).azimuth[0]
    for _ in range(10):
        result = alloc.allocate(target)
        assert result.azimuth[0] == stopped and result.thrust[0] == 0.0
    alloc.clear_faults()
    for _ in range(60):
        result = alloc.allocate(target)
    assert result.azimuth[0] == pytest.approx(2.3, abs=1e-3)


def test_limited_sector_keeps_the_angle_inside_and_turns_the_long_way():
    vehicle = single_azimuth(azimuth_min=-2.0, azimuth_max=2.0, azimuth_rate_max=1.0, azimuth_initial=1.9)
    alloc = Allocator(vehicle, dt=0.1)
    previous = alloc.stop()
    target = [50 * math.cos(-1.9), 50 * math.sin(-1.9), 0, 0, 0, 0]
    for _ in range(80):
        result = alloc.allocate(target)
        check_limits(vehicle, previous, result, 0.1)
        previous = result
    assert result.azimuth[0] == pytest.approx(-1.9, abs=1e-3)


def test_a_long_way_round_chosen_over_a_sector_leaves_the_window_open_both_ways():
    """Only a feasible sector's end closes the short way round. A free thruster whose goal lies
    nearly opposite, the long way chosen only because the short one crosses a forbidden sector,
    keeps its window on both sides: cut toward the long way, it lost the cut a rate step past
    the goal's antipode, where the long way became the short one, and the QP turned it back
    (with the planner's goal weighed, the DP vessel at 105 deg and 1.1 times its capability:
    its idle starboard unit 1.2 deg back and forth for good)."""
    rotation = vehicle_from(DP).actuators[0].rotation
    goal = math.radians(174.4)
    wanted = (424e3 * math.cos(goal), 424e3 * math.sin(goal))
    for angle in (0.0, math.radians(-4.8)):
        state = AzimuthState(angle=angle)
        limits = plan(rotation, state, 0.021, (0.0, 420e3), 10e3, wanted, 42.0)
        assert not state.turning
        assert (limits.low, limits.high) == pytest.approx((angle - 0.021, angle + 0.021))
        assert wrap(limits.goal - goal) == pytest.approx(0.0, abs=1e-9) and limits.goal < angle   # clockwise


def test_reversible_thruster_pushes_backwards_without_turning():
    vehicle = single_azimuth(reversible=True, thrust_min=-80.0, azimuth_rate_max=0.2)
    alloc = Allocator(vehicle, dt=0.1)
    result = alloc.allocate([-60.0, 0.0, 0, 0, 0, 0])
    assert result.thrust[0] == pytest.approx(-60.0, rel=1e-4)
    assert result.azimuth[0] == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("method", ROTATING)
def test_stuck_azimuth_keeps_its_angle_while_the_others_compensate(method):
    vehicle = vehicle_from(EXAMPLE)
    alloc = Allocator(vehicle, method=method)
    alloc.set_fault("azimuth_fwd", FaultMode.STUCK, angle=1.2)
    tau = np.array([120.0, 40.0, 0.0, 0.0, 0.0, 20.0])
    setups = alloc.stats.solver_setups
    for _ in range(150):
        result = alloc.allocate(tau)
        assert result.azimuth[0] == pytest.approx(1.2)
    assert not result.saturated
    assert result.achieved[[0, 1, 5]] == pytest.approx(tau[[0, 1, 5]], abs=0.2)
    assert alloc.stats.solver_setups == setups


@pytest.mark.parametrize("method", ROTATING)
def test_failed_azimuth_holds_its_angle_and_the_others_take_over(method):
    """A failed azimuth gives nothing, so no method may count on it nor turn it; the aft azimuth
    and the main propellers meet a request they can reach on their own."""
    vehicle = vehicle_from(EXAMPLE)
    alloc = Allocator(vehicle, method=method)
    alloc.set_fault("azimuth_fwd", FaultMode.FAILED)
    tau = np.array([100.0, 20.0, 0.0, 0.0, 0.0, 10.0])
    for _ in range(300):
        result = alloc.allocate(tau)
        assert result.azimuth[0] == 0.0 and result.thrust[0] == 0.0
    assert not result.saturated
    assert result.achieved[[0, 1, 5]] == pytest.approx(tau[[0, 1, 5]], abs=0.05)


def test_vertical_azimuth_pushes_in_the_x_z_plane():
    parameters = {"dofs": ["surge", "heave"], "actuators.names": ["v"], "actuators.v.type": "azimuth_vertical",
                  "actuators.v.position": [0.0, 0.0, 0.0], "actuators.v.thrust_max": 100.0}
    alloc = Allocator(vehicle_from_parameters(parameters))
    result = alloc.allocate([30.0, 0.0, 40.0, 0.0, 0.0, 0.0])
    assert result.thrust[0] == pytest.approx(50.0, rel=1e-4)
    assert result.azimuth[0] == pytest.approx(math.atan2(30.0, 40.0), abs=1e-4)   # 0 points along +z


def test_plan_and_resolve_units():
    vehicle = single_azimuth(azimuth_rate_max=1.0)
    rotation = vehicle.actuators[0].rotation
    state = AzimuthState(angle=0.0, thrust=20.0)
    limits = plan(rotation, state, 0.1, (0.0, 100.0), 5.0, (0.0, 50.0), 0.01)
    assert (limits.low, limits.high) == pytest.approx((-0.1, 0.1))
    assert (limits.thrust_low, limits.thrust_high) == (15.0, 25.0)
    thrust, angle = resolve(limits, 0.0, (0.0, 50.0), 0.01, continuous=True)
    assert angle == pytest.approx(0.1)
    assert thrust == 15.0          # the projection, 50 sin(0.1), is below what the rate limit allows
    held = resolve(AzimuthLimits(-0.1, 0.1, 1, 0.0, 25.0), 0.05, (1e-3, 0.0), 0.01, continuous=True)
    assert held[1] == 0.05


@pytest.mark.parametrize("reversible", [False, True])
def test_a_wish_that_would_start_a_crossing_puts_the_side_in_question(reversible):
    """`plan` turns the cheapest way toward the wanted direction, across a forbidden sector if
    that is shorter (plus a penalty) than the long way round. Whenever it would start such a
    crossing, `piece_in_question` must say so, so that the piece planner weighs it: otherwise the
    pseudo-inverse's wish, which ignores every limit, overrules the planner. (The DP vessel at
    75 deg and 1.1 times its capability: planned to 117.6 deg, the starboard unit passed 109.5 deg,
    the wish at 60.6 deg read as reachable the long way round, and `plan` ramped it down to cross
    back: a cycle of 45 samples.) The starboard unit's sector, from every allowed angle toward every
    direction, at rest (a crossing starts at once)."""
    rotation = vehicle_from(DP).actuators[0].rotation
    if reversible:
        rotation = dataclasses.replace(rotation, reversible=True)
    thrust_range = (-300e3 if reversible else 0.0, 420e3)
    step, hold = 0.021, 42.0
    assert piece_in_question(rotation, math.radians(109.5), step, (369e3 * math.cos(math.radians(60.6)),
                                                                   369e3 * math.sin(math.radians(60.6))), hold)
    for angle in np.radians(np.arange(-180.0, 180.0, 2.5)):
        if in_forbidden_sector(rotation, angle):
            continue
        for direction in np.radians(np.arange(0.0, 360.0, 5.0)):
            desired = (369e3 * math.cos(direction), 369e3 * math.sin(direction))
            state = AzimuthState(angle=float(angle))
            plan(rotation, state, step, thrust_range, 10e3, desired, hold)
            if state.turning:
                assert piece_in_question(rotation, float(angle), step, desired, hold), \
                    (math.degrees(angle), math.degrees(direction))


@pytest.mark.parametrize("sigma", [1, -1])
def test_a_fault_during_a_ramp_to_zero_overrides_the_rate_limit(sigma):
    """A thruster ramping its thrust down at the rate limit to cross a sector (or to reverse)
    when a fault narrows its range below that ramp: the thrust goes to the range's edge at once,
    as everywhere else a fault meets a rate limit, instead of ramping on from above the new limit
    (the case make soak found: azimuth_stbd at 168 kN against a DEGRADED limit of 54 kN)."""
    vehicle = single_azimuth(azimuth_rate_max=0.5, forbidden_sectors=[1.0, 2.0], reversible=True,
                             thrust_min=-100.0)
    rotation = vehicle.actuators[0].rotation
    state = AzimuthState(angle=0.8, thrust=sigma * 90.0, sigma=sigma)
    wish = (sigma * 50.0 * math.cos(2.3), sigma * 50.0 * math.sin(2.3))   # across the sector on its side
    nominal = plan(rotation, dataclasses.replace(state), 0.05, (-100.0, 100.0), 5.0, wish, 0.01)
    assert nominal.thrust_low == nominal.thrust_high == sigma * 85.0
    degraded = plan(rotation, dataclasses.replace(state), 0.05, (-30.0, 30.0), 5.0, wish, 0.01)
    assert degraded.thrust_low == degraded.thrust_high == sigma * 30.0
