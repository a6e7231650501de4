"""The shared runtime in a node on simulated time: the input trigger, body frames, stamped
input, parameter types and QoS overrides. Its outputs: test_outputs.py; process-level
behaviour: test_process.py."""

import numpy as np
import pytest
from conftest import ROOT, vehicle_from

from allocator_pkg import Allocator

EXAMPLE = ROOT / "config" / "example1_rov.yaml"
FLU = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])


def requested(status):
    from allocator_pkg.ros.conversions import wrench_to_array
    return list(wrench_to_array(status.requested))


@pytest.mark.params(EXAMPLE, trigger="input", wrench_timeout=0.5)
def test_input_trigger_allocates_each_wrench_at_once_and_coalesces_the_rest(harness):
    period = harness.node.period
    harness.send_wrench([5.0, 0.0, 0.0, 0.0, 0.0, 0.0])          # at the start's (stale) sample: waits
    harness.advance(period)                                       # for the timer, a period later
    assert requested(harness.status[-1])[0] == 5.0
    harness.advance(period)                                       # nothing new: no sample
    before = harness.node.samples
    harness.send_wrench([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])          # a period after the last sample
    harness.spin_until(lambda: len(harness.status) > before)     # no clock step: allocated on arrival
    assert harness.node.samples == before + 1 and requested(harness.status[-1])[0] == 10.0
    stamp = harness.commands[-1].header.stamp
    assert stamp.sec * 10**9 + stamp.nanosec == harness.time_ns
    harness.send_wrench([20.0, 0.0, 0.0, 0.0, 0.0, 0.0])         # within the period: they wait,
    harness.send_wrench([30.0, 0.0, 0.0, 0.0, 0.0, 0.0])         # the newest replacing the older
    harness.spin_for(0.1)
    assert harness.node.samples == before + 1
    harness.advance(period)                                       # one period after the last sample
    harness.spin_until(lambda: harness.node.samples == before + 2)
    assert requested(harness.status[-1])[0] == 30.0
    harness.advance(period)                                       # nothing new: no sample
    assert harness.node.samples == before + 2
    harness.advance(0.5)                                          # input stopped: the watchdog's zero
    harness.spin_until(lambda: harness.status[-1].solver_status.startswith("stale"))
    assert all(t == 0.0 for t in harness.commands[-1].thrust)
    count = harness.node.samples
    harness.advance(period)
    assert harness.node.samples == count + 1                      # zero thrust every period while stale


@pytest.mark.params(EXAMPLE, trigger="input", wrench_timeout=0.5)
def test_input_trigger_never_samples_faster_than_rate_hz(harness):
    period = harness.node.period
    stamps = []
    for _ in range(20):                      # a wrench every half period
        harness.advance(period / 2)
        harness.send_wrench([10.0, 0.0, 0.0, 0.0, 0.0, 1.0])
        stamps.append(harness.commands[-1].header.stamp.sec * 10**9 + harness.commands[-1].header.stamp.nanosec)
    intervals = np.diff(sorted(set(stamps)))
    assert intervals.min() >= round(period * 1e9)


@pytest.mark.params(EXAMPLE, frame="flu", wrench_timeout=0.0)
def test_a_flu_wrench_is_converted_at_the_boundary(harness):
    core = Allocator(vehicle_from(EXAMPLE))
    for _ in range(harness.node.samples):
        core.allocate(np.zeros(6))
    frd = np.array([100.0, 20.0, 0.0, 0.0, 0.0, 10.0])
    harness.send_wrench(frd * FLU)                               # the same wrench, as base_link (FLU) gives it
    harness.tick(5)
    for _ in range(5):
        expected = core.allocate(frd)
    assert np.array(harness.commands[-1].thrust) == pytest.approx(expected.thrust)
    assert np.array(harness.commands[-1].azimuth) == pytest.approx(expected.azimuth)
    status = harness.status[-1]
    assert requested(status) == list(frd * FLU)
    from allocator_pkg.ros.conversions import wrench_to_array
    assert wrench_to_array(status.achieved) == pytest.approx(expected.achieved * FLU)
    assert status.header.frame_id == harness.commands[-1].header.frame_id == "base_link"


@pytest.mark.params(EXAMPLE, wrench_type="wrench_stamped", base_frame="base_link_frd", wrench_timeout=0.0)
def test_a_stamped_wrench_in_another_frame_is_rejected_and_counted(harness):
    harness.send_wrench([80.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.send_wrench([50.0, 0.0, 0.0, 0.0, 0.0, 0.0], frame_id="odom")
    harness.send_wrench([40.0, 0.0, 0.0, 0.0, 0.0, 0.0], frame_id="")
    harness.tick(2)
    assert requested(harness.status[-1])[0] == 80.0
    assert harness.commands[-1].header.frame_id == "base_link_frd"
    values = harness.diagnostics_after_a_second()
    assert values["rejected wrench frames"] == "2" and values["rejected wrenches"] == "2"


@pytest.mark.params(EXAMPLE, rate_hz=25, actuators__main_port__position=[-1, 0, 0])
def test_an_integer_for_a_float_key_keeps_the_float_type(harness):
    from rclpy.parameter import Parameter
    rate = harness.node.get_parameter("rate_hz")
    assert rate.type_ == Parameter.Type.DOUBLE and rate.value == 25.0
    position = harness.node.get_parameter("actuators.main_port.position")
    assert position.type_ == Parameter.Type.DOUBLE_ARRAY and list(position.value) == [-1.0, 0.0, 0.0]
    assert harness.node.set_parameters([Parameter("rate_hz", value=20)])[0].successful
    rate = harness.node.get_parameter("rate_hz")
    assert rate.type_ == Parameter.Type.DOUBLE and harness.node.period == pytest.approx(1 / 20)


def test_a_qos_override_on_one_node_leaves_the_next_one_at_the_default(ros_context, namespace):
    """rclpy writes overrides into the profile it is given: each topic gets a profile of its own."""
    from rclpy.parameter import Parameter
    from rclpy.qos import ReliabilityPolicy

    from allocator_pkg.ros.node import AllocatorNode
    arguments = ["--ros-args", "--params-file", str(EXAMPLE)]
    overridden = AllocatorNode(context=ros_context, cli_args=[*arguments, "-r", f"__ns:={namespace}/qa"],
                               parameter_overrides=[Parameter(f"qos_overrides.{namespace}/qa/wrench_command."
                                                              "subscription.reliability", value="reliable")])
    default = AllocatorNode(context=ros_context, cli_args=[*arguments, "-r", f"__ns:={namespace}/qb"])
    try:
        def reliability(node, topic):
            return node.get_subscriptions_info_by_topic(topic)[0].qos_profile.reliability

        assert reliability(overridden, f"{namespace}/qa/wrench_command") == ReliabilityPolicy.RELIABLE
        assert reliability(default, f"{namespace}/qb/wrench_command") == ReliabilityPolicy.BEST_EFFORT
    finally:
        for node in (overridden, default):
            node.release()
            node.destroy_node()


DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"


@pytest.mark.params(DP_VESSEL, wrench_timeout=0.0, power__bus_ties=["bt_ab"],
                    power__bus_tie__bt_ab__sources=["swbd_a", "swbd_b"], power__bus_tie__bt_ab__closed=False)
def test_a_bus_tie_from_the_service_feeds_the_other_bus_from_the_next_sample(harness):
    """swbd_b at 0 kW with the tie open: its thrusters have no power. ~/set_bus_tie closes it:
    from the next sample they run on swbd_a's power, which allocation_status reports drawn from
    swbd_a; an unknown tie is refused and changes nothing."""
    harness.send_power({"swbd_b": 0.0})
    harness.send_wrench([0.0, 3e5, 0.0, 0.0, 0.0, 0.0])
    harness.tick(30)
    assert harness.commands[-1].thrust[1] == 0.0 and harness.commands[-1].thrust[3] == 0.0
    assert harness.set_bus_tie("bt_xy", True) == (False, "unknown bus tie 'bt_xy'; bus ties: bt_ab")
    assert harness.diagnostics_after_a_second()["bus ties"] == "bt_ab open (swbd_a + swbd_b)"
    assert harness.set_bus_tie("bt_ab", True) == (
        True, "bus tie bt_ab closed from the next sample; buses: swbd_a + swbd_b")
    count = len(harness.commands)
    harness.tick(1)
    harness.spin_until(lambda: len(harness.commands) > count)
    assert harness.commands[count].thrust[3] != 0.0
    harness.tick(2)
    status = harness.status[-1]
    assert status.source_power[1] == 0.0 and status.source_power[0] > 0.0
    assert harness.diagnostics_after_a_second()["bus ties"] == "bt_ab closed (swbd_a + swbd_b)"
