"""allocator-ctl step-test, the direction check: the words of each direction, and the tool
against a node process."""

import subprocess

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.ros.process import child_process, executable, namespace_arguments, node_command
from allocator_pkg.ros.step_test_client import MOTIONS, describe, motion
from allocator_pkg.vehicle.config import DOF_NAMES
from allocator_pkg.vehicle.frames import wrench_between
from allocator_pkg.vehicle.node_settings import FLU, FRD

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


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


@pytest.mark.slow
def test_the_tool_steps_each_dof_and_holds_each_actuator_of_a_running_node(namespace):
    """The actuators first, on a node that has had no wrench yet (its input stale): the first
    actuator is held for the whole step too, not released by the watchdog at the next sample.
    At 500 Hz that sample comes 2 ms after the hold starts, sooner than a client's first wrench."""
    with child_process(node_command(EXAMPLE, *namespace_arguments(namespace),
                                    parameters=["step_test.enabled:=true", "rate_hz:=500.0"])):
        ctl = [str(executable("allocator-ctl")), "--namespace", namespace, "step-test", "--share", "0.1", "--hold",
               "0.6", "--rest", "0.2"]
        held = subprocess.run([*ctl, "--actuators"], capture_output=True, text=True, timeout=60)
        steps = subprocess.run(ctl, capture_output=True, text=True, timeout=60)
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
    first = held.stdout.split("azimuth_fwd: +15.0 N alone")[1]
    assert first.split("\n")[1].split()[:3] == ["azimuth_fwd", "15.00", "N"]
    # azimuth_fwd at its first angle, 0 rad: along x at y = 0, no yaw moment.
    assert first.split("\n")[5] == "    pushes the vehicle: surge +15.0 N (move forward)"
    port = held.stdout.split("main_port: +30.0 N alone")[1]
    assert port.split("\n")[3].split()[:3] == ["main_port", "30.00", "N"]
    # main_port alone at 30 N: along x at y = -0.45 m, N = x F_y - y F_x = +13.5 N m
    assert "pushes the vehicle: surge +30.0 N (move forward), yaw +13.5 N m (turn nose to starboard)" in port
