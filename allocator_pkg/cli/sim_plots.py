"""Figures and tables of allocator-sim: the XY footprint around the set-point with the fault
interval marked, timelines of position error, thrust, azimuth and power, and the comparison
of methods (a markdown table of metrics and one figure)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

METRIC_ROWS = (("position_error_rms", "position error rms [m]", "{:.3f}"),
               ("position_error_max", "position error max [m]", "{:.3f}"),
               ("heading_error_rms", "heading error rms [deg]", "{:.3f}"),
               ("heading_error_max", "heading error max [deg]", "{:.3f}"),
               ("depth_error_max", "depth error max [m]", "{:.3f}"),
               ("energy", "energy [J]", "{:.4g}"),
               ("azimuth_travel", "azimuth travel [rad]", "{:.2f}"),
               ("thrust_reversals", "thrust reversals [count]", "{:.0f}"),
               ("saturated_fraction", "saturated fraction [share]", "{:.3f}"),
               ("realtime_factor", "real-time factor [x real time]", "{:.1f}"))


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _shade(axes, faults) -> None:
    for start, end in faults:
        axes.axvspan(start, end, color="tab:red", alpha=0.12)


def plot_run(out: Path, result, scenario) -> None:
    """``footprint.png`` and ``timeline.png`` of one run."""
    plt = _pyplot()
    a = result.trace.arrays()
    t = a["time"]
    offset = a["position"] - a["setpoint"]
    faulted = a["faulted"].astype(bool)
    scale = 1e3 if np.max(np.abs(a["thrust"]), initial=0.0) > 1e4 else 1.0
    unit = "kN" if scale == 1e3 else "N"

    figure, axes = plt.subplots(figsize=(6, 6))
    axes.plot(offset[:, 1], offset[:, 0], color="tab:blue", linewidth=0.8, label="track")
    if faulted.any():
        axes.plot(offset[faulted, 1], offset[faulted, 0], ".", color="tab:red", markersize=2,
                  label="during the fault")
    axes.plot(0.0, 0.0, "k+", markersize=14, label="set-point")
    limit = max(0.1, float(np.max(np.abs(offset[:, :2]), initial=0.0)) * 1.2)
    axes.set_xlim(-limit, limit)
    axes.set_ylim(-limit, limit)
    axes.set_aspect("equal")
    axes.grid(True)
    axes.set_xlabel("east of the set-point [m]")
    axes.set_ylabel("north of the set-point [m]")
    metrics = result.metrics
    axes.set_title(f"{scenario.name} ({scenario.method}): footprint\n"
                   f"rms {metrics['position_error_rms']:.2f} m, max {metrics['position_error_max']:.2f} m")
    axes.legend(loc="upper right", fontsize=8)
    figure.tight_layout()
    figure.savefig(out / "footprint.png", dpi=100)
    plt.close(figure)

    figure, (error, thrust, azimuth, power) = plt.subplots(4, 1, figsize=(10, 10), sharex=True)
    error.plot(t, result.trace.position_errors(), color="black", label="position error [m]")
    heading = np.degrees((a["attitude"][:, 2] - a["setpoint_heading"] + np.pi) % (2 * np.pi) - np.pi)
    error.plot(t, heading, color="tab:purple", linewidth=0.8, label="heading error [deg]")
    if not scenario.horizontal:
        error.plot(t, offset[:, 2], color="tab:cyan", linewidth=0.8, label="depth error [m]")
    rotating = [i for i, actuator in enumerate(result.vehicle.actuators) if actuator.rotatable]
    for i, name in enumerate(result.trace.names):
        thrust.plot(t, a["thrust"][:, i] / scale, linewidth=0.8, label=name)
        if i in rotating:
            azimuth.plot(t, np.degrees(np.unwrap(a["azimuth"][:, i])), linewidth=0.8, label=name)
    if not rotating:
        azimuth.plot(t, a["voltage"], color="tab:brown", label="supply voltage the limits follow")
    power.plot(t, a["power"] / 1e3, color="tab:green", label="power (1.44) [kW]")
    power.fill_between(t, 0, np.max(a["power"] / 1e3, initial=0.0) * a["saturated"], step="mid", color="tab:orange",
                       alpha=0.3, label="saturated")
    for axes in (error, thrust, azimuth, power):
        _shade(axes, result.fault_intervals)
        axes.grid(True)
        if axes.get_legend_handles_labels()[0]:
            axes.legend(loc="upper right", fontsize=7)
    shaded = "; a fault is in force in the shaded interval" if result.fault_intervals else ""
    error.set_title(f"{scenario.name} ({scenario.method}){shaded}")
    thrust.set_ylabel(f"thrust [{unit}]")
    azimuth.set_ylabel("azimuth [deg]" if rotating else "voltage [V]")
    power.set_ylabel("power [kW]")
    power.set_xlabel("time [s]")
    figure.tight_layout()
    figure.savefig(out / "timeline.png", dpi=100)
    plt.close(figure)


def compare_table(scenario, metrics: dict[str, dict[str, float]]) -> str:
    """A markdown table: one row per metric, one column per method."""
    methods = list(metrics)
    lines = [f"{scenario.name}: {scenario.duration:g} s, seed {scenario.seed}", "",
             "| metric | " + " | ".join(methods) + " |", "|---|" + "---:|" * len(methods)]
    for key, label, form in METRIC_ROWS:
        if key == "depth_error_max" and scenario.horizontal:
            continue
        if all(key in m for m in metrics.values()):
            lines.append(f"| {label} | " + " | ".join(form.format(metrics[m][key]) for m in methods) + " |")
    return "\n".join(lines) + "\n"


def plot_compare(path: Path, scenario, results: dict) -> None:
    """Position error against time for every method, and each method's footprint."""
    plt = _pyplot()
    figure, (timeline, footprint) = plt.subplots(1, 2, figsize=(13, 5), gridspec_kw={"width_ratios": [2, 1]})
    for method, result in results.items():
        a = result.trace.arrays()
        offset = a["position"] - a["setpoint"]
        timeline.plot(a["time"], result.trace.position_errors(), linewidth=0.9,
                      label=f"{method}: {result.metrics['energy'] / 1e6:.3g} MJ" if result.metrics["energy"] > 1e6
                      else f"{method}: {result.metrics['energy']:.3g} J")
        footprint.plot(offset[:, 1], offset[:, 0], linewidth=0.8, label=method)
    first = next(iter(results.values()))
    _shade(timeline, first.fault_intervals)
    timeline.set_xlabel("time [s]")
    timeline.set_ylabel("position error [m]")
    timeline.set_title(f"{scenario.name}: position error (legend: energy)")
    timeline.grid(True)
    timeline.legend(fontsize=8)
    footprint.plot(0.0, 0.0, "k+", markersize=14)
    footprint.set_aspect("equal", adjustable="datalim")
    footprint.set_xlabel("east [m]")
    footprint.set_ylabel("north [m]")
    footprint.set_title("footprint")
    footprint.grid(True)
    footprint.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)
