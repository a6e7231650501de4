"""The runtime's outputs in a node on simulated time: the status at most status_rate_hz and
only while someone subscribes, the thrust markers at most markers_rate_hz, the per-actuator
topics. The ros2_control arrays: test_ros2_control.py."""

import numpy as np
import pytest
from conftest import ROOT

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


def stamp_ns(message) -> int:
    from rclpy.time import Time
    return Time.from_msg(message.header.stamp).nanoseconds


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0, status_rate_hz=10.0)
def test_status_goes_out_at_most_status_rate_hz_while_commands_go_out_every_sample(harness):
    harness.send_wrench([150.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    commands, statuses = len(harness.commands), len(harness.status)
    harness.tick(50)                                              # one second at 50 Hz
    harness.spin_for(0.2)
    assert len(harness.commands) - commands == 50
    reported = harness.status[statuses:]
    assert 9 <= len(reported) <= 10
    assert np.diff([stamp_ns(s) for s in reported]).min() >= 10**8
    sampled = {stamp_ns(c) for c in harness.commands}
    assert all(stamp_ns(s) in sampled for s in reported)         # each status is one sample's
    assert harness.set_parameters({"status_rate_hz": 0.0}) == (True, "")
    before = len(harness.status)
    harness.tick(10)
    harness.spin_for(0.2)
    assert len(harness.status) - before == 10                     # every sample again


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_status_is_neither_built_nor_published_while_nobody_subscribes(harness):
    from allocator_msgs.msg import AllocationStatus
    runtime = harness.node.runtime
    topic = harness.probe.resolve_topic_name("allocation_status")
    subscription = next(s for s in harness.probe.subscriptions if s.topic_name == topic)
    harness.probe.destroy_subscription(subscription)
    harness.spin_until(lambda: harness.node.count_subscribers("allocation_status") == 0)
    published, samples = runtime.statuses_published, harness.node.samples
    for _ in range(5):
        before = len(harness.commands)
        harness.advance(harness.node.period)
        harness.spin_until(lambda before=before: len(harness.commands) > before)
    assert harness.node.samples == samples + 5 and runtime.statuses_published == published
    harness.probe.create_subscription(AllocationStatus, "allocation_status", harness.status.append, 100)
    harness.spin_until(lambda: harness.node.count_subscribers("allocation_status") == 1)
    received = len(harness.status)
    harness.tick(3)
    assert runtime.statuses_published == published + 3 and len(harness.status) == received + 3


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0, status_rate_hz=10.0)
def test_a_clock_set_back_does_not_silence_the_status(harness):
    harness.tick(100)                                             # two seconds at 50 Hz
    before = len(harness.status)
    harness.time_ns -= 10**9                                      # a second back: a simulator restarting
    harness.advance(harness.node.period)                          # (the timer restarts a period after the jump)
    harness.tick(2)
    harness.spin_for(0.2)
    assert len(harness.status) > before
    assert stamp_ns(harness.status[-1]) <= harness.time_ns


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0, frame="flu")
def test_thrust_markers_at_most_ten_per_second_along_each_force(harness):
    from visualization_msgs.msg import MarkerArray
    markers = []
    harness.probe.create_subscription(MarkerArray, "thrust_allocator/thrust_markers", markers.append, 100)
    harness.spin_until(lambda: harness.node.count_subscribers("~/thrust_markers") > 0)
    harness.send_wrench([150.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(50)                                              # one second at 50 Hz
    harness.spin_for(0.2)
    assert 9 <= len(markers) <= 10
    last = markers[-1].markers
    arrows = [m for m in last if m.ns == "thrust"]
    assert len(arrows) == 4 and len([m for m in last if m.ns == "actuators"]) == 4
    assert {m.header.frame_id for m in last} == {"base_link"}
    port = arrows[2]                                              # main_port: [-1.3, -0.45, 0] FRD, along +x
    start, end = port.points
    assert (start.x, start.y, start.z) == pytest.approx((-1.3, 0.45, 0.0))        # FLU: y to port is +
    sample = next(c for c in reversed(harness.commands) if c.header.stamp == port.header.stamp)
    from allocator_pkg.ros.markers import scale
    length, force = scale(harness.node.allocator.vehicle)
    assert end.x - start.x == pytest.approx(sample.thrust[2] / force * length)
    assert (end.y, end.z) == pytest.approx((start.y, start.z))


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0, markers_rate_hz=0.0)
def test_thrust_markers_off(harness):
    from visualization_msgs.msg import MarkerArray
    markers = []
    harness.probe.create_subscription(MarkerArray, "thrust_allocator/thrust_markers", markers.append, 100)
    harness.spin_until(lambda: harness.node.count_subscribers("~/thrust_markers") > 0)
    harness.tick(20)
    harness.spin_for(0.2)
    assert markers == []


@pytest.mark.params(EXAMPLE, per_actuator_topics=True, wrench_timeout=0.0)
def test_per_actuator_topics(harness):
    from std_msgs.msg import Float64
    thrust, azimuth = [], []
    harness.probe.create_subscription(Float64, "thrusters/main_stbd/thrust", thrust.append, 10)
    harness.probe.create_subscription(Float64, "thrusters/azimuth_fwd/azimuth", azimuth.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("thrusters/main_stbd/thrust") > 0)
    harness.send_wrench([60.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(3)
    expected = harness.commands[-1]
    harness.spin_until(lambda: thrust and azimuth and thrust[-1].data == expected.thrust[3]
                       and azimuth[-1].data == expected.azimuth[0])
    assert expected.thrust[3] > 0.0


def test_per_actuator_topics_set_while_a_managed_node_is_active_publish_at_once(allocator_harness):
    """A lifecycle publisher made after rclpy enabled the others is enabled when it is made."""
    from std_msgs.msg import Float64
    harness = allocator_harness(EXAMPLE, {"wrench_timeout": 0.0}, node="lifecycle")
    assert harness.set_parameters({"per_actuator_topics": True}) == (True, "")
    thrust = []
    harness.probe.create_subscription(Float64, "thrusters/main_stbd/thrust", thrust.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("thrusters/main_stbd/thrust") > 0)
    harness.send_wrench([60.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(3)
    expected = harness.commands[-1].thrust[3]
    harness.spin_until(lambda: thrust and thrust[-1].data == expected)
    assert expected > 0.0
