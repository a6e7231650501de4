"""Messages to and from the library's arrays and results."""

import math

import numpy as np
from builtin_interfaces.msg import Time
from conftest import ROOT
from std_msgs.msg import Header

from allocator_pkg import Allocator, load_vehicle
from allocator_pkg.ros.conversions import array_to_wrench, commands_message, status_message, wrench_to_array


def test_wrench_round_trip_in_dof_order():
    values = np.array([1.0, -2.0, 3.5, 0.25, -0.5, 7.0])
    wrench = array_to_wrench(values)
    assert (wrench.force.x, wrench.force.y, wrench.force.z) == (1.0, -2.0, 3.5)
    assert (wrench.torque.x, wrench.torque.y, wrench.torque.z) == (0.25, -0.5, 7.0)
    assert np.array_equal(wrench_to_array(wrench), values)


def test_commands_and_status_carry_one_sample():
    allocator = Allocator(load_vehicle(ROOT / "config" / "example1_rov.yaml"))
    result = allocator.allocate([50.0, 10.0, 0.0, 0.0, 0.0, 5.0])
    stamp = Time(sec=3, nanosec=7)
    commands = commands_message(result, allocator.names, Header(stamp=stamp, frame_id="base_link"))
    assert commands.header.stamp == stamp and commands.header.frame_id == "base_link"
    assert list(commands.name) == list(allocator.names)
    assert np.array_equal(commands.thrust, result.thrust) and np.array_equal(commands.azimuth, result.azimuth)
    assert np.array_equal(commands.command, result.command) and list(commands.mode) == [0, 0, 0, 0]
    status = status_message(result, "solved here", Header(stamp=stamp, frame_id="base_link"))
    assert status.solver_status == "solved here" and status.method == "qp"
    assert np.allclose(wrench_to_array(status.achieved), result.achieved)
    assert status.requested.force.x == 50.0 and status.saturated == result.saturated
    assert status.header.frame_id == "base_link"


def test_status_in_flu_flips_y_and_z_of_forces_and_moments():
    allocator = Allocator(load_vehicle(ROOT / "config" / "example1_rov.yaml"))
    result = allocator.allocate([50.0, 10.0, 0.0, 0.0, 0.0, 5.0])
    status = status_message(result, "solved", Header(), frame="flu")
    assert list(wrench_to_array(status.requested)) == [50.0, -10.0, -0.0, 0.0, -0.0, -5.0]
    assert np.allclose(wrench_to_array(status.achieved), result.achieved * [1, -1, -1, 1, -1, -1])


def test_status_carries_the_unallocated_wrench_in_the_nodes_frame_the_limit_flags_and_the_voltage():
    allocator = Allocator(load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml"))
    result = allocator.allocate([0.0, 30.0, 400.0, 0.0, 0.0, 0.0])
    assert result.saturated
    frd = status_message(result, "solved", Header(), voltage=allocator.voltage)
    flu = status_message(result, "solved", Header(), frame="flu", voltage=allocator.voltage)
    assert np.allclose(wrench_to_array(frd.unallocated), result.requested - result.achieved)
    assert np.allclose(wrench_to_array(flu.unallocated), (result.requested - result.achieved) * [1, -1, -1, 1, -1, -1])
    assert frd.unallocated.force.z > 100.0
    assert list(frd.at_thrust_limit) == result.at_thrust_limit.tolist() and any(frd.at_thrust_limit)
    assert list(frd.at_rate_limit) == [False] * 8
    assert frd.voltage == 16.0
    assert math.isnan(status_message(result, "solved", Header()).voltage)


def test_a_message_filled_again_carries_only_the_new_sample():
    """The node fills one ThrusterCommands and one AllocationStatus every sample: every field
    must be the new sample's, none left from the one before."""
    allocator = Allocator(load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml"))
    first = allocator.allocate([0.0, 30.0, 400.0, 0.0, 0.0, 0.0])
    allocator.set_voltage(14.0)
    second = allocator.allocate([5.0, 0.0, 0.0, 0.0, 0.0, 1.0])
    assert first.saturated and not second.saturated
    commands = commands_message(first, allocator.names, Header(frame_id="a"))
    status = status_message(first, "first", Header(frame_id="a"), frame="flu")
    assert math.isnan(status.voltage)
    again = commands_message(second, allocator.names, Header(frame_id="b"), commands)
    filled = status_message(second, "second", Header(frame_id="b"), voltage=14.0, message=status)
    assert again is commands and filled is status
    assert again == commands_message(second, allocator.names, Header(frame_id="b"))
    assert filled == status_message(second, "second", Header(frame_id="b"), voltage=14.0)
    assert not filled.saturated and filled.voltage == 14.0 and filled.solver_status == "second"
