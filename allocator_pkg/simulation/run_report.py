"""What ``metrics.json`` holds for one run, and its verdict: the metrics over the whole run
with their units, the same metrics over each window (the scenario's and the automatic ones of
its faults), the step-response figures of each set-point step, each power source's peak
power, least available power and time over it, and the checks of the scenario's bounds
against them.

The file is strict JSON (RFC 8259), which has no infinities: a number that is not finite (an
alarm that never rose: ``consequence_alarm_time`` inf) is written as one of the strings of
:data:`NON_FINITE`, which JavaScript's ``Number()`` and Python's ``float()`` read back, and
:func:`read_report` does; a step figure the run does not reach is ``null``."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from ..vehicle.config import Vehicle
from .metrics import METRIC_UNITS
from .scenario import Scenario
from .step_response import SETTLING_BAND
from .trace import Trace
from .verdict import Check, checks

NON_FINITE = ("Infinity", "-Infinity", "NaN")
"""How metrics.json writes inf, -inf and NaN."""
TEXT_KEYS = ("scenario", "method")
"""The keys of metrics.json whose values are text, never a number written as text."""
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
            "duration": scenario.duration, "metrics": metrics,
            "units": {name: METRIC_UNITS[name] for name in metrics}, "windows": windows,
            "steps": steps, "step_units": dict(STEP_UNITS), "settling_band": SETTLING_BAND,
            "sources": trace.source_figures(), "source_units": dict(SOURCE_UNITS)}


def report_checks(scenario: Scenario, report: dict) -> list[Check]:
    """The bounds the scenario holds its method to against a run's report: over the run, and
    each window's over that window (``Scenario.run_bounds`` and ``window_bounds``: the method's
    own where the scenario gives them)."""
    return checks(report["metrics"], scenario.run_bounds(),
                  {name: w["metrics"] for name, w in report["windows"].items()}, scenario.window_bounds())


def _encoded(value: Any) -> Any:
    """``value`` with every float that is not finite as its string of NON_FINITE, at any depth."""
    if isinstance(value, float) and not math.isfinite(value):
        return NON_FINITE[2] if math.isnan(value) else NON_FINITE[0] if value > 0 else NON_FINITE[1]
    if isinstance(value, dict):
        return {key: _encoded(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_encoded(item) for item in value]
    return value


def _decoded(value: Any) -> Any:
    """``value`` with every string of NON_FINITE as its float, at any depth."""
    if isinstance(value, str) and value in NON_FINITE:
        return float(value.replace("Infinity", "inf"))
    if isinstance(value, dict):
        return {key: _decoded(item) for key, item in value.items()}
    if isinstance(value, list):
        return [_decoded(item) for item in value]
    return value


def report_json(report: dict) -> str:
    """The text of metrics.json: strict JSON, each number that is not finite a string of NON_FINITE."""
    return json.dumps(_encoded(report), indent=2, allow_nan=False) + "\n"


def read_report(path: str | Path) -> dict:
    """A metrics.json as :func:`run_report` made it: the strings of NON_FINITE read back as
    inf, -inf and NaN (the text of TEXT_KEYS left as it is)."""
    data = json.loads(Path(path).read_text())
    return {key: value if key in TEXT_KEYS else _decoded(value) for key, value in data.items()}
