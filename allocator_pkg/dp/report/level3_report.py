"""The outputs of a DNV-ST-0111 Level 3 study (``allocator-capability --dnv-level3``), named
``<vehicle>_dp_l3...`` in the output folder:

- ``_number.png`` / ``_wind.png``: intact and worst single failure; ``_groups_number.png`` /
  ``_groups_wind.png``: each group's loss (the Level 1 plots, :mod:`.capability_plots`);
- ``_vs_l1_l2_number.png`` / ``_vs_l1_l2_wind.png``: Level 1, 2 and 3 of the vessel on one (Level 1
  and 2 as published, at the standard's 10 deg headings, whatever the study's step: the result's
  :attr:`~allocator_pkg.dp.capability_result.CapabilityResult.lower`);
- ``_footprints.png``: per heading the x-y track of each case at its number (solid) and at the
  first condition that failed (dashed), with the position limit, every panel on one scale (three
  times the limit; a track that leaves it says how far it went);
- ``.csv``, ``_table_a1.csv`` and Tables A-2 to A-5 (:mod:`.summary`) as at Level 1;
  ``_limits.csv``: why each number stops where it does; ``_cases.csv``: every case run with its
  excursion statistics;
- ``.txt``: the DP capability-L3(A, B, C, D) line, the scope, the criteria, the notes and the
  Level 1 and 2 lines of the comparison plots.

Every one states the criteria and that the result is not verified by DNV.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...capability.report.plotting import pyplot
from ..capability_result import INTACT, WORST, CapabilityResult
from ..level1 import MAX_STEP_DEG
from ..level3.case import CaseResult
from ..level3.study import Level3Study
from .capability_plots import Outline, polar_figure, polar_plot
from .files import write_csv
from .summary import TABLES, input_tables, write_table
from .tables import groups_of, table_a1

CASE_COLUMNS = ("case", "heading_deg", "capability_number", "seed", "wind_speed", "hs", "tp", "current",
                "max_position_m", "mean_position_m", "max_heading_deg", "held")
INTERRUPTED = 130
"""The exit status of a run stopped by SIGINT (128 + the signal's number, as a shell gives)."""
LIMIT_COLUMNS = ("case", "heading_deg", "capability_number", "limited_by")
CASES_TABLE = ("Level 3 cases run: the condition (number; wind [m/s], Hs [m], Tp [s], current [m/s]) from the "
               "heading, intact or the group failed after settling; position excursion from the set-point [m] (max, "
               "mean), heading deviation [deg] (max), held")
LIMITS_TABLE = ("Level 3 per case and heading: the capability number and what limits it (failed: the next "
                "condition failed in the time domain; static Level 2: the static balance fails the next one, not "
                "simulated; top condition)")


def write_level3(prepared: Level3Study, result: CapabilityResult, finished: dict[tuple, CaseResult],
                 out: Path) -> list[Path]:
    """Every output of the study into ``out``; the paths written."""
    out.mkdir(parents=True, exist_ok=True)
    stem = f"{prepared.inputs.vessel.stem}_dp_l3"
    title = prepared.analysis.particulars.name or prepared.inputs.vessel.stem
    criteria = prepared.setup.criteria.short()
    outline = Outline.of(prepared.analysis)
    paths = []
    for suffix, caption, cases in (("", "intact and worst single failure", [INTACT, WORST]),
                                   ("_groups", "loss of each redundancy group", groups_of(result))):
        for wind, quantity in ((False, "number"), (True, "wind")):
            paths.append(out / f"{stem}{suffix}_{quantity}.png")
            polar_plot(paths[-1], result, title, f"{caption} ({criteria})", wind, cases, outline, (), suffix == "")
    level1, level2 = result.lower
    for wind, quantity in ((False, "number"), (True, "wind")):
        paths.append(out / f"{stem}_vs_l1_l2_{quantity}.png")
        levels_plot(paths[-1], (*result.lower, result), title, wind, outline, criteria)
    paths.append(out / f"{stem}_footprints.png")
    footprints(paths[-1], prepared, result, finished, title)
    paths.append(out / f"{stem}.csv")
    write_csv(paths[-1], result)
    scope = f"{result.scope} Criteria: {prepared.setup.criteria.describe()}."
    a1_columns, a1_rows = table_a1(result)
    tables = {**input_tables(prepared.analysis), "table_a1": (a1_columns, a1_rows)}
    for key, (columns, rows) in tables.items():
        paths.append(out / f"{stem}_{key}.csv")
        write_table(paths[-1], TABLES[key], scope, columns, rows)
    paths.append(out / f"{stem}_limits.csv")
    write_table(paths[-1], LIMITS_TABLE, scope, LIMIT_COLUMNS, limit_rows(prepared, finished))
    paths.append(out / f"{stem}_cases.csv")
    write_table(paths[-1], CASES_TABLE, scope, CASE_COLUMNS, case_rows(prepared, finished))
    paths.append(out / f"{stem}.txt")
    compared = (f"The comparison plots (_vs_l1_l2) show Level 1 and Level 2 as published (--dnv-level1, "
                f"--dnv-level2), at the standard's {MAX_STEP_DEG:g} deg headings: {level1.summary_line()}, "
                f"{level2.summary_line()}.")
    paths[-1].write_text("\n".join([f"{title}: {result.summary_line()}", "", result.scope, *result.notes, compared])
                         + "\n")
    return paths


def limit_rows(prepared: Level3Study, finished: dict[tuple, CaseResult]) -> list[tuple]:
    search = prepared.search
    return [(case, heading, outcome.number, outcome.reason) for heading, case in search.chains()
            for outcome in (search.outcome((heading, case), finished),)]


def case_rows(prepared: Level3Study, finished: dict[tuple, CaseResult]) -> list[tuple]:
    """One row per case run, in the order of the search's chains, then number and seed."""
    order = {case: k for k, case in enumerate(prepared.search.cases)}
    rows = []
    for key in sorted(finished, key=lambda k: (order[k[2]], k[0], k[1], k[3])):
        result, condition = finished[key], prepared.setup.conditions[key[1]]
        rows.append((key[2], key[0], key[1], key[3], condition.wind, condition.hs, condition.tp, condition.current,
                     result.max_position, result.mean_position, result.max_heading_deg, result.held))
    return rows


def levels_plot(path: Path, results: tuple[CapabilityResult, CapabilityResult, CapabilityResult], title: str,
                wind: bool,
                outline: Outline, criteria: str) -> None:
    """Level 1, 2 and 3, intact and worst single failure, on one polar figure."""
    plt = pyplot()

    level1, level2, level3 = results
    figure = polar_figure(level3, title, f"Level 1, 2 and 3 ({criteria})", wind, [INTACT, WORST], outline)
    axes = figure.axes[0]
    for line in axes.get_lines():
        line.set_label(f"Level 3 {line.get_label()}")
    for result, level, colours in ((level1, 1, ("tab:cyan", "tab:orange")), (level2, 2, ("tab:green", "tab:purple"))):
        angles = np.radians(np.append(result.headings_deg, result.headings_deg[0]))
        values = result.wind_limits if wind else result.numbers
        for case, colour in zip((INTACT, WORST), colours):
            axes.plot(angles, np.append(values[case], values[case][0]), color=colour, linewidth=1.3,
                      linestyle=":" if level == 1 else "-.", label=f"Level {level} {case} ({result.summary_line()})")
    top = max(r.conditions[-1].wind for r in results) if wind else max(len(r.conditions) for r in results) - 1
    axes.set_ylim(0.0, top)
    if not wind:
        axes.set_yticks(range(top + 1))
    for legend in figure.legends:
        legend.remove()
    figure.legend(loc="lower center", bbox_to_anchor=(0.5, 0.05), ncol=2, fontsize=7.5, frameon=False)
    figure.savefig(path, dpi=100)
    plt.close(figure)


FOOTPRINT_VIEW = 3.0
"""Every footprint panel shows this many times the position limit about the set-point, the same
scale in each, so that the limit's circle reads alike; a track that leaves the view says how far
it went."""
CASE_COLOURS = ("tab:blue", "tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:pink", "tab:olive",
                "tab:cyan")


def footprints(path: Path, prepared: Level3Study, result: CapabilityResult, finished: dict[tuple, CaseResult],
               title: str) -> None:
    """:func:`footprints_figure` written to ``path``."""
    figure = footprints_figure(prepared, result, finished, title)
    figure.savefig(path, dpi=90)
    pyplot().close(figure)


def footprints_figure(prepared: Level3Study, result: CapabilityResult, finished: dict[tuple, CaseResult], title: str):
    """Per heading, each case's x-y track (seed 0) at its number (solid) and at the first condition
    that failed (dashed), east to the right, north up, with the position limit's circle: every
    panel :data:`FOOTPRINT_VIEW` times the limit about the set-point, axes in metres on the outer
    panels, each case's number in the panel's title, one legend under the panels."""
    import textwrap

    from matplotlib.lines import Line2D
    from matplotlib.ticker import MaxNLocator

    plt = pyplot()

    search, limit = prepared.search, prepared.setup.criteria.position_limit
    view = FOOTPRINT_VIEW * limit
    columns = min(6, len(search.headings))
    rows = math.ceil(len(search.headings) / columns)
    figure, grid = plt.subplots(rows, columns, figsize=(2.6 * columns, 2.7 * rows + 2.0), squeeze=False,
                                sharex=True, sharey=True, layout="constrained")
    colours = dict(zip(search.cases, CASE_COLOURS))
    circle = np.linspace(0.0, 2.0 * math.pi, 73)
    for axes, heading in zip(grid.flat, search.headings):
        axes.plot(limit * np.sin(circle), limit * np.cos(circle), color="tab:red", linewidth=0.8)
        numbers, farthest = [], 0.0
        for case in search.cases:
            number = search.outcome((heading, case), finished).number
            numbers.append(f"{case} {number}")
            for shown, style in ((number, "-"), (number + 1, "--")):
                track = finished.get((heading, shown, case, 0))
                if track is not None:
                    points = np.array(track.track)
                    axes.plot(points[:, 1], points[:, 0], style, color=colours.get(case, "k"), linewidth=0.9)
                    farthest = max(farthest, float(np.max(np.abs(points), initial=0.0)))
        axes.set_title(f"{heading:g} deg\n" + "\n".join(textwrap.wrap(", ".join(numbers), 44)), fontsize=7)
        if farthest > view:
            axes.text(0.03, 0.03, f"off view: to {farthest:.0f} m", transform=axes.transAxes, fontsize=6.5,
                      color="0.25")
        axes.set_xlim(-view, view)
        axes.set_ylim(-view, view)
        axes.set_aspect("equal")
        axes.tick_params(labelsize=7)
        for axis in (axes.xaxis, axes.yaxis):
            axis.set_major_locator(MaxNLocator(5, symmetric=True))
    for axes in list(grid.flat)[len(search.headings):]:
        axes.axis("off")
    for axes in grid[-1, :]:
        axes.set_xlabel("east [m]", fontsize=8)
    for axes in grid[:, 0]:
        axes.set_ylabel("north [m]", fontsize=8)
    handles = [Line2D([], [], color=colours[case], linewidth=1.2, label=case) for case in search.cases]
    handles += [Line2D([], [], color="0.3", linestyle="-", label="at the case's number (in the panel's title)"),
                Line2D([], [], color="0.3", linestyle="--", label="at the first condition that failed"),
                Line2D([], [], color="tab:red", linewidth=0.8, label=f"position limit {limit:g} m")]
    figure.legend(handles=handles, loc="outside lower center", ncol=min(len(handles), 4), fontsize=8, frameon=False)
    heading_text = (f"{title}: {result.summary_line()}. x-y track from the set-point [m] (east right, north up; bow "
                    f"north, environment from the heading), seed 0. {prepared.setup.criteria.describe()}. "
                    "Not verified by DNV.")
    figure.suptitle("\n".join(textwrap.wrap(heading_text, int(26 * columns))), fontsize=9)
    return figure

