"""The power of ``timeline.png`` (:mod:`.timeline`), for a vehicle with power sources: each
source's power drawn [kW], as the node's status reports it, against what the simulated power
plant could give (dashed, the same colour), the stretches of the consequence alarm hatched in a
colour of their own (faults are red), and each actuator's thrust bound from the available power
(:func:`power_bounds`), which the thrust panel draws."""

from __future__ import annotations

import numpy as np

from ...allocation.allocator import Allocator
from ...effectiveness.faults import FaultMode
from ..run_setup import RunResult
from ..scenario import Scenario
from .style import actuator_style, fit_view

ALARM_COLOUR = "tab:purple"
"""The consequence alarm's hatching: not the red of a fault in force."""
ACTUATOR_EVENTS = ("fault", "clear_faults", "group_fault")


def power_bounds(result: RunResult, scenario: Scenario) -> np.ndarray | None:
    """[N] per sample and actuator, the thrust magnitude the available power leaves it in its
    range (:meth:`~allocator_pkg.allocation.power_budget.PowerBudget.limit`): the proportional
    bound for a method without power rows, the derating of a lost feed for one with them (whose
    rows keep the sources within their power without a bound per thruster); NaN where the power
    sets none. The scenario's faults and group losses, the recorded supply voltage and available
    power are replayed on an allocator of the run's vehicle and the scenario's method, so that
    the bounds are those the node worked with. None without power sources, or when the power
    never bounds a thrust."""
    trace = result.trace
    if not trace.sources:
        return None
    allocator = Allocator(result.vehicle, method=scenario.method)
    a = trace.arrays()
    available = trace.power_arrays()["source_available"]
    events = sorted((e for e in scenario.events if e.kind in ACTUATOR_EVENTS), key=lambda e: e.time)
    rows, voltage, power = [], None, None
    for k, t in enumerate(a["time"]):
        while events and events[0].time <= t + 1e-9:
            _replay(allocator, events.pop(0), a["azimuth"][k])
        if np.isfinite(a["voltage"][k]) and a["voltage"][k] != voltage:
            voltage = float(a["voltage"][k])
            allocator.set_voltage(voltage)
        if power is None or not np.array_equal(power, available[k]):
            power = available[k]
            allocator.set_available_power(dict(zip(trace.sources, power.tolist())))
        limit = allocator.power_limit
        rows.append(np.where(limit.limited, limit.bound, np.nan))
    bounds = np.array(rows, dtype=float).reshape(len(a["time"]), len(trace.names))
    return bounds if np.isfinite(bounds).any() else None


def _replay(allocator: Allocator, event, azimuth: np.ndarray) -> None:
    """A fault, clearing the faults or a group's loss on ``allocator``, as the run had them."""
    if event.kind == "group_fault":
        allocator.set_group_fault(event.name)
    elif event.kind == "clear_faults":
        allocator.clear_faults()
    else:
        mode = FaultMode[event.mode.upper()]
        index = allocator.names.index(event.actuator)
        angle = (float(azimuth[index]) if event.value is None else float(event.value)) \
            if mode == FaultMode.STUCK else 0.0
        allocator.set_fault(event.actuator, mode, efficiency=float(event.value) if mode == FaultMode.DEGRADED
                            else None, angle=angle)


def sources_panel(axes, result: RunResult) -> None:
    """Drawn and available power of every source, the view fitted to the power drawn (an
    available power far above it is named in the legend); the consequence alarm hatched."""
    trace = result.trace
    t = np.array(trace.time)
    a = trace.power_arrays()
    drawn, available = a["source_power"], a["source_available"]
    top = fit_view(drawn, available, floor=0.0)
    for j, name in enumerate(trace.sources):
        colour = actuator_style(j)["color"]
        axes.plot(t, drawn[:, j], color=colour, linewidth=1.2, label=f"{name} drawn")
        beyond = float(np.max(available[:, j], initial=0.0)) > top[1]
        label = f"{name} available" + (f" (up to {np.max(available[:, j]):.0f} kW, above the view)" if beyond else "")
        axes.plot(t, available[:, j], color=colour, linestyle="--", linewidth=1.0, label=label)
    if a["consequence_alarm"].any():
        axes.fill_between(t, 0.0, 1.0, where=a["consequence_alarm"], step="mid", facecolor="none",
                          edgecolor=ALARM_COLOUR, hatch="///", alpha=0.5, linewidth=0,
                          transform=axes.get_xaxis_transform(), label="consequence alarm")
    axes.set_ylim(*top)
    axes.set_ylabel("power per source [kW]")
