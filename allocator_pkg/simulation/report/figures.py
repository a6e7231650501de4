"""Figures and tables of allocator-sim: a run's ``footprint.png`` (:mod:`.sim_footprint`) and
``timeline.png`` (:mod:`.sim_timeline`), the comparison of methods (a markdown table of metrics
and one figure; the power and alarm rows for a scenario with power events), and the nominal run
a failure is read against: the same scenario and seed without its faults, battery ramps,
changes of available power and parameter changes."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from ...capability.report.plotting import pyplot
from ..run_setup import RunResult
from ..scenario import Scenario
from .footprint import footprint_figure
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
               ("realtime_factor", "real-time factor [x real time]", "{:.1f}"))
POWER_ROWS = ("time_over_available", "consequence_alarm_time", "alarm_lead_time")
"""Rows for a scenario with power events (group faults, available power, weather ramps) only."""
POWER_EVENTS = ("group_fault", "power", "weather_ramp")
FAILURES = ("fault", "clear_faults", "battery_ramp", "parameter", "group_fault", "power")
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
    """``footprint.png`` and ``timeline.png`` of one run, the nominal run's dashed."""
    plt = pyplot()
    for name, figure in (("footprint", footprint_figure(result, scenario, nominal_result)),
                         ("timeline", timeline_figure(result, scenario, nominal_result))):
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


def _energy(joules: float) -> str:
    return f"{joules / 1e6:.3g} MJ" if joules > 1e6 else f"{joules:.3g} J"


def plot_compare(path: Path, scenario: Scenario, results: dict[str, RunResult],
                 nominal_results: dict[str, RunResult] | None = None) -> None:
    """``compare.png``: :func:`compare_figure`."""
    figure = compare_figure(scenario, results, nominal_results)
    figure.savefig(path, dpi=100)
    pyplot().close(figure)


def compare_figure(scenario: Scenario, results: dict[str, RunResult],
                   nominal_results: dict[str, RunResult] | None = None):
    """Position error against time for every method, its nominal run dashed in the same colour,
    and each method's footprint."""
    plt = pyplot()
    nominal_results = nominal_results or {}
    figure, (timeline, footprint) = plt.subplots(1, 2, figsize=(15, 6), gridspec_kw={"width_ratios": [2, 1]},
                                                 layout="constrained")
    for k, (method, result) in enumerate(results.items()):
        colour = PALETTE[k % len(PALETTE)]
        a = result.trace.arrays()
        offset = a["position"] - a["setpoint"]
        timeline.plot(a["time"], result.trace.position_errors(), color=colour, linewidth=1.1,
                      label=f"{method}: {_energy(result.metrics['energy'])}")
        footprint.plot(offset[:, 1], offset[:, 0], color=colour, linewidth=0.9, label=method)
        if method in nominal_results:
            quiet = nominal_results[method]
            b = quiet.trace.arrays()
            timeline.plot(b["time"], quiet.trace.position_errors(), color=colour, linestyle="--", linewidth=0.9,
                          label=f"{method}, nominal: {_energy(quiet.metrics['energy'])}")
            footprint.plot((b["position"] - b["setpoint"])[:, 1], (b["position"] - b["setpoint"])[:, 0],
                           color=colour, linestyle="--", linewidth=0.8)
    first = next(iter(results.values()))
    timeline.set_xlim(first.trace.time[0], first.trace.time[-1])
    shade_faults(timeline, first.fault_intervals)
    rows = mark_events([timeline], scenario.events)
    if first.fault_intervals:
        timeline.axvspan(0.0, 0.0, color=FAULT_COLOUR, alpha=0.1, label="a fault in force")
    timeline.set_xlabel("time [s]")
    timeline.set_ylabel("position error [m]")
    nominal_note = f"; dashed: {NOMINAL_LABEL}" if nominal_results else ""
    timeline.set_title(f"{scenario.name} (seed {scenario.seed}): position error, legend: energy{nominal_note}",
                       loc="left", fontsize=10, pad=6 + rows * 12)
    timeline.grid(True, alpha=0.5)
    timeline.legend(fontsize=8, loc="upper left", ncol=2 if nominal_results else 1)
    footprint.plot(0.0, 0.0, "k+", markersize=14)
    bound = scenario.bounds.get("position_error_max")
    if bound is not None:
        footprint.add_patch(plt.Circle((0.0, 0.0), bound, fill=False, color=FAULT_COLOUR, linestyle="--",
                                       linewidth=1.0, label=f"bound {bound:g} m"))
    footprint.set_aspect("equal", adjustable="datalim")
    footprint.set_xlabel("east of the set-point [m]")
    footprint.set_ylabel("north of the set-point [m]")
    footprint.set_title("footprint", loc="left", fontsize=10)
    footprint.grid(True, alpha=0.5)
    legend_beside(footprint)
    return figure
