"""The direction check: ~/hold_actuator on the node (refused unless step_test.enabled, bounded,
through the limits, faults and rate limits, stopped by the watchdog, the faults put back), the
words of each direction, and allocator-ctl step-test against a node process."""

import subprocess

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.cli.step_test import MOTIONS, describe, motion
from allocator_pkg.ros.process import child_process, executable, node_command
from allocator_pkg.vehicle.config import DOF_NAMES
from allocator_pkg.vehicle.frames import wrench_between
from allocator_pkg.vehicle.node_settings import FLU, FRD

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
    success, message = hold(harness, "main_port", 10.0, 1.0)
    assert not success and "step_test.enabled is false" in message


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


def test_flu_words_are_the_frd_words_of_the_same_wrench():
    for i, dof in enumerate(DOF_NAMES):
        for sign in (1.0, -1.0):
            flu = np.zeros(6)
            flu[i] = sign
            frd = wrench_between(flu, FLU)
            assert motion(dof, sign, FLU) == motion(dof, frd[i], FRD)


def test_frd_words_follow_the_axes_and_the_right_hand_rule():
    """x forward, y starboard, z down: +Z pushes down; +N about z down turns x toward y, the nose
    to starboard; +M about y turns z toward x, so x toward -z, the nose up; +K turns y toward z,
    the starboard side down."""
    assert [MOTIONS[FRD][dof][0] for dof in DOF_NAMES] == ["move forward", "move to starboard", "move down",
                                                          "roll starboard side down", "pitch nose up",
                                                          "turn nose to starboard"]
    assert describe(np.array([40.0, 0.0, 0.0, 0.0, 0.0, 18.0]), ["surge", "sway", "yaw"], FRD) == \
        "surge +40.0 N (move forward), yaw +18.0 N m (turn nose to starboard)"


def test_the_tool_steps_each_dof_and_holds_each_actuator_of_a_running_node():
    with child_process(node_command(EXAMPLE, parameters=["step_test.enabled:=true"])):
        ctl = [str(executable("allocator-ctl")), "step-test", "--share", "0.1", "--hold", "0.6", "--rest", "0.2"]
        steps = subprocess.run(ctl, capture_output=True, text=True, timeout=60)
        held = subprocess.run([*ctl, "--actuators"], capture_output=True, text=True, timeout=60)
    assert steps.returncode == 0, steps.stderr
    lines = steps.stdout.splitlines()
    assert lines[0].startswith("step test: 3 DOFs (surge, sway, yaw)")
    surge = next(i for i, line in enumerate(lines) if line.startswith("surge +:"))
    assert lines[surge].endswith("the vehicle should move forward")
    assert [line.split()[0] for line in lines[surge + 1:surge + 5]] == ["azimuth_fwd", "azimuth_aft", "main_port",
                                                                        "main_stbd"]
    # 10 % of the surge capability with nothing failed; main_port and main_stbd push forward.
    assert all(float(lines[surge + k].split()[1]) > 0.0 for k in (3, 4))
    assert any(line.startswith("yaw -:") and line.endswith("should turn nose to port") for line in lines)
    assert held.returncode == 0, held.stdout + held.stderr
    port = held.stdout.split("main_port: +30.0 N alone")[1]
    assert port.split("\n")[3].split()[:3] == ["main_port", "30.00", "N"]
    # main_port alone at 30 N: along x at y = -0.45 m, N = x F_y - y F_x = +13.5 N m
    assert "pushes the vehicle: surge +30.0 N (move forward), yaw +13.5 N m (turn nose to starboard)" in port
