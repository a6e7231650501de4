"""allocator_pkg.simulation.metrics on small runs worked out by hand."""

import math

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.simulation.metrics import (
    alarm_metrics,
    azimuth_travel,
    energy,
    heading_errors,
    position_errors,
    power_metrics,
    run_metrics,
    settled_samples,
    source_figures,
    thrust_reversals,
)
from allocator_pkg.simulation.trace import Trace


def test_position_error_is_horizontal_for_a_vessel_and_3d_for_an_rov():
    position = np.array([[3.0, 4.0, 12.0], [0.0, 0.0, 0.0]])
    setpoint = np.zeros((2, 3))
    assert position_errors(position, setpoint, horizontal=True) == pytest.approx([5.0, 0.0])
    assert position_errors(position, setpoint, horizontal=False) == pytest.approx([13.0, 0.0])


def test_heading_error_wraps():
    assert heading_errors(np.array([math.radians(179.0)]), np.array([math.radians(-179.0)])) == pytest.approx(
        [math.radians(-2.0)])


def test_energy_of_the_power_model():
    thrust = np.array([[100.0, -400.0], [0.0, 900.0]])
    # P = 2 |f1|^1.5 + 3 |f2|^1.5: 2 * 1000 + 3 * 8000 = 26000 W, then 3 * 27000 = 81000 W
    assert energy(thrust, np.array([2.0, 3.0]), 0.1) == pytest.approx(0.1 * (26000.0 + 81000.0))


def test_azimuth_travel_takes_the_short_way_round():
    angles = np.array([[3.0, 0.0], [-3.0, 0.5], [-3.0, 0.0]])
    assert azimuth_travel(angles) == pytest.approx((2 * math.pi - 6.0) + 0.5 + 0.5)


def test_thrust_reversals_ignore_a_thrust_near_zero():
    thrust = np.array([[10.0], [0.5], [-10.0], [-0.5], [10.0], [20.0]])
    assert thrust_reversals(thrust, np.array([100.0])) == 2          # +, (0.5 ignored), -, (-0.5 ignored), +, +
    assert thrust_reversals(thrust, np.array([10000.0])) == 0        # everything below 1 % of 10 kN


def test_run_metrics_together():
    metrics = run_metrics(position=np.array([[3.0, 4.0, 0.0], [0.0, 0.0, 0.0]]), position_setpoint=np.zeros((2, 3)),
                          heading=np.array([0.1, -0.1]), heading_setpoint=np.zeros(2), horizontal=True,
                          thrust=np.array([[1.0], [-1.0]]), angles=np.zeros((2, 1)), saturated=np.array([True, False]),
                          power_coefficients=np.array([1.0]), thrust_scale=np.array([1.0]), period=0.5)
    assert metrics == pytest.approx({"position_error_rms": math.sqrt(12.5), "position_error_max": 5.0,
                                     "heading_error_rms": math.degrees(0.1), "energy": 1.0, "azimuth_travel": 0.0,
                                     "thrust_reversals": 1, "saturated_fraction": 0.5})


def test_a_source_is_over_its_available_power_beyond_one_percent():
    available = np.array([[100.0, 0.0], [100.0, 0.0], [100.0, 0.0], [50.0, 0.0]])
    power = np.array([[101.0, 0.0], [101.5, 0.0], [80.0, 1e-9], [60.0, 0.0]])      # 1 %: not over; then over
    assert power_metrics(power, available, 0.1)["time_over_available"] == pytest.approx(0.3)
    figures = source_figures(["a", "b"], power, available, 0.1)
    assert figures["a"] == {"peak_power": 101.5, "least_available": 50.0, "time_over_available": pytest.approx(0.2)}
    assert figures["b"]["time_over_available"] == pytest.approx(0.1)
    assert power_metrics(np.zeros((4, 0)), np.zeros((4, 0)), 0.1) == {"time_over_available": 0.0}
    assert source_figures([], np.zeros((4, 0)), np.zeros((4, 0)), 0.1) == {}


def test_the_alarm_is_timed_against_the_loss_of_position():
    time = np.arange(6.0)
    distance = np.array([0.0, 1.0, 2.0, 6.0, 7.0, 4.0])                            # lost at 3 s beyond 5 m
    early = alarm_metrics(time, np.array([0, 1, 1, 0, 1, 1]), distance, 5.0)
    assert early == {"consequence_alarm_time": 1.0, "position_lost_time": 3.0, "alarm_lead_time": 2.0,
                     "alarm_after_position_loss": 0.0}
    late = alarm_metrics(time, np.array([0, 0, 0, 0, 0, 1]), distance, 5.0)
    assert late["alarm_lead_time"] == -2.0 and late["alarm_after_position_loss"] == 2.0
    never = alarm_metrics(time, np.zeros(6), distance, 5.0)
    assert never["consequence_alarm_time"] == math.inf and never["alarm_lead_time"] == -math.inf
    assert never["alarm_after_position_loss"] == math.inf
    held = alarm_metrics(time, np.zeros(6), distance, 10.0)
    assert held["position_lost_time"] == math.inf and held["alarm_after_position_loss"] == 0.0
    assert alarm_metrics(time, np.ones(6), distance, 10.0)["alarm_lead_time"] == math.inf


def test_a_commanded_move_is_not_a_loss_of_position():
    """A 10 m step with a 5 m limit: the error is 10 m at the step, but the position is lost
    only when the error exceeds the limit again after it came back within it."""
    setpoint = np.array([[0.0, 0.0, 0.0]] * 2 + [[10.0, 0.0, 0.0]] * 6)
    distance = np.array([0.5, 0.5, 10.0, 6.0, 4.0, 2.0, 6.0, 1.0])
    counted = settled_samples(setpoint, distance, 5.0)
    assert counted.tolist() == [True, True, False, False, True, True, True, True]
    time = np.arange(8.0)
    assert alarm_metrics(time, np.zeros(8), distance, 5.0)["position_lost_time"] == 2.0      # the step itself
    assert alarm_metrics(time, np.zeros(8), distance, 5.0, counted)["position_lost_time"] == 6.0
    ramp = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [4.0, 0.0, 0.0], [6.0, 0.0, 0.0], [6.0, 0.0, 0.0]])
    assert settled_samples(ramp, np.array([0.0, 2.0, 5.5, 6.0, 5.5]), 5.0).tolist() == [True, False, False, False,
                                                                                        False]
    assert settled_samples(ramp, np.array([0.0, 2.0, 5.5, 6.0, 3.0]), 5.0).tolist()[-1]     # back within: counted


def test_the_trace_leaves_a_set_point_step_out_of_the_loss_of_position():
    vehicle = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
    trace = Trace(names=list(vehicle.names), period=1.0, horizontal=True, position_limit=5.0)
    thrust = [0.0] * len(vehicle.names)
    for t, north, goal in [(0.0, 0.0, 0.0), (1.0, 0.0, 10.0), (2.0, 7.0, 10.0), (3.0, 10.0, 10.0), (4.0, 16.0, 10.0)]:
        trace.add(t, [north, 0.0, 0.0], [0.0, 0.0, 0.0], [goal, 0.0, 0.0], 0.0, thrust, thrust, False, 0.0, False)
    assert trace.metrics(vehicle)["position_lost_time"] == 4.0
    assert trace.metrics(vehicle, 1.0, 3.0)["position_lost_time"] == math.inf      # a window inside the move
