"""``footprint.png`` of an ``allocator-sim`` run: the track north and east of the set-point,
the samples under a fault in red, the heading as arrows at even intervals, start and end
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


def _offsets(result: RunResult) -> np.ndarray:
    """North and east of the set-point of each sample [m]."""
    a = result.trace.arrays()
    return (a["position"] - a["setpoint"])[:, :2]


def footprint_figure(result: RunResult, scenario: Scenario, nominal: RunResult | None = None):
    """The footprint of ``result`` (of ``scenario``), with ``nominal``'s track dashed."""
    plt = pyplot()
    a = result.trace.arrays()
    offset = _offsets(result)
    north, east = offset[:, 0], offset[:, 1]
    figure, axes = plt.subplots(figsize=(7.5, 8.4), layout="constrained")
    if nominal is not None:
        nominal_offset = _offsets(nominal)
        axes.plot(nominal_offset[:, 1], nominal_offset[:, 0], **NOMINAL, label=NOMINAL_LABEL)
    axes.plot(east, north, color="tab:blue", linewidth=1.0, label="track")
    faulted = a["faulted"].astype(bool)
    if faulted.any():
        axes.plot(east[faulted], north[faulted], ".", color=FAULT_COLOUR, markersize=2.5,
                  label="samples under a fault")
    extent = float(np.max(np.abs(offset), initial=0.0))
    if nominal is not None:
        extent = max(extent, float(np.max(np.abs(nominal_offset), initial=0.0)))
    bound = scenario.bounds.get("position_error_max")
    if bound is not None:
        shown = bound <= BOUND_IN_VIEW * extent
        extent = max(extent, bound) if shown else extent
        axes.add_patch(plt.Circle((0.0, 0.0), bound, fill=False, color=FAULT_COLOUR, linestyle="--", linewidth=1.0,
                                  label=f"bound {bound:g} m" + ("" if shown else " (beyond the view)")))
    limit = max(0.1, 1.1 * extent)
    interval = arrow_interval(scenario.duration)
    every = np.arange(0, len(north), max(1, round(interval / result.trace.period)))
    heading = a["attitude"][every, 2]
    length = 0.08 * limit
    axes.quiver(east[every], north[every], np.sin(heading) * length, np.cos(heading) * length, angles="xy",
                scale_units="xy", scale=1.0, width=0.004, color="0.25", label=f"heading, every {interval:g} s")
    axes.plot(east[0], north[0], "o", color="tab:green", markersize=8, label="start")
    axes.plot(east[-1], north[-1], "s", color="black", markersize=7, label="end")
    axes.plot(0.0, 0.0, "k+", markersize=14, markeredgewidth=1.5, label="set-point")
    axes.set_xlim(-limit, limit)
    axes.set_ylim(-limit, limit)
    axes.set_aspect("equal")
    axes.grid(True, alpha=0.5)
    axes.set_xlabel("east of the set-point [m]")
    axes.set_ylabel("north of the set-point [m]")
    metrics = result.metrics
    figure.suptitle(f"{scenario.name} ({scenario.method}, seed {scenario.seed}): footprint\n"
                    f"position error rms {metrics['position_error_rms']:.2f} m, max "
                    f"{metrics['position_error_max']:.2f} m", x=0.02, ha="left", fontsize=11)
    figure.legend(loc="outside lower center", ncol=2, fontsize=8, frameon=False)
    return figure
