"""The text ``allocator-sim`` prints about a run: its metrics with their units over the whole
run and each window, the figures of each set-point step, and the verdict against the
scenario's bounds (one table for a run, one line per method for ``compare``)."""

from __future__ import annotations

from ..run_report import report_checks
from ..scenario import Scenario
from ..verdict import broken, count, verdict_lines


def _value(value) -> str:
    if value is None:
        return "-"
    return f"{value:.0f}" if isinstance(value, int) else f"{value:.4g}"


def metrics_lines(report: dict) -> list[str]:
    """One row per metric (its unit in brackets), one column for the run and one per window."""
    units = report["units"]
    windows = report["windows"]
    columns = ["run", *windows]
    width = max(14, *(len(name) + 2 for name in columns))
    lines = [f"{'metric':32s}" + "".join(f"{name:>{width}s}" for name in columns)]
    if windows:
        lines.append(f"{'  window [s]':32s}" + f"{'0 - ' + format(report['duration'], 'g'):>{width}s}" + "".join(
            f"{format(w['start'], 'g') + ' - ' + format(w['end'], 'g'):>{width}s}" for w in windows.values()))
    for name, unit in units.items():
        row = [report["metrics"].get(name)] + [w["metrics"].get(name) for w in windows.values()]
        lines.append(f"{name + ' [' + unit + ']':32s}" + "".join(f"{_value(v):>{width}s}" for v in row))
    return lines


def steps_lines(report: dict) -> list[str]:
    """One line per set-point step: its time, channel and size, rise time (10-90 %),
    overshoot and settling time into the band; '-' for a figure the run did not reach."""
    lines = []
    for step in report["steps"]:
        unit = "m" if step["channel"] == "position" else "deg"
        lines.append(f"step at {step['time']:g} s, {step['channel']} {step['size']:+.4g} {unit}: rise time "
                     f"{_value(step['rise_time'])} s, overshoot {step['overshoot']:.3g} %, settling time "
                     f"{_value(step['settling_time'])} s (band +-{100 * report['settling_band']:g} %)")
    return lines


def verdict(scenario: Scenario, report: dict) -> tuple[bool, list[str]]:
    """(whether the run holds every bound, the verdict table)."""
    checks = report_checks(scenario, report)
    return not broken(checks), verdict_lines(checks)


def method_verdict(scenario: Scenario, method: str, report: dict) -> tuple[bool, str]:
    """(whether the run holds every bound ``scenario`` holds ``method`` to, one line: the
    method, PASS or FAIL and each bound it broke, and the bounds of its own the scenario gives
    it, with why)."""
    checks = report_checks(scenario, report)
    failed = broken(checks)
    own = scenario.method_bounds.get(method)
    expected = ""
    if own is not None:
        given = [f"{name} {value:g}" for name, value in own.bounds.items()] + [
            f"{window} {name} {value:g}" for window, limits in own.windows.items() for name, value in limits.items()]
        expected = " (its own bounds: " + ", ".join(given) + (f"; {own.note}" if own.note else "") + ")"
    if not failed:
        return True, f"{method}: PASS, {count(checks)} held{expected}"
    units = report["units"]
    return False, f"{method}: FAIL, broke " + "; ".join(
        f"{c.scope} {c.metric} {c.value:.4g} {units[c.metric]} > {c.bound:g}" for c in failed) + expected


def compare_summary(judged: list[str], broke: list[str], failed: list[str], no_verdict: bool) -> str:
    """The last line of ``compare``: how many methods held their bounds, which broke one, and
    which runs failed (told apart: a failed run has no verdict)."""
    parts = []
    if no_verdict:
        parts.append(f"{len(judged)} run(s) without a verdict")
    else:
        held = len(judged) - len(broke)
        parts.append(f"{held} method(s) held every bound")
        if broke:
            parts.append(f"bounds broken by {', '.join(broke)}")
    if failed:
        parts.append(f"run failed (crashed, no verdict): {', '.join(failed)}")
    return ("FAIL: " if broke or failed else "PASS: ") + "; ".join(parts)
