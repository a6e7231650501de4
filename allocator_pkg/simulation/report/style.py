"""What the figures of ``allocator-sim`` share: one colour and line style per actuator, the
scenario's events as labelled vertical lines, the fault intervals shaded, views and units fitted
to the data (a limit far beyond it named, not drawn), legends beside the axes, and the nominal
run's style (matplotlib itself from :func:`allocator_pkg.capability.report.plotting.pyplot`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..scenario import Event

PALETTE = ("#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf")
"""Actuator colours: matplotlib's tab10 without red (faults) and grey (limits), eight that tell
apart (the Foxglove layouts use them too)."""
STYLES = ("-", "-.", ":", (0, (3, 1, 1, 1, 1, 1)))
OVERLAID = (0, (5, 4))
"""The dashes of a trace drawn over an equal one."""
FAULT_COLOUR = "tab:red"
LIMIT_COLOUR = "#595959"
NOMINAL = {"color": "0.6", "linestyle": (0, (4, 2)), "linewidth": 3.0, "zorder": 1.5}
"""The nominal run (same seed, nothing going wrong): wide light dashes under the run's line,
seen beside it where the two agree."""
NOMINAL_LABEL = "nominal run: same seed, no failure"
EVENT_COLOURS = {"fault": FAULT_COLOUR, "group_fault": FAULT_COLOUR, "clear_faults": "tab:green"}
LABEL_SIZE = 8
"""[pt] of the events' labels."""


def actuator_style(index: int) -> dict[str, Any]:
    """Colour and line style of actuator ``index``: a colour of its own up to eight, then the
    colours again with another line style."""
    return {"color": PALETTE[index % len(PALETTE)], "linestyle": STYLES[index // len(PALETTE) % len(STYLES)],
            "linewidth": 1.3}


def overlaid(values: np.ndarray, share: float = 0.9) -> list[bool]:
    """Per column of ``values`` (samples x actuators): whether it runs along an earlier column,
    within 1 % of the largest magnitude in at least ``share`` of the samples. Such a trace is
    drawn dashed (:data:`OVERLAID`) over the other, so that both show."""
    tolerance = 0.01 * max(float(np.nanmax(np.abs(values), initial=0.0)), 1e-12)
    close = [[np.mean(np.abs(values[:, j] - values[:, i]) <= tolerance) >= share for i in range(j)]
             for j in range(values.shape[1])]
    return [any(row) for row in close]


VIEW_REACH = 2.0
"""A limit line is in view when at most this many times the largest magnitude of the data."""
VIEW_MARGIN = 0.08
"""The share of a view's span left free above and below the data."""


def fit_view(data: np.ndarray, *references: np.ndarray, floor: float | None = None) -> tuple[float, float]:
    """(low, high) of an axis that shows ``data`` and zero, and the values of ``references``
    (limits, available power) that lie within :data:`VIEW_REACH` times the data's largest
    magnitude, with a margin; not below ``floor`` when given. A reference farther out would
    squeeze the data into a sliver of the axis: the caller names it in the legend instead."""
    values = np.asarray(data, dtype=float)
    values = values[np.isfinite(values)]
    low, high = min(float(values.min(initial=0.0)), 0.0), max(float(values.max(initial=0.0)), 0.0)
    reach = VIEW_REACH * max(abs(low), abs(high))
    for reference in references:
        shown = np.asarray(reference, dtype=float)
        shown = shown[np.isfinite(shown) & (np.abs(shown) <= reach)]
        if shown.size:
            low, high = min(low, float(shown.min())), max(high, float(shown.max()))
    margin = VIEW_MARGIN * ((high - low) or 1.0)
    low, high = low - margin, high + margin
    return (low if floor is None else max(low, floor)), high


def in_view(values: np.ndarray, view: tuple[float, float]) -> bool:
    """Whether some finite value of ``values`` lies inside ``view``."""
    values = np.asarray(values, dtype=float)
    return bool(np.any(np.isfinite(values) & (values >= view[0]) & (values <= view[1])))


def scale(values: np.ndarray, unit: str) -> tuple[float, str]:
    """(divisor, unit with its prefix): k or M where the largest magnitude reaches 1e4 or 1e7."""
    largest = float(np.nanmax(np.abs(values), initial=0.0)) if np.size(values) else 0.0
    if largest >= 1e7:
        return 1e6, f"M{unit}"
    if largest >= 1e4:
        return 1e3, f"k{unit}"
    return 1.0, unit


def event_label(event: Event) -> str:
    """What happened at an event, in a few words."""
    if event.kind == "fault":
        words = f"{event.actuator} {event.mode.upper()}"
        if event.mode == "degraded":
            words += f" to {event.value:g}"
        elif event.mode == "stuck" and event.value is not None:
            words += f" at {math.degrees(event.value):.0f} deg"
        return words
    if event.kind == "clear_faults":
        return "faults cleared"
    if event.kind == "battery_ramp":
        return f"battery to {event.value:g} V in {event.duration:g} s"
    if event.kind == "parameter":
        return f"{event.name.removeprefix('actuators.')} = {event.value}"
    if event.kind == "group_fault":
        return f"{event.name} FAILED"
    if event.kind == "power":
        return f"{event.name} {event.value:g} kW"
    if event.kind == "weather_ramp":
        return f"weather x{event.value:g} in {event.duration:g} s"
    return event.kind.replace("_", " ")


def mark_events(axes_list, events) -> int:
    """Each event as a dotted vertical line on every axes, its label above the first, in as many
    rows as keep the labels apart; the number of rows. Call it once the figure holds everything
    that takes room beside the axes (legends): the labels are measured on the laid-out figure."""
    from matplotlib.font_manager import FontProperties

    top = axes_list[0]
    figure = top.figure
    figure.draw_without_rendering()
    renderer = figure.canvas.get_renderer()
    span = top.get_xlim()
    width = top.get_window_extent(renderer).width                              # [px]
    font = FontProperties(size=LABEL_SIZE)
    gap = 8.0 * figure.dpi / 72.0                                              # [px] the offset and a space
    ends: list[float] = []                                                     # per row, where its last label ends
    for event in sorted(events, key=lambda e: e.time):
        colour = EVENT_COLOURS.get(event.kind, "0.2")
        for axes in axes_list:
            axes.axvline(event.time, color=colour, linestyle=":", linewidth=1.2)
        text = event_label(event)
        start = (event.time - span[0]) / (span[1] - span[0])
        length = (renderer.get_text_width_height_descent(text, font, ismath=False)[0] + gap) / width
        right = start + length > 1.0                                           # written leftward from the line
        first, last = (start - length, start) if right else (start, start + length)
        row = next((r for r, end in enumerate(ends) if end < first), len(ends))
        ends[row:row + 1] = [last]
        top.annotate(text, xy=(event.time, 1.0), xycoords=("data", "axes fraction"),
                     xytext=(-2 if right else 2, 3 + row * (LABEL_SIZE + 4)), textcoords="offset points",
                     ha="right" if right else "left", va="bottom", fontsize=LABEL_SIZE, color=colour)
    return len(ends)


def shade_faults(axes, intervals) -> None:
    for start, end in intervals:
        axes.axvspan(start, end, color=FAULT_COLOUR, alpha=0.1, linewidth=0)


def legend_beside(axes) -> None:
    """The axes' legend to its right, outside the data."""
    if axes.get_legend_handles_labels()[0]:
        axes.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
