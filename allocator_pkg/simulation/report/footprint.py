"""``footprint.png`` of an ``allocator-sim`` run: the track north and east of the set-point (of
the first set-point, each later one marked, when the set-point moves), the samples under a
fault in red, the heading as arrows at even intervals, start and end
marked, the scenario's bound on the position error as a circle, and the nominal run's track
(same seed, nothing going wrong) dashed."""

from __future__ import annotations

import math

import numpy as np

from ...capability.report.plotting import pyplot
from ..run_setup import RunResult
from ..scenario import Scenario
from .style import FAULT_COLOUR, NOMINAL, NOMINAL_LABEL

ARROWS = 12
"""About how many heading arrows a track gets."""
MARKED = 6
"""At most this many set-points a moving run held are marked one by one; more make a path."""
BOUND_IN_VIEW = 2.5
"""The bound circle is in view when at most this many times the track's extent; farther out,
the view keeps to the track and the legend gives the bound."""


def arrow_interval(duration: float) -> float:
    """[s] between heading arrows: 1, 2 or 5 times a power of ten, about ``ARROWS`` in ``duration``."""
    if duration <= 0.0:
        return 1.0
    rough = duration / ARROWS
    power = 10.0 ** math.floor(math.log10(rough))
    return next(step * power for step in (1.0, 2.0, 5.0, 10.0) if step * power >= rough)


def held_setpoints(result: RunResult) -> list[tuple[float, np.ndarray]]:
    """(time [s], north and east [m]) of each set-point position the run held, in order."""
    a = result.trace.arrays()
    held: list[tuple[float, np.ndarray]] = []
    for t, point in zip(a["time"], a["setpoint"][:, :2]):
        if not held or np.any(point != held[-1][1]):
            held.append((float(t), point))
    return held


def offsets(result: RunResult, origin: np.ndarray | None) -> np.ndarray:
    """North and east [m] of each sample: of ``origin`` (the first set-point of a run whose
    set-point moves), or of the set-point in force (None), which would show a vehicle that
    follows a set-point 10 m north going 10 m south."""
    a = result.trace.arrays()
    return a["position"][:, :2] - (a["setpoint"][:, :2] if origin is None else origin)


def origin_of(result: RunResult) -> np.ndarray | None:
    """The first set-point when the run's set-point moves, else None (:func:`offsets`)."""
    held = held_setpoints(result)
    return held[0][1] if len(held) > 1 else None


def mark_setpoints(axes, result: RunResult, origin: np.ndarray | None, bound: float | None = None) -> None:
    """The set-point (a cross), or each one a moving run held, labelled with the time it came;
    with ``bound``, the bound circle about each (a path when it moved through many)."""
    plt = pyplot()
    held = held_setpoints(result) if origin is not None else [(0.0, np.zeros(2))]
    base = np.zeros(2) if origin is None else origin
    if len(held) > MARKED:
        path = np.array([point for _, point in held]) - base
        axes.plot(path[:, 1], path[:, 0], color="black", linewidth=0.8, linestyle=":", label="set-point path")
        held = [held[0], held[-1]]
    for k, (t, point) in enumerate(held):
        north, east = point - base
        axes.plot(east, north, "k+", markersize=14, markeredgewidth=1.5, label="_" if k else "set-point")
        if origin is not None:
            axes.annotate(f"set-point from {t:g} s", (east, north), xytext=(6, 6), textcoords="offset points",
                          fontsize=8)
        if bound is not None:
            axes.add_patch(plt.Circle((east, north), bound, fill=False, color=FAULT_COLOUR, linestyle="--",
                                      linewidth=1.0, label="_" if k else f"bound {bound:g} m"
                                      + (" about each set-point" if len(held) > 1 else "")))


def footprint_figure(result: RunResult, scenario: Scenario, nominal: RunResult | None = None):
    """The footprint of ``result`` (of ``scenario``), with ``nominal``'s track dashed."""
    plt = pyplot()
    a = result.trace.arrays()
    origin = origin_of(result)
    offset = offsets(result, origin)
    north, east = offset[:, 0], offset[:, 1]
    figure, axes = plt.subplots(figsize=(7.5, 8.4), layout="constrained")
    if nominal is not None:
        nominal_offset = offsets(nominal, origin)
        axes.plot(nominal_offset[:, 1], nominal_offset[:, 0], **NOMINAL, label=NOMINAL_LABEL)
    axes.plot(east, north, color="tab:blue", linewidth=1.0, label="track")
    faulted = a["faulted"].astype(bool)
    if faulted.any():
        axes.plot(east[faulted], north[faulted], ".", color=FAULT_COLOUR, markersize=2.5,
                  label="samples under a fault")
    points = [offset] + ([nominal_offset] if nominal is not None else [])
    base = np.zeros(2) if origin is None else origin
    targets = np.array([p - base for _, p in held_setpoints(result)]) if origin is not None else np.zeros((1, 2))
    extent = float(np.max(np.abs(np.concatenate(points)), initial=0.0))
    bound = scenario.bounds.get("position_error_max")
    shown = bound is not None and bound <= BOUND_IN_VIEW * extent
    mark_setpoints(axes, result, origin, bound if shown else None)
    if bound is not None and not shown:
        axes.plot([], [], color=FAULT_COLOUR, linestyle="--", linewidth=1.0,
                  label=f"bound {bound:g} m (beyond the view)")
    content = np.concatenate([*points, targets] + ([targets - bound, targets + bound] if shown else []))
    low, high = content.min(axis=0), content.max(axis=0)
    centre, half = (low + high) / 2.0, max(0.1, 0.55 * float(np.max(high - low)))
    interval = arrow_interval(scenario.duration)
    every = np.arange(0, len(north), max(1, round(interval / result.trace.period)))
    heading = a["attitude"][every, 2]
    length = 0.08 * half
    axes.quiver(east[every], north[every], np.sin(heading) * length, np.cos(heading) * length, angles="xy",
                scale_units="xy", scale=1.0, width=0.004, color="0.25", label=f"heading, every {interval:g} s")
    axes.plot(east[0], north[0], "o", color="tab:green", markersize=8, label="start")
    axes.plot(east[-1], north[-1], "s", color="black", markersize=7, label="end")
    axes.set_xlim(centre[1] - half, centre[1] + half)
    axes.set_ylim(centre[0] - half, centre[0] + half)
    axes.set_aspect("equal")
    axes.grid(True, alpha=0.5)
    where = "the set-point" if origin is None else "the first set-point"
    axes.set_xlabel(f"east of {where} [m]")
    axes.set_ylabel(f"north of {where} [m]")
    metrics = result.metrics
    figure.suptitle(f"{scenario.name} ({scenario.method}, seed {scenario.seed}): footprint\n"
                    f"position error rms {metrics['position_error_rms']:.2f} m, max "
                    f"{metrics['position_error_max']:.2f} m", x=0.02, ha="left", fontsize=11)
    figure.legend(loc="outside lower center", ncol=2, fontsize=8, frameon=False)
    return figure
