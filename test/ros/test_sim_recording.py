"""The frames of an allocator-sim recording (allocator_pkg.ros.sim_recording): /tf chains map
(ENU) -> ned -> base_link (FRD) so that a point of the body lands where the odometry puts it; a
short run records /tf with every odometry, the node's thrust markers and its diagnostics, all
on the run's time (0 s at its first step, as its events).

:func:`recorded` runs a shipped scenario short once per session (test_foxglove_layout reads
the same recordings)."""

import math
import re

import numpy as np
import pytest
from conftest import ROOT
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from nav_msgs.msg import Odometry
from rosbags.typesys import Stores, get_typestore
from test_recording import rosbags_messages
from visualization_msgs.msg import Marker, MarkerArray

from allocator_msgs.msg import ActuatorFault
from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.ros.recording import fields
from allocator_pkg.ros.sim_recording import TOPICS, shifted, transforms
from allocator_pkg.simulation.kinematics import quaternion, rotation
from allocator_pkg.simulation.scenario import load_scenario


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


RUNS: dict[str, tuple] = {}
SHORT = {"dp_azimuth_failure": 0.05, "rov_battery_sag": 0.05}
"""Shipped scenarios recorded here, each with the scale of its duration."""


def recorded(name: str, tmp_path_factory) -> tuple:
    """(scenario, output folder, the recording's messages as rosbags decodes them) of a shipped
    scenario run short, once per session."""
    if name not in RUNS:
        from allocator_pkg.cli.allocator_sim import run

        case = load_scenario(ROOT / "config" / "scenarios" / f"{name}.yaml").scaled(SHORT[name])
        out = tmp_path_factory.mktemp(name)
        run(case, out, log=lambda _: None)
        RUNS[name] = (case, out, rosbags_messages(out / "run.mcap"))
    return RUNS[name]


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(SHORT))
def test_a_run_records_tf_for_every_odometry_and_the_nodes_markers_and_diagnostics(name, tmp_path_factory):
    case, out, messages = recorded(name, tmp_path_factory)
    odometry, tf = messages["/odometry"], messages["/tf"]
    assert len(tf) == len(odometry) == len(messages["/clock"])
    for pose, message in zip(odometry, tf):
        world, body = message.transforms
        assert (world.header.frame_id, world.child_frame_id, body.header.frame_id, body.child_frame_id) == (
            "map", "ned", "ned", "base_link")
        assert (body.header.stamp.sec, body.header.stamp.nanosec) == (pose.header.stamp.sec, pose.header.stamp.nanosec)
        assert (body.transform.translation.x, body.transform.rotation.z) == (pose.pose.pose.position.x,
                                                                            pose.pose.pose.orientation.z)
    start, end = (_stamp_ns(odometry[0]), _stamp_ns(odometry[-1]))
    markers = messages[TOPICS["markers"]]
    vehicle = load_vehicle(case.vehicle)
    period = round(1e9 / min(vehicle.rate_hz, 10.0))                   # markers_rate_hz: 10 by default
    assert len(markers) >= (end - start) // period - 1
    for message in markers:
        assert {marker.header.frame_id for marker in message.markers} == {"base_link"}
        assert start <= _stamp_ns(message.markers[0]) <= end
        assert len(message.markers) == 2 * len(vehicle.actuators)
    diagnostics = messages[TOPICS["diagnostics"]]
    assert len(diagnostics) >= int(case.duration) - 1                 # one a second of sim time
    assert re.fullmatch(r"/run_\d+_[0-9a-f]{8}/thrust_allocator: thrust allocation",   # the run's namespace
                        diagnostics[-1].status[0].name)
    with open(out / "run.mcap", "rb") as stream:
        summary = make_reader(stream).get_summary()
    hashes = {c.topic: c.metadata["topic_type_hash"] for c in summary.channels.values()}
    assert hashes["/tf"] == get_typestore(Stores.ROS2_JAZZY).hash_rihs01("tf2_msgs/msg/TFMessage")


def _stamp_ns(message) -> int:
    return message.header.stamp.sec * 1_000_000_000 + message.header.stamp.nanosec


@pytest.mark.slow
def test_battery_state_is_recorded_only_for_a_scenario_with_a_supply_voltage(tmp_path_factory):
    """The DP vessel's scenario gives no voltage: no /battery_state; the ROV's battery sag does; the
    run.mcap topics of docs/closed_loop.md say so."""
    assert load_scenario(ROOT / "config" / "scenarios" / "dp_azimuth_failure.yaml").voltage is None
    assert "/battery_state" not in recorded("dp_azimuth_failure", tmp_path_factory)[2]
    assert recorded("rov_battery_sag", tmp_path_factory)[2]["/battery_state"]
    text = " ".join((ROOT / "docs" / "closed_loop.md").read_text().split())
    assert "`/battery_state` (when the scenario gives a supply `voltage`)" in text


def test_every_time_of_a_message_moves_onto_the_runs_time_but_durations():
    markers = MarkerArray(markers=[Marker()])
    markers.markers[0].header.stamp.sec, markers.markers[0].header.stamp.nanosec = 130, 250_000_000
    markers.markers[0].lifetime.sec = 130
    moved = shifted(fields(markers), 120_500_000_000)
    assert moved["markers"][0]["header"]["stamp"] == {"sec": 9, "nanosec": 750_000_000}
    assert moved["markers"][0]["lifetime"] == {"sec": 130, "nanosec": 0}          # a duration, not a time
    clock = {"clock": {"sec": 121, "nanosec": 0}}
    assert shifted(clock, 120_500_000_000, ("stamp", "clock")) == {"clock": {"sec": 0, "nanosec": 500_000_000}}


@pytest.mark.slow
def test_the_recording_starts_at_0_s_with_the_run_and_its_events(tmp_path_factory):
    """The port azimuth fails at 5 s of the shortened dp_azimuth_failure: the node's commands say
    FAILED from the step at 5 s of the recording on, as in metrics.json and the figures."""
    case, out, _ = recorded("dp_azimuth_failure", tmp_path_factory)
    fault = next(e for e in case.events if e.kind == "fault")
    port = load_vehicle(case.vehicle).names.index(fault.actuator)
    times: dict[str, list[int]] = {}
    failed_at = None
    with open(out / "run.mcap", "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        for _, channel, record, message in reader.iter_decoded_messages():
            times.setdefault(channel.topic, []).append(record.log_time)
            stamp = getattr(message, "header", None)
            if stamp is not None:
                assert _stamp_ns(message) == record.log_time, channel.topic       # stamps on the same time
            failing = channel.topic == "/thruster_commands" and message.mode[port] == ActuatorFault.FAILED
            if failing and failed_at is None:
                failed_at = record.log_time
        assert reader.get_summary().statistics.message_start_time == 0
    assert times["/clock"][0] == times["/odometry"][0] == 0
    assert failed_at * 1e-9 == pytest.approx(fault.time, abs=1e-6)
