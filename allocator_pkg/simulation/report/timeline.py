"""``timeline.png`` of an ``allocator-sim`` run, panel under panel against time: position error
[m] (and depth error, 6 DOF), heading error [deg], roll and pitch [deg] (6 DOF), every
actuator's thrust against its limits (at the supply voltage in force, for thrust tables measured
at several voltages) and its bound from the available power, the view fitted to the thrusts,
azimuth angles [deg], the supply voltage when it changes, the power
estimate (1.44) with the saturated samples, and for a vehicle with power sources each source's
power against its available power with the consequence alarm (:mod:`.power_figure`); the
scenario's events as labelled lines, the faults shaded, and the
nominal run (same seed, nothing going wrong) dashed under the errors and the power."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...capability.report.plotting import pyplot
from ...effectiveness.faults import thrust_limits
from ...vehicle.config import Vehicle
from ..metrics import heading_errors
from ..run_setup import RunResult
from ..scenario import Scenario
from .power_figure import power_bounds, sources_panel
from .style import (
    FAULT_COLOUR,
    LABEL_SIZE,
    LIMIT_COLOUR,
    NOMINAL,
    NOMINAL_LABEL,
    OVERLAID,
    actuator_style,
    fit_view,
    in_view,
    legend_beside,
    mark_events,
    overlaid,
    scale,
    shade_faults,
)

POWER_LABEL = r"power estimate $\sum_i P_i\,|f_i|^{1.5}$ (1.44)"
TALL = {"thrust": 1.7}
"""Panels taller than the others, by how much."""


def thrust_limits_over_time(vehicle: Vehicle, voltage: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(low, high), one row per sample: every actuator's thrust range at the sample's supply
    voltage (:func:`~allocator_pkg.effectiveness.faults.thrust_limits`; the nominal voltage
    where the sample has none, NaN)."""
    ranges: dict[float | None, tuple[np.ndarray, np.ndarray]] = {}
    rows = []
    for value in voltage:
        key = float(value) if np.isfinite(value) else None
        if key not in ranges:
            ranges[key] = thrust_limits(vehicle, key)
        rows.append(ranges[key])
    count = len(vehicle.actuators)
    low = np.array([row[0] for row in rows]).reshape(-1, count)
    high = np.array([row[1] for row in rows]).reshape(-1, count)
    return low, high


def _heading_error(arrays: dict[str, np.ndarray]) -> np.ndarray:
    return np.degrees(heading_errors(arrays["attitude"][:, 2], arrays["setpoint_heading"]))


def _errors(axes: dict[str, Any], result: RunResult, nominal: RunResult | None, horizontal: bool) -> None:
    """Position (and depth) error, heading error, roll and pitch; the nominal run's dashed."""
    a = result.trace.arrays()
    t = a["time"]
    distance = "horizontal distance from the set-point" if horizontal else "distance from the set-point"
    axes["position"].plot(t, result.trace.position_errors(), color="black", linewidth=1.2, label=distance)
    axes["heading"].plot(t, _heading_error(a), color="black", linewidth=1.2, label="heading error")
    if not horizontal:
        axes["position"].plot(t, a["position"][:, 2] - a["setpoint"][:, 2], color="tab:blue", linewidth=1.0,
                              label="depth error (down positive)")
        axes["roll_pitch"].plot(t, np.degrees(a["attitude"][:, 0]), color="tab:blue", linewidth=1.0, label="roll")
        axes["roll_pitch"].plot(t, np.degrees(a["attitude"][:, 1]), color="tab:orange", linewidth=1.0, label="pitch")
    if nominal is not None:
        b = nominal.trace.arrays()
        axes["position"].plot(b["time"], nominal.trace.position_errors(), **NOMINAL, label=NOMINAL_LABEL)
        axes["heading"].plot(b["time"], _heading_error(b), **NOMINAL, label=NOMINAL_LABEL)
    axes["position"].set_ylabel("position error [m]")
    axes["heading"].set_ylabel("heading error [deg]")
    if "roll_pitch" in axes:
        axes["roll_pitch"].set_ylabel("roll, pitch [deg]")


def _traces(axes, t: np.ndarray, values: np.ndarray, names: list[str], columns: list[int]) -> None:
    """One line per actuator of ``columns``, in its style; dashed over an equal one."""
    covering = overlaid(values[:, columns])
    for k, i in enumerate(columns):
        style = actuator_style(i)
        if covering[k]:
            style["linestyle"] = OVERLAID
        axes.plot(t, values[:, i], label=names[i] + (" (dashed: along another)" if covering[k] else ""), **style)


def _thrust(axes, result: RunResult, bounds: np.ndarray | None) -> None:
    """Every actuator's thrust, the view fitted to it (:func:`~.style.fit_view`); its limits
    dashed, one pair per set of actuators with the same limits all along (grey when shared, in
    the actuator's colour otherwise; a limit of zero is the axis and not drawn; one beyond the
    view named in the legend); the power bounds ``bounds`` (:func:`~.power_figure.power_bounds`)
    dash-dotted in each actuator's colour."""
    a = result.trace.arrays()
    t, thrust, names = a["time"], a["thrust"], result.trace.names
    low, high = thrust_limits_over_time(result.vehicle, a["voltage"])
    references = [low, high] + ([bounds, np.where(np.any(thrust < 0.0, axis=0), -bounds, np.nan)]
                                if bounds is not None else [])
    view = fit_view(thrust, *references)
    divisor, unit = scale(np.array(view), "N")
    _traces(axes, t, thrust / divisor, names, list(range(len(names))))
    groups: dict[bytes, list[int]] = {}
    for i in range(len(names)):
        groups.setdefault(low[:, i].tobytes() + high[:, i].tobytes(), []).append(i)
    varying = bool(np.any(low != low[:1]) or np.any(high != high[:1]))
    supply = a["voltage"][np.isfinite(a["voltage"])]
    at = " at the supply voltage" if varying else f" at {supply[0]:g} V" if supply.size else ""
    for members in groups.values():
        shared = len(members) > 1
        who = "every actuator" if len(members) == len(names) else ", ".join(names[i] for i in members)
        drawn = [bound for bound in (high[:, members[0]], low[:, members[0]]) if np.any(bound != 0.0)]
        hidden = [float(b[np.argmax(np.abs(b))]) / divisor for b in drawn if not in_view(b, view)]
        if len(hidden) == 2 and hidden[0] == -hidden[1]:
            where = f"+/-{abs(hidden[0]):.4g}"
        else:
            where = " and ".join(f"{b:+.4g}" for b in hidden)
        label = f"limits of {who}{at}" + (f", {where} {unit} beyond the view" if hidden else "")
        colour = LIMIT_COLOUR if shared else actuator_style(members[0])["color"]
        for bound in drawn:
            axes.plot(t, bound / divisor, color=colour, linestyle="--", linewidth=1.0, label=label)
            label = "_"
    if bounds is not None:
        label = "power bound: share of the available power"
        for i in range(len(names)):
            for sign in (1.0, -1.0) if np.any(thrust[:, i] < 0.0) else (1.0,):
                if np.isfinite(bounds[:, i]).any():
                    axes.plot(t, sign * bounds[:, i] / divisor, color=actuator_style(i)["color"], linestyle="-.",
                              linewidth=1.0, label=label)
                    label = "_"
    axes.axhline(0.0, color="black", linewidth=0.5)
    axes.set_ylim(view[0] / divisor, view[1] / divisor)
    axes.set_ylabel(f"thrust [{unit}]")


def _azimuth(axes, result: RunResult) -> None:
    a = result.trace.arrays()
    rotating = [i for i, actuator in enumerate(result.vehicle.actuators) if actuator.rotatable]
    _traces(axes, a["time"], np.degrees(np.unwrap(a["azimuth"], axis=0)), result.trace.names, rotating)
    axes.set_ylabel("azimuth [deg]")


def _power(axes, result: RunResult, nominal: RunResult | None) -> None:
    """The node's power estimate, the nominal run's dashed, and the saturated samples shaded."""
    a = result.trace.arrays()
    powers = [a["power"]] + ([nominal.trace.arrays()["power"]] if nominal is not None else [])
    divisor, unit = scale(np.concatenate(powers), "W")
    axes.plot(a["time"], a["power"] / divisor, color="black", linewidth=1.2, label=POWER_LABEL)
    if nominal is not None:
        axes.plot(nominal.trace.arrays()["time"], powers[1] / divisor, **NOMINAL, label=NOMINAL_LABEL)
    if a["saturated"].any():
        axes.fill_between(a["time"], 0.0, 1.0, where=a["saturated"] > 0, step="mid", color="tab:orange", alpha=0.35,
                          linewidth=0, transform=axes.get_xaxis_transform(), label="saturated samples")
    axes.set_ylim(bottom=0.0)
    axes.set_ylabel(f"power [{unit}]")


def timeline_figure(result: RunResult, scenario: Scenario, nominal: RunResult | None = None):
    """The timeline of ``result`` (of ``scenario``), with ``nominal``'s errors and power dashed."""
    plt = pyplot()
    a = result.trace.arrays()
    rotating = any(actuator.rotatable for actuator in result.vehicle.actuators)
    sagging = np.ptp(np.nan_to_num(a["voltage"])) > 0.0
    panels = ["position", "heading", *([] if scenario.horizontal else ["roll_pitch"]), "thrust",
              *(["azimuth"] if rotating else []), *(["voltage"] if sagging else []), "power",
              *(["sources"] if result.trace.sources else [])]
    ratios = [TALL.get(panel, 1.0) for panel in panels]
    figure, column = plt.subplots(len(panels), 1, figsize=(12.0, 1.2 + 1.9 * sum(ratios)), sharex=True,
                                  gridspec_kw={"height_ratios": ratios}, layout="constrained")
    axes = dict(zip(panels, column))
    _errors(axes, result, nominal, scenario.horizontal)
    _thrust(axes["thrust"], result, power_bounds(result, scenario))
    if rotating:
        _azimuth(axes["azimuth"], result)
    if "voltage" in axes:
        axes["voltage"].plot(a["time"], a["voltage"], color="black", linewidth=1.2,
                             label="supply voltage (the thrust limits follow it)")
        axes["voltage"].set_ylabel("voltage [V]")
    _power(axes["power"], result, nominal)
    if "sources" in axes:
        sources_panel(axes["sources"], result)
    column[0].set_xlim(a["time"][0], a["time"][-1])
    for panel in column:
        shade_faults(panel, result.fault_intervals)
        panel.grid(True, alpha=0.5)
    if result.fault_intervals:
        column[0].axvspan(0.0, 0.0, color=FAULT_COLOUR, alpha=0.1, label="a fault in force")
    for panel in column:
        legend_beside(panel)
    rows = mark_events(list(column), scenario.events)
    column[0].set_title(f"{scenario.name} ({scenario.method}, seed {scenario.seed})", loc="left",
                        pad=6 + rows * (LABEL_SIZE + 4))
    column[-1].set_xlabel("time [s]")
    return figure
