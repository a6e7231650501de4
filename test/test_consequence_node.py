"""The consequence analysis in the node (allocator_pkg.ros.consequence), on simulated time: the
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
from allocator_pkg.analysis.consequence import Consequence
from allocator_pkg.ros.consequence import consequence_status

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
HELD = [200e3, 0.0, 0.0, 0.0, 0.0, 0.0]         # either azimuth alone holds it
BEYOND_B = [500e3, 0.0, 0.0, 0.0, 0.0, 0.0]     # the port azimuth holds it, the starboard one (420 kN) not


def analysis_of(harness, received, wrench):
    """Send ``wrench``, step the clock a second at a time until an analysis of it arrives."""
    harness.send_wrench(wrench)
    for _ in range(5):
        count = len(received)
        harness.step(1.0)
        harness.spin_until(lambda count=count: len(received) > count)
        if received[-1].load.force.x == wrench[0]:
            return received[-1]
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
    harness.spin_until(lambda: harness.node.count_subscribers("/thrust_allocator/consequence") > 0)
    vehicle = vehicle_from(DP_VESSEL)
    expected = Consequence(vehicle)
    low, high = Allocator(vehicle).ranges

    held = analysis_of(harness, received, HELD)
    assert [g.group for g in held.groups] == ["switchboard_a", "switchboard_b"]
    assert [g.utilisation for g in held.groups] == pytest.approx(
        [g.utilisation for g in expected.utilisation(HELD, low, high)], abs=1e-9)
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


@pytest.mark.params(DP_VESSEL, wrench_timeout=0.0, consequence__filter_time=5.0)
def test_the_load_is_the_request_low_pass_filtered_sample_by_sample(harness):
    """From zero, k samples 0.1 s apart leave HELD (1 - exp(-0.1 / 5)^k): k a whole number."""
    received = []
    harness.probe.create_subscription(ConsequenceAnalysis, "thrust_allocator/consequence", received.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("/thrust_allocator/consequence") > 0)
    harness.send_wrench(HELD)
    count = len(received)
    harness.step(3.0)
    harness.spin_until(lambda: len(received) > count + 2)
    loads = [message.load.force.x for message in received[count:]]
    samples = [math.log(1.0 - load / HELD[0]) / (-0.1 / 5.0) for load in loads]
    assert all(k == pytest.approx(round(k), abs=1e-6) for k in samples), samples
    # A second apart: ten samples, give or take the one at the instant of the analysis (timers due together).
    assert all(9 <= round(b - a) <= 11 for a, b in itertools.pairwise(samples)), samples


@pytest.mark.params(DP_VESSEL, wrench_timeout=0.0, consequence__rate=0.0, consequence__filter_time=0.0)
def test_rate_zero_is_off_and_a_rate_set_turns_it_on(harness):
    received = []
    harness.probe.create_subscription(ConsequenceAnalysis, "thrust_allocator/consequence", received.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("/thrust_allocator/consequence") > 0)
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
    from allocator_pkg.analysis.consequence import GroupUtilisation
    status = consequence_status("/n", 1.0, (GroupUtilisation("a", math.inf), GroupUtilisation("b", 0.5)))
    assert status.level == DiagnosticStatus.ERROR and "a (more than it gives" in status.message
    assert [(v.key, v.value) for v in status.values][:2] == [("utilisation a", "inf"), ("utilisation b", "0.5000")]
    assert consequence_status("/n", 1.0, None).message == "no analysis yet"
    assert np.isinf(float(status.values[0].value))


def test_the_managed_node_analyses_while_active_only(allocator_harness):
    harness = allocator_harness(DP_VESSEL, {"wrench_timeout": 0.0, "consequence.filter_time": 0.0}, node="lifecycle")
    received = []
    harness.probe.create_subscription(ConsequenceAnalysis, "thrust_allocator/consequence", received.append, 10)
    harness.spin_until(lambda: harness.node.count_subscribers("/thrust_allocator/consequence") > 0)
    assert analysis_of(harness, received, BEYOND_B).alarm
    harness.node.trigger_deactivate()
    count = len(received)
    harness.advance(3.0)
    harness.spin_for(0.3)
    assert len(received) == count
    harness.node.trigger_cleanup()
    assert harness.node.runtime is None
