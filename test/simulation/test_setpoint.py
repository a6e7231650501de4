"""allocator_pkg.simulation.setpoint: steps and ramps of the position and the heading, each
channel on its own, an event starting where a ramp has got to, the heading the short way
round, and the steps the step-response figures are taken of."""

import math

import numpy as np
import pytest

from allocator_pkg.simulation.setpoint import SetpointSchedule, SetpointTarget


def test_without_events_the_set_point_stays():
    schedule = SetpointSchedule((1.0, 2.0, 3.0), 0.5, [])
    position, heading = schedule.at(100.0)
    assert position == pytest.approx([1.0, 2.0, 3.0]) and heading == 0.5
    assert schedule.steps(100.0) == []


def test_a_step_applies_from_its_time():
    schedule = SetpointSchedule((0.0, 0.0, 0.0), 0.0, [(10.0, SetpointTarget(position=(3.0, 4.0, 0.0)))])
    assert schedule.at(9.9)[0] == pytest.approx([0.0, 0.0, 0.0])
    assert schedule.at(10.0)[0] == pytest.approx([3.0, 4.0, 0.0])
    (step,) = schedule.steps(60.0)
    assert (step.channel, step.time, step.until, step.size) == ("position", 10.0, 60.0, pytest.approx(5.0))


def test_a_position_ramp_moves_at_its_speed_along_the_straight_line():
    schedule = SetpointSchedule((0.0, 0.0, 0.0), 0.0, [(10.0, SetpointTarget(position=(3.0, 4.0, 0.0), speed=0.5))])
    assert schedule.at(12.0)[0] == pytest.approx([0.6, 0.8, 0.0])          # 1 m of 5 m after 2 s
    assert schedule.at(20.0)[0] == pytest.approx([3.0, 4.0, 0.0])          # 5 m at 0.5 m/s: there at 20 s
    assert schedule.at(30.0)[0] == pytest.approx([3.0, 4.0, 0.0])
    assert schedule.steps(60.0) == []                                     # a ramp is no step


def test_a_heading_ramp_turns_the_short_way_round_at_its_rate():
    start, end = math.radians(170.0), math.radians(-170.0)
    schedule = SetpointSchedule((0.0, 0.0, 0.0), start, [(0.0, SetpointTarget(heading=end,
                                                                               heading_rate=math.radians(2.0)))])
    assert math.degrees(schedule.at(5.0)[1]) == pytest.approx(180.0)     # 10 deg on, through 180
    assert math.degrees(schedule.at(10.0)[1]) == pytest.approx(-170.0)   # 20 deg in 10 s, not 340 deg
    assert math.degrees(schedule.at(50.0)[1]) == pytest.approx(-170.0)


def test_position_and_heading_change_independently_and_an_event_starts_where_the_ramp_is():
    schedule = SetpointSchedule((0.0, 0.0, 0.0), 0.0, [
        (0.0, SetpointTarget(position=(10.0, 0.0, 0.0), speed=1.0)),
        (4.0, SetpointTarget(heading=math.radians(30.0))),                  # the position ramp goes on
        (6.0, SetpointTarget(position=(6.0, 8.0, 0.0)))])                  # a step from 6 m north
    position, heading = schedule.at(5.0)
    assert position == pytest.approx([5.0, 0.0, 0.0]) and math.degrees(heading) == pytest.approx(30.0)
    steps = schedule.steps(20.0)
    assert [(s.channel, s.time) for s in steps] == [("heading", 4.0), ("position", 6.0)]
    assert steps[1].start == pytest.approx([6.0, 0.0, 0.0]) and steps[1].size == pytest.approx(8.0)
    assert steps[0].until == 20.0 and math.degrees(steps[0].size) == pytest.approx(30.0)


def test_a_step_ends_at_the_next_change_of_its_channel():
    schedule = SetpointSchedule((0.0, 0.0, 0.0), 0.0, [(5.0, SetpointTarget(position=(1.0, 0.0, 0.0))),
                                                        (8.0, SetpointTarget(heading=0.1)),
                                                        (12.0, SetpointTarget(position=(2.0, 0.0, 0.0)))])
    assert [(s.channel, s.time, s.until) for s in schedule.steps(30.0)] == [
        ("position", 5.0, 12.0), ("heading", 8.0, 30.0), ("position", 12.0, 30.0)]
    assert [s.time for s in schedule.steps(10.0)] == [5.0, 8.0]        # a step after the run is not in it


def test_scaling_stretches_a_ramp_with_the_run():
    target = SetpointTarget(position=(1.0, 0.0, 0.0), heading=0.2, speed=0.5, heading_rate=0.01).scaled(0.1)
    assert (target.speed, target.heading_rate) == pytest.approx((5.0, 0.1))
    assert SetpointTarget(position=(1.0, 0.0, 0.0)).scaled(0.1).speed is None
    assert np.array_equal(target.position, (1.0, 0.0, 0.0))
