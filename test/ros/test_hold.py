"""~/hold_actuator on the node (the bench's step test): refused unless step_test.enabled and
within its bounds, the held thrust through the limits, faults and rate limits, stopped by the
watchdog, the faults in force before put back."""

import pytest
from conftest import ROOT

from allocator_pkg import Allocator, parse_parameters, read_parameters
from allocator_pkg.ros.hold import refusal

EXAMPLE = ROOT / "config" / "example1_rov.yaml"
MAIN_PORT = 2                     # index in actuators.names
RATE_STEP = 600.0 / 50.0          # main_port's thrust_rate_max [N/s] over one period at 50 Hz [N]


def hold(harness, actuator, thrust, duration):
    from allocator_msgs.srv import HoldActuator
    client = harness.probe.create_client(HoldActuator, "thrust_allocator/hold_actuator")
    response = harness.call(client, HoldActuator.Request(actuator=actuator, thrust=thrust, duration=duration))
    return response.success, response.message


def feed(harness, periods):
    """Zero wrenches, one a period, keeping the watchdog fed."""
    for _ in range(periods):
        harness.send_wrench([0.0] * 6)
        harness.tick(1)


@pytest.mark.params(EXAMPLE)
def test_a_hold_is_refused_unless_enabled(harness):
    assert hold(harness, "main_port", 10.0, 1.0) == (False, "step_test.enabled is false (enable it on the bench "
                                                            "only)")


@pytest.mark.params(EXAMPLE, step_test__enabled=True)
def test_a_hold_beyond_its_bounds_is_refused_with_the_bound(harness):
    assert hold(harness, "main_port", 60.5, 1.0) == (False, "thrust 60.5 N of main_port: at most 60 N in magnitude "
                                                            "(step_test.thrust_share 0.2 of 300 N)")
    assert hold(harness, "main_port", -60.5, 1.0)[0] is False
    assert hold(harness, "main_port", 10.0, 5.5) == (False, "duration 5.5 s: more than 0 and at most "
                                                            "step_test.duration_max 5 s")
    assert hold(harness, "main_port", 10.0, 0.0)[0] is False
    assert "unknown actuator 'bow'" in hold(harness, "bow", 10.0, 1.0)[1]
    assert harness.node.allocator.faults == {}


@pytest.mark.params(EXAMPLE, step_test__enabled=True)
def test_the_held_thrust_ramps_at_the_rate_limit_alone_and_ends_with_the_faults_as_before(harness):
    assert harness.set_fault("main_stbd", "degraded", efficiency=0.5)[0]
    feed(harness, 2)
    success, message = hold(harness, "main_port", 40.0, 0.5)
    assert success, message
    feed(harness, 1)
    first = harness.commands[-1]
    assert list(first.mode) == [2, 2, 0, 2]                     # every other actuator FAILED
    assert 0.0 < first.thrust[MAIN_PORT] <= RATE_STEP + 1e-6
    feed(harness, 5)
    held = harness.commands[-1]
    assert held.thrust[MAIN_PORT] == pytest.approx(40.0, abs=1e-3)
    assert [held.thrust[i] for i in (0, 1, 3)] == [0.0, 0.0, 0.0]
    requested = harness.status[-1].requested                    # main_port's direction [1, 0, 0] at y = -0.45
    assert (requested.force.x, requested.torque.z) == pytest.approx((40.0, 0.45 * 40.0))
    feed(harness, 25)                                           # past the 0.5 s
    assert list(harness.commands[-1].mode) == [0, 0, 0, 1]      # main_stbd DEGRADED again
    assert harness.node.allocator.faults["main_stbd"].efficiency == 0.5
    assert abs(harness.commands[-1].thrust[MAIN_PORT]) < 1.0


@pytest.mark.params(EXAMPLE, step_test__enabled=True, step_test__thrust_share=0.5)
def test_the_held_actuator_keeps_its_own_fault(harness):
    assert harness.set_fault("main_port", "degraded", efficiency=0.1)[0]     # 30 N of its 300 N
    feed(harness, 1)
    assert hold(harness, "main_port", 100.0, 2.0)[0]
    feed(harness, 15)
    assert harness.commands[-1].thrust[MAIN_PORT] == pytest.approx(30.0, abs=1e-3)


@pytest.mark.params(EXAMPLE, step_test__enabled=True, wrench_timeout=0.2)
def test_the_watchdog_stops_a_hold(harness):
    feed(harness, 1)
    assert hold(harness, "main_port", 40.0, 5.0)[0]
    feed(harness, 5)
    assert harness.commands[-1].thrust[MAIN_PORT] > 0.0
    harness.step(0.5)                                           # no wrench: stale after 0.2 s
    assert list(harness.commands[-1].thrust) == [0.0, 0.0, 0.0, 0.0]
    assert list(harness.commands[-1].mode) == [0, 0, 0, 0]      # and the hold is over
    feed(harness, 5)
    assert abs(harness.commands[-1].thrust[MAIN_PORT]) < 1e-3              # zero wrench, no hold


@pytest.mark.params(EXAMPLE, step_test__enabled=True)
def test_a_hold_is_refused_while_the_input_is_stale_and_lasts_its_duration_once_fed(harness):
    """The watchdog ends a hold at the first sample that finds the input stale: a hold accepted
    before any wrench came (or after wrench_timeout without one) would end at the next sample,
    1/rate_hz later, whenever the client's first wrench is slower than that."""
    stale = hold(harness, "azimuth_fwd", 15.0, 1.0)
    assert stale == (False, "wrench_command is stale (no valid wrench for 0.5 s): send wrenches (zero) on it "
                            "before and during the hold, which the watchdog ends as soon as it is stale")
    harness.tick(1)
    assert list(harness.commands[-1].mode) == [0, 0, 0, 0] and harness.node.allocator.faults == {}
    feed(harness, 1)
    assert hold(harness, "azimuth_fwd", 15.0, 1.0)[0]
    harness.tick(1)                                             # no wrench in this period: 20 ms < 0.5 s
    assert list(harness.commands[-1].mode) == [0, 2, 2, 2]
    assert harness.status[-1].requested.force.x == pytest.approx(15.0)       # azimuth_fwd at 0 rad: along x
    feed(harness, 48)                                           # 0.98 s of the 1 s
    assert list(harness.commands[-1].mode) == [0, 2, 2, 2]
    feed(harness, 2)
    assert list(harness.commands[-1].mode) == [0, 0, 0, 0]
    harness.step(0.6)                                           # no wrench for 0.5 s: stale again
    assert hold(harness, "azimuth_fwd", 15.0, 1.0)[0] is False


def bench(path, **overrides):
    """The allocator and node settings of a params file, step_test.enabled."""
    vehicle, settings = parse_parameters({**read_parameters(path), "step_test.enabled": True, **overrides})
    return Allocator(vehicle), settings


def test_a_control_surface_an_inactive_node_and_an_actuator_off_the_dofs_are_refused():
    allocator, settings = bench(ROOT / "config" / "infante_auv.yaml")
    assert refusal(allocator, settings, "fin_bow_port", 1.0, 1.0, active=True) == \
        "fin_bow_port is a control surface: it has no thrust of its own to hold"
    assert refusal(allocator, settings, "thruster_port", 1.0, 1.0, active=False) == \
        "not active: no samples to hold an actuator in"
    assert refusal(allocator, settings, "thruster_port", 1.0, 1.0, active=True) is None
    planar, settings = bench(ROOT / "config" / "bluerov2_heavy.yaml", dofs=["surge", "sway", "yaw"])
    assert refusal(planar, settings, "thruster_5", 1.0, 1.0, active=True) == \
        "thruster_5 acts on none of the controlled DOFs (surge, sway, yaw)"


def test_a_hold_gives_back_the_failed_redundancy_groups():
    from allocator_pkg import load_vehicle
    from allocator_pkg.ros.hold import Hold
    allocator = Allocator(load_vehicle(ROOT / "config" / "dp_vessel.yaml"))
    allocator.set_group_fault("switchboard_b")
    held = Hold.start(allocator, "azimuth_stbd", 1000.0, 0)
    assert allocator.modes().tolist() == [0, 2, 2, 2]
    held.release(allocator)
    assert allocator.group_faults == ("switchboard_b",) and allocator.power.available.tolist() == [5600.0, 0.0]
    assert allocator.modes().tolist() == [0, 2, 0, 2]
