"""The consequence analysis in the node (allocator_pkg.ros.consequence_topic), on simulated time: the
DP vessel's ``~/consequence``, the status's ``consequence_alarm`` and the diagnostics rise when a
load beyond what one switchboard's loss leaves is requested, and clear when it is not."""

import itertools
import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from diagnostic_msgs.msg import DiagnosticStatus

from allocator_msgs.msg import ConsequenceAnalysis
from allocator_pkg import Allocator
from allocator_pkg.capability.consequence import Consequence
from allocator_pkg.capability.group_loss import InForce
from allocator_pkg.ros.consequence_topic import consequence_status

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
HELD = [200e3, 0.0, 0.0, 0.0, 0.0, 0.0]         # either azimuth alone holds it
BEYOND_B = [500e3, 0.0, 0.0, 0.0, 0.0, 0.0]     # the port azimuth holds it, the starboard one (420 kN) not
SWAY = [0.0, 300e3, 0.0, 0.0, 0.0, 0.0]


def analysis_of(harness, received, wrench):
    """Send ``wrench``, step the clock a second at a time until an analysis of it, taken after
    it was sent, arrives."""
    harness.send_wrench(wrench)
    sent = harness.time_ns
    for _ in range(5):
        count = len(received)
        harness.step(1.0)
        harness.spin_until(lambda count=count: len(received) > count)
        last = received[-1]
        stamp = last.header.stamp.sec * 1_000_000_000 + last.header.stamp.nanosec
        if stamp > sent and (last.load.force.x, last.load.force.y) == (wrench[0], wrench[1]):
            return last
    raise AssertionError(f"no analysis of {wrench} arrived")


def consequence_diagnostics(harness):
    """The consequence analysis' status in the next diagnostics report."""
    count = len(harness.diagnostics)
    harness.step(1.0)
    harness.spin_until(lambda: len(harness.diagnostics) > count)
    return next(s for s in harness.diagnostics[-1].status if s.name.endswith(": consequence analysis"))


@pytest.mark.params(DP_VESSEL, wrench_timeout=0.0, consequence__filter_time=0.0)
def test_the_alarm_rises_and_clears_on_the_topic_the_status_and_the_diagnostics(harness):
    received = []
    harness.probe.create_subscription(ConsequenceAnalysis, "thrust_allocator/consequence", received.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("~/consequence") > 0)
    expected = Consequence(vehicle_from(DP_VESSEL))

    held = analysis_of(harness, received, HELD)
    assert [g.group for g in held.groups] == ["switchboard_a", "switchboard_b"]
    assert [g.utilisation for g in held.groups] == pytest.approx(
        [g.utilisation for g in expected.utilisation(HELD)], abs=1e-9)
    assert all(g.margin == pytest.approx(1.0 - g.utilisation) for g in held.groups)
    assert not held.alarm and held.header.frame_id == harness.node.runtime.settings.base_frame
    assert consequence_diagnostics(harness).level == DiagnosticStatus.OK
    assert not harness.status[-1].consequence_alarm

    beyond = analysis_of(harness, received, BEYOND_B)
    lose_a, lose_b = beyond.groups
    assert beyond.alarm and lose_b.utilisation > 1.0 > lose_a.utilisation and lose_b.margin < 0.0
    status = consequence_diagnostics(harness)
    assert status.level == DiagnosticStatus.ERROR
    assert "switchboard_b" in status.message and "switchboard_a" not in status.message
    assert harness.status[-1].consequence_alarm

    cleared = analysis_of(harness, received, HELD)
    assert not cleared.alarm
    assert consequence_diagnostics(harness).level == DiagnosticStatus.OK
    assert not harness.status[-1].consequence_alarm


@pytest.mark.params(DP_VESSEL, wrench_timeout=0.0, consequence__filter_time=0.0)
def test_a_failed_group_and_the_available_power_in_force_count_in_the_analysis(harness):
    """A sway load: after switchboard B's loss, the starboard azimuth (its sector lifted with the
    port unit) and the bow tunnel hold it. With B failed, A's loss leaves nothing; with A at
    500 kW, what B's loss leaves shares A's power."""
    received = []
    harness.probe.create_subscription(ConsequenceAnalysis, "thrust_allocator/consequence", received.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("~/consequence") > 0)
    vehicle = vehicle_from(DP_VESSEL)
    expected = Consequence(vehicle)
    before = analysis_of(harness, received, SWAY)
    assert not before.alarm and before.groups[1].utilisation == pytest.approx(41.5 / 78.5, rel=1e-9)

    assert harness.set_group_fault("switchboard_b")[0]
    failed = analysis_of(harness, received, SWAY)
    assert failed.alarm and math.isinf(failed.groups[0].utilisation)
    assert failed.groups[1].utilisation == pytest.approx(41.5 / 78.5, rel=1e-9)   # B's loss adds nothing more
    status = consequence_diagnostics(harness)
    assert status.level == DiagnosticStatus.ERROR and "switchboard_a" in status.message
    assert {v.key: v.value for v in status.values}["sources already lost"] == "swbd_b"
    assert harness.status[-1].consequence_alarm

    harness.clear_faults()
    harness.send_power({"swbd_a": 500.0})
    shared = analysis_of(harness, received, SWAY)
    allocator = Allocator(vehicle)
    allocator.set_available_power({"swbd_a": 500.0})
    reference = expected.utilisation([0.0, SWAY[1], 0.0, 0.0, 0.0, 0.0], InForce.of(allocator))
    assert [g.utilisation for g in shared.groups] == pytest.approx([g.utilisation for g in reference], rel=1e-9)
    assert shared.groups[1].utilisation > 1.0 > before.groups[1].utilisation


@pytest.mark.params(DP_VESSEL, wrench_timeout=0.0, consequence__filter_time=5.0)
def test_the_load_is_the_request_low_pass_filtered_sample_by_sample(harness):
    """From zero, k samples 0.1 s apart leave HELD (1 - exp(-0.1 / 5)^k): k a whole number."""
    received = []
    harness.probe.create_subscription(ConsequenceAnalysis, "thrust_allocator/consequence", received.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("~/consequence") > 0)
    harness.send_wrench(HELD)
    count = len(received)
    for second in range(1, 4):                  # each analysis published before the next snapshot is due
        harness.step(1.0)
        harness.spin_until(lambda wanted=count + second: len(received) >= wanted)
    loads = [message.load.force.x for message in received[count:]]
    samples = [math.log(1.0 - load / HELD[0]) / (-0.1 / 5.0) for load in loads]
    assert all(k == pytest.approx(round(k), abs=1e-6) for k in samples), samples
    # A second apart: ten samples, give or take the one at the instant of the analysis (timers due together).
    assert all(9 <= round(b - a) <= 11 for a, b in itertools.pairwise(samples)), samples


@pytest.mark.params(DP_VESSEL, wrench_timeout=0.0, consequence__rate=0.0, consequence__filter_time=0.0)
def test_rate_zero_is_off_and_a_rate_set_turns_it_on(harness):
    received = []
    harness.probe.create_subscription(ConsequenceAnalysis, "thrust_allocator/consequence", received.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("~/consequence") > 0)
    harness.send_wrench(BEYOND_B)
    harness.step(2.0)
    harness.spin_for(0.2)
    assert received == [] and consequence_diagnostics(harness).message == "off (consequence.rate 0)"
    assert harness.set_parameters({"consequence.rate": 2.0}) == (True, "")
    assert analysis_of(harness, received, BEYOND_B).alarm


def test_a_vehicle_without_redundancy_groups_has_no_consequence_topic(harness):
    assert "consequence" not in harness.node.runtime.topics()
    harness.tick(1)
    assert not harness.status[-1].consequence_alarm


def test_the_diagnostic_of_a_direction_nothing_left_gives():
    from allocator_pkg.capability.consequence import GroupUtilisation
    status = consequence_status("/n", 1.0, (GroupUtilisation("a", math.inf), GroupUtilisation("b", 0.5)))
    assert status.level == DiagnosticStatus.ERROR and "a (more than it gives" in status.message
    assert [(v.key, v.value) for v in status.values][:3] == [("utilisation a", "inf"), ("utilisation b", "0.5000"),
                                                             ("sources already lost", "none")]
    assert consequence_status("/n", 1.0, None).message == "no analysis yet"
    assert np.isinf(float(status.values[0].value))


def test_the_managed_node_analyses_while_active_only(allocator_harness):
    harness = allocator_harness(DP_VESSEL, {"wrench_timeout": 0.0, "consequence.filter_time": 0.0}, node="lifecycle")
    received = []
    harness.probe.create_subscription(ConsequenceAnalysis, "thrust_allocator/consequence", received.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("~/consequence") > 0)
    assert analysis_of(harness, received, BEYOND_B).alarm
    harness.node.trigger_deactivate()
    harness.spin_for(0.3)                      # an analysis published before deactivating may still be on its way
    count = len(received)
    harness.advance(3.0)
    harness.spin_for(0.3)
    assert len(received) == count
    harness.node.trigger_cleanup()
    assert harness.node.runtime is None
