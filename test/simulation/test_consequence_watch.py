"""allocator_pkg.simulation.consequence_watch: the in-process consequence analysis filters the
requested wrench as the node does (first order, time constant consequence.filter_time),
analyses at the multiples of 1 / consequence.rate of the sim clock only, and alarms exactly
when the Consequence analysis of the filtered load does."""

import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.allocation.allocator import Allocator
from allocator_pkg.capability.consequence import Consequence
from allocator_pkg.capability.group_loss import InForce
from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.simulation.consequence_watch import ConsequenceWatch
from allocator_pkg.simulation.in_process import InProcessLink
from allocator_pkg.simulation.scenario import load_scenario

VESSEL = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
SETTINGS = InProcessLink(load_scenario(ROOT / "config" / "scenarios" / "dp_switchboard_trip.yaml")).settings
SECOND = 1_000_000_000
AHEAD = np.array([500e3, 0.0, 0.0, 0.0, 0.0, 0.0])          # the starboard azimuth alone cannot hold it


def test_the_filter_is_the_first_order_lag_of_the_requests():
    watch = ConsequenceWatch(Allocator(VESSEL))
    watch.observe(np.zeros(6), 0, SETTINGS)
    for k in range(1, 51):                                      # 5 s of a step at 10 Hz
        watch.observe(AHEAD, k * SECOND // 10, SETTINGS)
    expected = AHEAD * (1.0 - math.exp(-5.0 / SETTINGS.consequence_filter_time))
    np.testing.assert_allclose(watch.load, expected, rtol=1e-12)
    watch.observe(-AHEAD, 0, SETTINGS)                           # the clock went back: the request itself
    np.testing.assert_array_equal(watch.load, -AHEAD)


def test_the_alarm_is_the_analysis_of_the_filtered_load_at_the_analysis_times_only():
    allocator = Allocator(VESSEL)
    watch = ConsequenceWatch(allocator)
    watch.observe(AHEAD, 0, SETTINGS)
    reference = Consequence(VESSEL).utilisation(AHEAD, InForce.of(allocator))
    assert any(group.alarm for group in reference)
    watch.tick(SECOND + SECOND // 10, SETTINGS)                  # between two analyses: nothing yet
    assert not watch.alarm
    watch.tick(2 * SECOND, SETTINGS)
    assert watch.alarm
    watch.observe(np.zeros(6), 2 * SECOND, replace(SETTINGS, consequence_filter_time=0.0))
    watch.tick(3 * SECOND, SETTINGS)
    assert not watch.alarm
    watch.observe(AHEAD, 3 * SECOND, replace(SETTINGS, consequence_filter_time=0.0))
    watch.tick(4 * SECOND, replace(SETTINGS, consequence_rate=0.0))   # analysis off: no alarm
    assert not watch.alarm


@pytest.mark.parametrize("rate", [1.0, 2.0])
def test_the_in_process_link_reports_the_alarm_of_its_watch(rate):
    case = load_scenario(ROOT / "config" / "scenarios" / "dp_switchboard_trip.yaml")
    link = InProcessLink(replace(case, parameters={"consequence.rate": rate}))
    t_ns, answer = link.begin(0, SECOND // 10, None, AHEAD)
    assert not answer.consequence_alarm and answer.source_power is not None
    link.set_group_fault("switchboard_b")
    alarms = []
    while t_ns < 2 * SECOND:
        t_ns += SECOND // 10
        alarms.append(link.step(t_ns, None, None, AHEAD, np.zeros(3), 0.0).consequence_alarm)
    first = alarms.index(True)
    assert (first + 5) * SECOND // 10 % round(SECOND / rate) == 0    # at an analysis time of the clock
    assert np.all(link.step(t_ns + SECOND // 10, None, None, AHEAD, np.zeros(3), 0.0).source_power[1] == 0.0)
