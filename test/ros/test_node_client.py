"""allocator_pkg.simulation.controller: the nonlinear PD + integral law in the body frame and
its anti-windup, against hand calculations."""

import math

import numpy as np
import pytest

from allocator_pkg.simulation.controller import Gains, StationKeeping


def planar(ki=(0.1, 0.2, 0.3)):
    return StationKeeping(Gains(kp=(10.0, 20.0, 30.0), kd=(1.0, 2.0, 3.0), ki=ki))


def test_the_error_is_rotated_into_the_body_frame():
    controller = planar()
    # heading east (90 deg), 1 m north of the set-point: north is the vessel's port side (-y),
    # so the controller pushes to starboard
    tau = controller.wrench(np.array([1.0, 0.0, math.pi / 2]), np.zeros(3), np.array([0.0, 0.0, math.pi / 2]))
    assert tau == pytest.approx([0.0, 20.0, 0.0], abs=1e-12)       # the sway gain acts
    tau = controller.wrench(np.zeros(3), np.array([0.5, -1.0, 0.1]), np.array([0.0, 0.0, 0.2]))
    assert tau == pytest.approx([-0.5, 2.0, 30.0 * 0.2 - 0.3])


def test_heading_errors_wrap():
    controller = planar()
    e = controller.error(np.array([0, 0, math.radians(179)]), np.array([0, 0, math.radians(-179)]))
    assert e[2] == pytest.approx(math.radians(-2))


def test_integral_action_integrates_the_error():
    controller = planar()
    for _ in range(10):
        controller.integrate(np.array([1.0, -2.0, 0.1]), np.zeros(3), 0.5)
    assert controller.integral == pytest.approx([5.0, -10.0, 0.5])
    tau = controller.wrench(np.zeros(3), np.zeros(3), np.zeros(3))
    assert tau == pytest.approx([-0.5, 2.0, -0.15])


def test_anti_windup_stops_a_dof_whose_shortfall_integrating_would_grow():
    controller = StationKeeping(Gains(kp=(1.0,) * 3, kd=(0.0,) * 3, ki=(1.0,) * 3, unallocated_threshold=(5.0,) * 3))
    eta = np.array([2.0, -2.0, 0.0])            # north +2 m: the request pushes south (negative X)
    # unallocated X = -10 N (short in the direction integrating pushes): frozen in surge;
    # Y short by +10 N, and integrating (east error -2) also pushes +Y: frozen in sway too
    controller.integrate(eta, np.zeros(3), 1.0, unallocated=np.array([-10.0, 10.0, 0.0]))
    assert controller.integral == pytest.approx([0.0, 0.0, 0.0])
    # a shortfall the other way, or below the threshold, does not stop it
    controller.integrate(eta, np.zeros(3), 1.0, unallocated=np.array([10.0, 4.0, 0.0]))
    assert controller.integral == pytest.approx([2.0, -2.0, 0.0])


def test_anti_windup_reads_the_body_frame_shortfall_at_the_heading():
    controller = StationKeeping(Gains(kp=(1.0,) * 3, kd=(0.0,) * 3, ki=(1.0,) * 3))
    eta = np.array([1.0, 0.0, math.pi / 2])     # heading east; north error pushes the hull to starboard (+Y body)
    controller.integrate(eta, np.zeros(3), 1.0, unallocated=np.array([0.0, 3.0, 0.0]))
    assert controller.integral[0] == pytest.approx(0.0, abs=1e-12)
    controller.integrate(eta, np.zeros(3), 1.0, unallocated=np.array([3.0, 0.0, 0.0]))
    assert controller.integral[0] == pytest.approx(1.0)


def test_six_dof_rotates_the_position_error_only():
    controller = StationKeeping(Gains(kp=(1.0, 1.0, 2.0, 3.0, 3.0, 3.0), kd=(0.0,) * 6, ki=(0.0,) * 6))
    eta = np.array([0.0, 0.0, 1.0, 0.1, 0.0, 0.0])     # 1 m deep of the set-point, rolled 0.1 rad
    tau = controller.wrench(eta, np.zeros(6), np.zeros(6))
    # down error (0, 0, 1) in a body rolled by 0.1: (0, sin 0.1, cos 0.1), times the body gains
    assert tau[:3] == pytest.approx(-np.array([0.0, math.sin(0.1), 2.0 * math.cos(0.1)]))
    assert tau[3] == pytest.approx(-0.3)


def test_bad_gains_are_refused():
    with pytest.raises(ValueError, match=r"3 .* or 6"):
        Gains(kp=(1.0, 2.0), kd=(1.0, 2.0), ki=(1.0, 2.0))
    with pytest.raises(ValueError, match=r"controller\.kd"):
        Gains(kp=(1.0,) * 3, kd=(1.0, -2.0, 1.0), ki=(0.0,) * 3)
    with pytest.raises(ValueError, match="unallocated_threshold"):
        Gains(kp=(1.0,) * 3, kd=(1.0,) * 3, ki=(0.0,) * 3, unallocated_threshold=(1.0,))


def test_settle_answers_a_steady_force_with_the_integral_alone():
    controller = planar()
    eta = np.array([0.0, 0.0, math.radians(30.0)])
    force = np.array([1000.0, -2000.0, 300.0])
    controller.settle(eta, force)
    assert controller.wrench(eta, np.zeros(3), eta) == pytest.approx(-force)
