"""What ``metrics.json`` holds for one run, and its verdict: the metrics over the whole run
with their units, the same metrics over each window (the scenario's and the automatic ones of
its faults), the step-response figures of each set-point step, each power source's peak
power, least available power and time over it, and the checks of the scenario's bounds
against them."""

from __future__ import annotations

import math

from ..vehicle.config import Vehicle
from .metrics import METRIC_UNITS
from .scenario import Scenario
from .step_response import SETTLING_BAND
from .trace import Trace
from .verdict import Check, checks

SOURCE_UNITS = {"peak_power": "kW", "least_available": "kW", "time_over_available": "s"}
STEP_UNITS = {"time": "s", "size": "m or deg (the channel's)", "rise_time": "s", "overshoot": "%",
              "settling_time": "s"}


def run_report(scenario: Scenario, trace: Trace, vehicle: Vehicle, realtime_factor: float) -> dict:
    """The contents of metrics.json (see the module); figures a step does not reach are None."""
    metrics = trace.metrics(vehicle)
    metrics["realtime_factor"] = realtime_factor
    windows = {window.name: {"start": window.start, "end": window.end,
                             "metrics": trace.metrics(vehicle, window.start, window.end)}
               for window in scenario.all_windows()}
    steps = []
    for step in scenario.schedule().steps(scenario.duration):
        size = step.size if step.channel == "position" else math.degrees(float(step.end[0] - step.start[0]))
        steps.append({"channel": step.channel, "time": step.time, "size": size,
                      **trace.step_response(step).as_dict()})
    return {"scenario": scenario.name, "method": scenario.method, "seed": scenario.seed,
            "duration": scenario.duration, "metrics": metrics, "units": dict(METRIC_UNITS), "windows": windows,
            "steps": steps, "step_units": dict(STEP_UNITS), "settling_band": SETTLING_BAND,
            "sources": trace.source_figures(), "source_units": dict(SOURCE_UNITS)}


def report_checks(scenario: Scenario, report: dict) -> list[Check]:
    """The bounds the scenario holds its method to against a run's report: over the run, and
    each window's over that window (``Scenario.run_bounds`` and ``window_bounds``: the method's
    own where the scenario gives them)."""
    return checks(report["metrics"], scenario.run_bounds(),
                  {name: w["metrics"] for name, w in report["windows"].items()}, scenario.window_bounds())
