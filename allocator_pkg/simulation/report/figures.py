"""Figures and tables of allocator-sim: a run's ``footprint.png`` (:mod:`.footprint`) and
``timeline.png`` (:mod:`.timeline`), the comparison of methods (a markdown table of metrics
and one figure: position error and footprint, and every bound of the verdict with each method's
value; the power and alarm rows of the table for a scenario with power events), and the nominal run
a failure is read against: the same scenario and seed without its faults, battery ramps,
changes of available power and parameter changes."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np

from ...capability.report.plotting import pyplot
from ..metrics import METRIC_UNITS
from ..run_report import report_checks
from ..run_setup import RunResult
from ..scenario import Scenario
from ..verdict import RUN
from .footprint import footprint_figure, mark_setpoints, offsets, origin_of
from .plant_figure import plant_figure
from .style import FAULT_COLOUR, NOMINAL_LABEL, PALETTE, legend_beside, mark_events, shade_faults
from .timeline import timeline_figure

METRIC_ROWS = (("position_error_rms", "position error rms [m]", "{:.3f}"),
               ("position_error_max", "position error max [m]", "{:.3f}"),
               ("heading_error_rms", "heading error rms [deg]", "{:.3f}"),
               ("heading_error_max", "heading error max [deg]", "{:.3f}"),
               ("depth_error_max", "depth error max [m]", "{:.3f}"),
               ("energy", "energy [J]", "{:.4g}"),
               ("azimuth_travel", "azimuth travel [rad]", "{:.2f}"),
               ("thrust_reversals", "thrust reversals [count]", "{:.0f}"),
               ("saturated_fraction", "saturated fraction [share]", "{:.3f}"),
               ("time_over_available", "time over available power [s]", "{:.1f}"),
               ("consequence_alarm_time", "consequence alarm at [s]", "{:.1f}"),
               ("alarm_lead_time", "alarm lead time [s]", "{:.1f}"),
               ("frequency_dip", "frequency dip [pu]", "{:.4f}"),
               ("time_under_frequency", "time under 0.95 pu [s]", "{:.1f}"),
               ("generator_sets_tripped", "generator sets tripped [count]", "{:.0f}"),
               ("realtime_factor", "real-time factor [x real time]", "{:.1f}"))
POWER_ROWS = ("time_over_available", "consequence_alarm_time", "alarm_lead_time")
"""Rows for a scenario with power events (group faults, available power, weather ramps, a simulated
plant's generator trips and bus ties) only; a plant's own rows only where its runs have them."""
POWER_EVENTS = ("group_fault", "power", "weather_ramp", "generator_trip", "bus_tie")
FAILURES = ("fault", "clear_faults", "battery_ramp", "parameter", "group_fault", "power", "generator_trip")
"""The kinds of event the nominal run leaves out: what goes wrong, not what is asked."""


def nominal(scenario: Scenario) -> Scenario | None:
    """The same scenario and seed without its faults (of actuators and groups), battery ramps,
    changes of available power and parameter changes (set-points and weather kept): what the
    run is without the failure. None when it has none of them."""
    kept = tuple(event for event in scenario.events if event.kind not in FAILURES)
    return None if len(kept) == len(scenario.events) else replace(scenario, events=kept)


def nominal_run(scenario: Scenario, out: Path, run: Callable[[Scenario, Path], RunResult]) -> RunResult | None:
    """``run`` of the :func:`nominal` scenario into ``out`` (a run as long as the scenario's
    own); None when the scenario has nothing to leave out."""
    quiet = nominal(scenario)
    return None if quiet is None else run(quiet, out)


def plot_run(out: Path, result: RunResult, scenario: Scenario, nominal_result: RunResult | None = None) -> None:
    """``footprint.png`` and ``timeline.png`` of one run, the nominal run's dashed; with a
    simulated electric power plant, ``plant.png`` (:mod:`.plant_figure`)."""
    plt = pyplot()
    figures = [("footprint", footprint_figure(result, scenario, nominal_result)),
               ("timeline", timeline_figure(result, scenario, nominal_result))]
    if result.plant is not None:
        figures.append(("plant", plant_figure(result, scenario)))
    for name, figure in figures:
        figure.savefig(out / f"{name}.png", dpi=100)
        plt.close(figure)


def compare_table(scenario: Scenario, metrics: dict[str, dict[str, float]],
                  nominal_metrics: dict[str, dict[str, float]] | None = None) -> str:
    """A markdown table: one row per metric, one column per method; then, given the nominal
    runs' metrics, the same table of those."""
    lines = [f"{scenario.name}: {scenario.duration:g} s, seed {scenario.seed}", "", *_table(scenario, metrics)]
    if nominal_metrics:
        lines += ["", "The same seed without the faults, battery ramps and parameter changes (nominal runs):", "",
                  *_table(scenario, nominal_metrics)]
    return "\n".join(lines) + "\n"


def _table(scenario: Scenario, metrics: dict[str, dict[str, float]]) -> list[str]:
    methods = list(metrics)
    lines = ["| metric | " + " | ".join(methods) + " |", "|---|" + "---:|" * len(methods)]
    for key, label, form in METRIC_ROWS:
        if key == "depth_error_max" and scenario.horizontal:
            continue
        if key in POWER_ROWS and not any(event.kind in POWER_EVENTS for event in scenario.events):
            continue
        if all(key in m for m in metrics.values()):
            lines.append(f"| {label} | " + " | ".join(form.format(metrics[m][key]) for m in methods) + " |")
    return lines


def same_lines(series: dict[str, np.ndarray], tolerance: float = 0.01) -> list[list[str]]:
    """The keys of ``series`` grouped by lines that coincide: within ``tolerance`` of the
    largest magnitude of all of them at every sample (first key of a group first)."""
    largest = max((float(np.nanmax(np.abs(v), initial=0.0)) for v in series.values()), default=0.0)
    groups: list[list[str]] = []
    for key, values in series.items():
        twin = next((g for g in groups if series[g[0]].shape == values.shape
                     and np.nanmax(np.abs(series[g[0]] - values), initial=0.0) <= tolerance * max(largest, 1e-12)),
                    None)
        if twin is None:
            groups.append([key])
        else:
            twin.append(key)
    return groups


def plot_compare(path: Path, scenario: Scenario, results: dict[str, RunResult],
                 nominal_results: dict[str, RunResult] | None = None) -> None:
    """``compare.png``: :func:`compare_figure`."""
    figure = compare_figure(scenario, results, nominal_results)
    figure.savefig(path, dpi=100)
    pyplot().close(figure)


def compare_figure(scenario: Scenario, results: dict[str, RunResult],
                   nominal_results: dict[str, RunResult] | None = None):
    """Position error against time for every method (methods whose lines coincide drawn once,
    named together), the nominal runs dashed; each method's footprint; and under them every
    bound of the verdict, each method's value as a share of the bound, those that break it red."""
    plt = pyplot()
    nominal_results = nominal_results or {}
    figure = plt.figure(figsize=(15, 9.5), layout="constrained")
    grid = figure.add_gridspec(2, 2, width_ratios=[2, 1], height_ratios=[1.6, 1])
    timeline, footprint = figure.add_subplot(grid[0, 0]), figure.add_subplot(grid[0, 1])
    checks_axes = figure.add_subplot(grid[1, :])
    colours = {method: PALETTE[k % len(PALETTE)] for k, method in enumerate(results)}
    first = next(iter(results.values()))
    origin = origin_of(first)
    errors = {m: r.trace.position_errors() for m, r in results.items()}
    for group in same_lines(errors):
        result = results[group[0]]
        label = ", ".join(group) + (" (one line)" if len(group) > 1 else "")
        timeline.plot(result.trace.arrays()["time"], errors[group[0]], color=colours[group[0]], linewidth=1.1,
                      label=label)
        offset = offsets(result, origin)
        footprint.plot(offset[:, 1], offset[:, 0], color=colours[group[0]], linewidth=0.9, label=label)
    quiet_errors = {m: q.trace.position_errors() for m, q in nominal_results.items()}
    for k, group in enumerate(same_lines(quiet_errors)):
        quiet = nominal_results[group[0]]
        timeline.plot(quiet.trace.arrays()["time"], quiet_errors[group[0]], color=colours[group[0]],
                      linestyle="--", linewidth=0.9, label="_" if k else f"dashed: {NOMINAL_LABEL}")
        offset = offsets(quiet, origin)
        footprint.plot(offset[:, 1], offset[:, 0], color=colours[group[0]], linestyle="--", linewidth=0.8)
    timeline.set_xlim(first.trace.time[0], first.trace.time[-1])
    shade_faults(timeline, first.fault_intervals)
    if first.fault_intervals:
        timeline.axvspan(0.0, 0.0, color=FAULT_COLOUR, alpha=0.1, label="a fault in force")
    timeline.set_xlabel("time [s]")
    timeline.set_ylabel("position error [m]")
    timeline.grid(True, alpha=0.5)
    timeline.legend(fontsize=8, loc="upper left")
    bound = scenario.bounds.get("position_error_max")
    mark_setpoints(footprint, first, origin, bound)
    footprint.set_aspect("equal", adjustable="datalim")
    where = "the set-point" if origin is None else "the first set-point"
    footprint.set_xlabel(f"east of {where} [m]")
    footprint.set_ylabel(f"north of {where} [m]")
    footprint.set_title("footprint", loc="left", fontsize=10)
    footprint.grid(True, alpha=0.5)
    legend_beside(footprint)
    _checks_panel(checks_axes, scenario, results, colours)
    rows = mark_events([timeline], scenario.events)
    timeline.set_title(f"{scenario.name} (seed {scenario.seed}): position error", loc="left", fontsize=10,
                       pad=6 + rows * 12)
    return figure


SHARE_CAP = 2.0
"""The bound panel shows shares of a bound up to this; a value beyond it is written on its bar."""


def _checks_panel(axes, scenario: Scenario, results: dict[str, RunResult], colours: dict[str, str]) -> None:
    """Every bound of the verdict (the whole run's and each window's): each method's value as a
    share of the bound, a bar per method, red-edged and labelled with its value where it breaks
    the bound (a bound of 0, whose share is no number: every value written, any above 0 breaks it)."""
    found = {m: report_checks(scenario, r.report) for m, r in results.items()}
    checks = next(iter(found.values()))
    if not checks:
        axes.text(0.5, 0.5, "the scenario sets no bounds", ha="center", va="center", transform=axes.transAxes)
        axes.set_axis_off()
        return
    width = 0.8 / len(results)
    highest = 1.0
    for k, (method, method_checks) in enumerate(found.items()):
        for j, check in enumerate(method_checks):
            if check.bound > 0.0:
                share = check.value / check.bound if math.isfinite(check.value) else math.inf
            else:
                share = 0.0 if check.passed else math.inf
            x = j - 0.4 + (k + 0.5) * width
            failed = not check.passed
            axes.bar(x, min(share, SHARE_CAP), width * 0.9, color=colours[method],
                     edgecolor=FAULT_COLOUR if failed else "none", linewidth=2.0 if failed else 0.0,
                     label=method if j == 0 else "_")
            highest = max(highest, min(share, SHARE_CAP))
            if failed or check.bound == 0.0:
                axes.annotate(f"{check.value:.3g}", (x, min(share, SHARE_CAP)), xytext=(0, 2),
                              textcoords="offset points", ha="center", va="bottom", fontsize=7,
                              color=FAULT_COLOUR if failed else "black")
    axes.axhline(1.0, color=FAULT_COLOUR, linestyle="--", linewidth=1.0, label="the bound")
    axes.set_xticks(range(len(checks)))
    axes.set_xticklabels([f"{c.metric}\n{'' if c.scope == RUN else c.scope + ': '}<= {c.bound:g} "
                          f"{METRIC_UNITS[c.metric]}" for c in checks], fontsize=8)
    axes.set_ylim(0.0, highest * 1.15)
    axes.set_ylabel("value / bound")
    axes.set_title("the verdict's bounds: each method's value as a share of the bound (red edge: broken, "
                   "its value written)", loc="left", fontsize=10)
    axes.grid(True, axis="y", alpha=0.5)
    legend_beside(axes)
