"""allocator_pkg.simulation.trace: metrics over a window of the run, and the step response
of the position along its step and of the heading."""

import math

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.simulation.setpoint import Step
from allocator_pkg.simulation.trace import Trace

VESSEL = load_vehicle(ROOT / "config" / "dp_vessel.yaml")


def trace_of(positions, headings, period=1.0):
    trace = Trace(names=list(VESSEL.names), period=period, horizontal=True)
    for k, (position, heading) in enumerate(zip(positions, headings)):
        trace.add(k * period, position, [0.0, 0.0, heading], [0.0, 0.0, 0.0], 0.0, np.full(4, 1000.0 * k),
                  np.zeros(4), k % 2 == 0, 0.0, False)
    return trace


def test_the_metrics_of_a_window_take_its_samples_only():
    trace = trace_of([[float(k), 0.0, 0.0] for k in range(10)], [0.0] * 10)
    whole, window = trace.metrics(VESSEL), trace.metrics(VESSEL, 2.0, 5.0)      # samples at 2, 3, 4 s
    assert whole["position_error_max"] == 9.0 and window["position_error_max"] == 4.0
    assert window["position_error_rms"] == pytest.approx(math.sqrt((4 + 9 + 16) / 3))
    coefficients = np.array([a.power_coefficient for a in VESSEL.actuators])
    assert window["energy"] == pytest.approx(sum((1000.0 * k) ** 1.5 * coefficients.sum() for k in (2, 3, 4)))
    assert window["saturated_fraction"] == pytest.approx(2 / 3)
    with pytest.raises(ValueError, match="no sample"):
        trace.metrics(VESSEL, 20.0, 30.0)


def test_the_position_response_is_measured_along_the_step_in_the_horizontal_plane():
    # the vessel moves to 3 m north, 4 m east (5 m along the step) over 5 samples, depth ignored
    positions = [[0.6 * min(k, 5), 0.8 * min(k, 5), 7.0] for k in range(20)]
    step = Step("position", 0.0, np.zeros(3), np.array([3.0, 4.0, 0.0]), 20.0)
    figures = trace_of(positions, [0.0] * 20).step_response(step)
    assert figures.rise_time == pytest.approx(4.0)                  # 10 % at 0.5 s, 90 % at 4.5 s
    assert figures.overshoot == 0.0 and figures.settling_time == pytest.approx(4.75)


def test_the_heading_response_wraps():
    start, end = math.radians(175.0), math.radians(175.0 + 10.0)
    headings = [math.remainder(start + math.radians(2.0 * min(k, 6)), 2 * math.pi) for k in range(20)]   # to 187
    figures = trace_of([[0.0, 0.0, 0.0]] * 20, headings).step_response(
        Step("heading", 0.0, np.array([start]), np.array([end]), 20.0))
    assert figures.overshoot == pytest.approx(20.0)                  # 12 deg of a 10 deg step
    assert figures.rise_time == pytest.approx(4.0)                   # 1 deg at 0.5 s, 9 deg at 4.5 s
    assert figures.settling_time is None                             # never back within 0.5 deg of 185
