"""``plant.png`` of a run with a simulated electric power plant (:mod:`..electric_plant`): per
switchboard the frequency of its bus [pu] (with the 0.95 pu of ``time_under_frequency`` and the
relays' 0.9 pu), the power it supplies [MW] against what the power management system reports
available to its thrusters (dashed), and the vessel's position error [m]; the scenario's events
marked, each set a relay tripped named where it tripped. :func:`plant_columns` draws several
runs side by side (docs/power.md's benchmark figure)."""

from __future__ import annotations

import numpy as np

from ...capability.report.plotting import pyplot
from ..electric_plant import RELAY
from ..plant_metrics import UNDER_FREQUENCY
from ..run_setup import RunResult
from ..scenario import Scenario
from .style import FAULT_COLOUR, LABEL_SIZE, LIMIT_COLOUR, PALETTE, mark_events


def plant_panels(axes, result: RunResult, scenario: Scenario, title: str, start: float = 0.0) -> None:
    """Frequency, power and position error of ``result`` on the three ``axes``, from ``start`` [s]."""
    record, trace = result.plant, result.trace
    time = np.array(record.time)
    frequency = np.array(record.frequency)
    load = np.array(record.load) / 1000.0
    sources = trace.sources
    available = np.array(trace.source_available) / 1000.0
    for j, name in enumerate(sources):
        colour = PALETTE[j % len(PALETTE)]
        axes[0].plot(time, frequency[:, j], color=colour, linewidth=1.2, label=name)
        axes[1].plot(time, load[:, j], color=colour, linewidth=1.2, label=f"{name} supplied")
        axes[1].plot(trace.time, available[:, j], color=colour, linewidth=1.0, linestyle=(0, (4, 2)),
                     label=f"{name} available to its thrusters")
    for level, text in ((UNDER_FREQUENCY, f"{UNDER_FREQUENCY:g} pu"), (0.9, "relays 0.9 pu")):
        axes[0].axhline(level, color=LIMIT_COLOUR, linewidth=0.8, linestyle=":")
        axes[0].annotate(text, (time[0], level), fontsize=LABEL_SIZE, color=LIMIT_COLOUR, va="bottom")
    for when, name, why in record.trips:
        if why == RELAY:
            axes[0].annotate(f"{name} tripped", (when, 0.9), fontsize=LABEL_SIZE, color=FAULT_COLOUR, ha="left")
    low = max(0.85, float(np.min(frequency[frequency > 0.0], initial=1.0)) - 0.01)
    axes[0].set_ylim(low, max(1.02, float(frequency.max()) + 0.005))
    axes[0].set_ylabel("bus frequency [pu]")
    axes[1].set_ylabel("power [MW]")
    errors = trace.position_errors()
    axes[2].plot(trace.time, errors, color="k", linewidth=1.2)
    axes[2].set_ylim(0.0, 1.1 * float(np.max(errors[np.array(trace.time) >= start], initial=1.0)))
    axes[2].set_ylabel("position error [m]")
    axes[2].set_xlabel("time [s]")
    for a in axes:
        a.grid(True, alpha=0.5)
        a.set_xlim(start, time[-1])
    axes[0].legend(fontsize=LABEL_SIZE, loc="lower left")
    axes[1].legend(fontsize=LABEL_SIZE - 1, loc="upper left", ncol=2)
    rows = mark_events(list(axes), scenario.events)
    axes[0].set_title(title, loc="left", fontsize=10, pad=6 + 11 * rows)


def plant_columns(runs: list[tuple[RunResult, Scenario, str]], start: float = 0.0):
    """One column of :func:`plant_panels` per run (result, scenario, title), from ``start`` [s]."""
    plt = pyplot()
    figure, axes = plt.subplots(3, len(runs), figsize=(7.0 * len(runs), 9.0), sharex=True, squeeze=False)
    figure.subplots_adjust(left=0.07, right=0.98, top=0.9, bottom=0.06, hspace=0.12, wspace=0.18)
    for column, (result, scenario, title) in enumerate(runs):
        plant_panels(axes[:, column], result, scenario, title, start)
    return figure


def plant_figure(result: RunResult, scenario: Scenario):
    """``plant.png`` of one run."""
    return plant_columns([(result, scenario, f"{scenario.name}: the power plant")])
