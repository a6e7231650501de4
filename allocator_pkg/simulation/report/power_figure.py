"""The power panel of ``timeline.png`` (:mod:`.sim_timeline`), for a vehicle with power sources:
each source's power drawn [kW], as the node's status reports it, against what the simulated
power plant could give (dashed, the same colour), and the stretches of the consequence alarm
shaded."""

from __future__ import annotations

import numpy as np

from ..run_setup import RunResult
from .style import actuator_style

ALARM_COLOUR = "tab:red"


def sources_panel(axes, result: RunResult) -> None:
    """Drawn and available power of every source; the consequence alarm shaded."""
    trace = result.trace
    t = np.array(trace.time)
    a = trace.power_arrays()
    drawn, available = a["source_power"], a["source_available"]
    for j, name in enumerate(trace.sources):
        colour = actuator_style(j)["color"]
        axes.plot(t, drawn[:, j], color=colour, linewidth=1.2, label=f"{name} drawn")
        axes.plot(t, available[:, j], color=colour, linestyle="--", linewidth=1.0,
                  label=f"{name} available")
    if a["consequence_alarm"].any():
        axes.fill_between(t, 0.0, 1.0, where=a["consequence_alarm"], step="mid", color=ALARM_COLOUR, alpha=0.12,
                          linewidth=0, transform=axes.get_xaxis_transform(), label="consequence alarm")
    axes.set_ylim(bottom=0.0)
    axes.set_ylabel("power per source [kW]")
