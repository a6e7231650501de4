"""The frames of an allocator-sim recording (allocator_pkg.cli.sim_recording): /tf chains map
(ENU) -> ned -> base_link (FRD) so that a point of the body lands where the odometry puts it."""

import math

import numpy as np
import pytest
from nav_msgs.msg import Odometry

from allocator_pkg.cli.sim_recording import transforms
from allocator_pkg.simulation.kinematics import quaternion, rotation


def rotate(q: dict, v: np.ndarray) -> np.ndarray:
    """``v`` rotated by the unit quaternion ``q`` (x, y, z, w)."""
    u, w = np.array([q["x"], q["y"], q["z"]]), q["w"]
    return v + 2.0 * np.cross(u, np.cross(u, v) + w * v)


def in_parent(transform: dict, point: np.ndarray) -> np.ndarray:
    t = transform["transform"]
    translation = np.array([t["translation"][k] for k in "xyz"])
    return rotate(t["rotation"], point) + translation


def odometry(position, roll, pitch, yaw) -> Odometry:
    message = Odometry()
    message.header.frame_id, message.child_frame_id = "ned", "base_link"
    message.header.stamp.sec, message.header.stamp.nanosec = 101, 500
    p, o = message.pose.pose.position, message.pose.pose.orientation
    p.x, p.y, p.z = position
    o.x, o.y, o.z, o.w = quaternion(roll, pitch, yaw)
    return message


@pytest.mark.parametrize("attitude", [(0.0, 0.0, 0.0), (0.0, 0.0, math.pi / 2), (0.1, -0.2, 2.5)])
def test_a_body_point_lands_in_map_at_the_east_north_up_of_its_ned_position(attitude):
    position = np.array([1.0, 2.0, 3.0])                   # north, east, down
    message = transforms(odometry(position, *attitude))
    world, body = message["transforms"]
    assert (world["header"]["frame_id"], world["child_frame_id"]) == ("map", "ned")
    assert (body["header"]["frame_id"], body["child_frame_id"]) == ("ned", "base_link")
    assert world["header"]["stamp"] == body["header"]["stamp"] == {"sec": 101, "nanosec": 500}
    for point in (np.zeros(3), np.array([1.0, 0.0, 0.0]), np.array([0.3, -0.4, 0.5])):   # FRD
        ned = position + rotation(*attitude) @ point
        assert in_parent(world, in_parent(body, point)) == pytest.approx([ned[1], ned[0], -ned[2]], abs=1e-12)


def test_heading_east_points_the_bow_along_map_x_and_down_along_minus_z():
    world, body = transforms(odometry((0.0, 0.0, 0.0), 0.0, 0.0, math.pi / 2))["transforms"]
    assert in_parent(world, in_parent(body, np.array([1.0, 0.0, 0.0]))) == pytest.approx([1.0, 0.0, 0.0], abs=1e-12)
    assert in_parent(world, in_parent(body, np.array([0.0, 0.0, 1.0]))) == pytest.approx([0.0, 0.0, -1.0], abs=1e-12)
