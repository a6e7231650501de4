"""The plots of a DNV-ST-0111 Level 3 study that show its runs (``<vessel>_dp_l3...``):

- ``_footprints.png``: per heading the x-y track of each case at its number (solid) and at the
  first condition that failed (dashed), one fixed scale over every panel about the position
  limit's circle; a track that leaves the view ends in a marker on its edge and the panel says
  how far each case went;
- ``_quantiles.png``: per case and heading the stated quantile over the seeds of the largest
  position excursion and heading deviation, with its bootstrap interval, at the case's number
  and at the first condition that failed, and the limits;
- ``_transients.png``: per redundancy group the position excursion against the time since the
  failure at the case's number, every heading, with the post-failure limit over its window and
  the position limit after it.

Each shows one seed's run where it shows a run: the seed whose largest excursion is nearest the
stated quantile (:func:`representative`). Every caption states the criteria and that the result
is not verified by DNV.
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Mapping

import numpy as np

from ...capability.report.plotting import pyplot
from ..capability_result import INTACT, CapabilityResult
from ..level3.case import TRACK_PERIOD, CaseResult, Criteria
from ..level3.statistics import condition_spreads, seed_quantile
from ..level3.study import Level3Study

FOOTPRINT_VIEW = 3.0
"""Every footprint panel shows this many times the position limit about the set-point, the same
scale in each, so that the limit's circle reads alike."""
TRANSIENT_VIEW = 2.0
"""The transients plot shows excursions up to this many times the larger of the two position limits."""
QUANTILE_VIEW = 2.0
"""A quantiles panel shows up to this many times its limit (a group's: the larger of its limit and
its post-failure limit); a quantile above it is drawn on the edge with its value."""
CASE_COLOURS = ("tab:blue", "tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:pink", "tab:olive",
                "tab:cyan")


def representative(results: list[CaseResult], criteria: Criteria) -> CaseResult:
    """The run whose largest position excursion is nearest the criteria's quantile of them over
    ``results`` (the lowest seed of equals)."""
    target = seed_quantile([r.max_position for r in results], criteria)
    return min(results, key=lambda r: (abs(r.max_position - target), r.case.seed))


def shown_run(prepared: Level3Study, chain: tuple[float, str], number: int,
              finished: Mapping[tuple, CaseResult]) -> CaseResult | None:
    """The :func:`representative` run of ``chain`` at ``number``, None if not every seed ran."""
    results = prepared.search.seed_results(chain, number, finished)
    return None if results is None else representative(results, prepared.setup.criteria)


def caption(prepared: Level3Study, result: CapabilityResult, title: str, what: str, width: int) -> str:
    """A figure's title: the summary, what it shows, the criteria, not verified by DNV; wrapped to
    ``width`` characters a line."""
    text = (f"{title}: {result.summary_line()}. {what} Criteria: {prepared.setup.criteria.short()}. "
            "DNV-ST-0111 Level 3 as read here, no Level 3 text available. Not verified by DNV.")
    return "\n".join(textwrap.wrap(text, width))


def save(figure, path) -> None:
    figure.savefig(path, dpi=90)
    pyplot().close(figure)


def footprints_figure(prepared: Level3Study, result: CapabilityResult, finished: Mapping[tuple, CaseResult],
                      title: str):
    """Per heading, each case's x-y track (:func:`shown_run`) at its number (solid) and at the
    first condition that failed (dashed), east to the right, north up, with the position limit's
    circle: every panel :data:`FOOTPRINT_VIEW` times the limit about the set-point, axes in metres
    on the outer panels, each case's number in the panel's title, one legend under the panels; a
    track that leaves the view ends in a triangle on its edge and the panel lists how far (the
    largest distance from the set-point) each such case went."""
    from matplotlib.lines import Line2D
    from matplotlib.ticker import MaxNLocator

    plt = pyplot()
    search, limit = prepared.search, prepared.setup.criteria.position_limit
    post_limit = prepared.setup.criteria.post_failure_position_limit
    view = FOOTPRINT_VIEW * limit
    columns = min(6, len(search.headings))
    rows = math.ceil(len(search.headings) / columns)
    width = max(2.6 * columns, 8.0)
    figure, grid = plt.subplots(rows, columns, figsize=(width, 2.6 * rows + 2.0), squeeze=False, sharex=True,
                                sharey=True, layout="constrained")
    colours = dict(zip(search.cases, CASE_COLOURS))
    circle = np.linspace(0.0, 2.0 * math.pi, 73)
    for axes, heading in zip(grid.flat, search.headings):
        axes.plot(limit * np.sin(circle), limit * np.cos(circle), color="tab:red", linewidth=0.8)
        if post_limit != limit and post_limit < view:
            axes.plot(post_limit * np.sin(circle), post_limit * np.cos(circle), color="tab:purple", linewidth=0.8,
                      linestyle=":")
        numbers, beyond = [], []
        for case in search.cases:
            number = search.outcome((heading, case), finished).number
            numbers.append(f"{case} {number}")
            for shown, style in ((number, "-"), (number + 1, "--")):
                run = shown_run(prepared, (heading, case), shown, finished)
                if run is not None:
                    farthest = draw_track(axes, np.array(run.track), view, style, colours[case])
                    if farthest > view:
                        beyond.append(f"{case} {shown}: {farthest:.3g} m")
        axes.set_title(f"{heading:g} deg\n" + "\n".join(textwrap.wrap(", ".join(numbers), int(17 * width / columns))),
                       fontsize=7)
        if beyond:
            axes.text(0.03, 0.03, "off view:\n" + "\n".join(beyond), transform=axes.transAxes, fontsize=5.5,
                      color="0.2", va="bottom", bbox=dict(facecolor="white", alpha=0.7, linewidth=0))
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
                Line2D([], [], color="0.3", marker=">", linestyle="none", label="leaves the view here"),
                Line2D([], [], color="tab:red", linewidth=0.8, label=f"position limit {limit:g} m")]
    if post_limit != limit and post_limit < view:
        handles.append(Line2D([], [], color="tab:purple", linewidth=0.8, linestyle=":",
                              label=f"post-failure limit {post_limit:g} m"))
    figure.legend(handles=handles, loc="outside lower center", ncol=min(len(handles), 4), fontsize=8, frameon=False)
    what = ("x-y track from the set-point [m] (east right, north up; bow north, environment from the heading) of "
            "the seed nearest the quantile.")
    figure.suptitle(caption(prepared, result, title, what, int(15 * width)), fontsize=8)
    return figure


def draw_track(axes, points: np.ndarray, view: float, style: str, colour: str) -> float:
    """A track (north, east) on ``axes``, a triangle where it first leaves the square of half-side
    ``view``; the largest distance [m] from the set-point it reaches."""
    axes.plot(points[:, 1], points[:, 0], style, color=colour, linewidth=0.9)
    outside = np.flatnonzero(np.max(np.abs(points), axis=1) > view)
    if outside.size:
        north, east = np.clip(points[outside[0]], -view, view)
        axes.plot(east, north, marker=">", color=colour, markersize=5, clip_on=False)
    return float(np.max(np.hypot(points[:, 0], points[:, 1]), initial=0.0))


QUANTITIES = (("steady_position", "position excursion [m]", "position_limit"),
              ("steady_heading_deg", "heading deviation [deg]", "heading_limit_deg"))
"""(metric, axis label, limit) of each row of the quantiles plot."""


def quantiles_figure(prepared: Level3Study, result: CapabilityResult, finished: Mapping[tuple, CaseResult],
                     title: str):
    """Per case (a column) and heading the quantile over the seeds of each run's largest position
    excursion (top) and heading deviation (bottom), outside the post-failure window, with its
    bootstrap interval, at the case's number (dots) and at the first condition that failed
    (squares), and the limit; a group's post-failure quantiles (triangles) against the
    post-failure limit (dashed)."""
    plt = pyplot()
    search, criteria = prepared.search, prepared.setup.criteria
    columns = len(search.cases)
    width = max(3.6 * columns, 8.0)
    figure, grid = plt.subplots(2, columns, figsize=(width, 7.2), squeeze=False, sharex=True, layout="constrained")
    for column, case in enumerate(search.cases):
        for row, (metric, label, limit) in enumerate(QUANTITIES):
            axes = grid[row, column]
            transient = metric.replace("steady", "transient")
            post = getattr(criteria, f"post_failure_{limit}")
            top = QUANTILE_VIEW * max(getattr(criteria, limit), post if case != INTACT else 0.0)
            for series, marker, fill in ((0, "o", None), (1, "s", "none")):
                draw_quantiles(axes, prepared, finished, (case, series, metric), (marker, fill, "tab:blue"), top)
                if case != INTACT and series == 0:
                    draw_quantiles(axes, prepared, finished, (case, series, transient), ("^", None, "tab:purple"),
                                   top)
            axes.axhline(getattr(criteria, limit), color="tab:red", linewidth=0.9)
            if case != INTACT:
                axes.axhline(post, color="tab:purple", linewidth=0.9, linestyle="--")
            axes.set_ylim(0.0, top)
            axes.set_ylabel(label, fontsize=8)
            axes.tick_params(labelsize=7)
        grid[0, column].set_title(case, fontsize=9)
        grid[1, column].set_xlabel("heading [deg] (environment from)", fontsize=8)
        grid[1, column].set_xticks(np.arange(0.0, 361.0, 90.0))
    from matplotlib.lines import Line2D
    q = f"P{100 * criteria.quantile:g}"
    handles = [Line2D([], [], color="tab:blue", marker="o", linestyle="none", label=f"{q} at the case's number"),
               Line2D([], [], color="tab:blue", marker="s", markerfacecolor="none", linestyle="none",
                      label=f"{q} at the first condition that failed"),
               Line2D([], [], color="tab:purple", marker="^", linestyle="none",
                      label=f"{q} within {criteria.post_failure_window:g} s of the failure, at the number"),
               Line2D([], [], color="0.3", label=f"{100 * criteria.confidence:g} % bootstrap interval"),
               Line2D([], [], color="tab:red", label="limit"),
               Line2D([], [], color="tab:purple", linestyle="--", label="post-failure limit")]
    figure.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=8, frameon=False)
    what = f"{q} over {criteria.seeds} seeds of each run's largest excursion per heading, with its interval."
    figure.suptitle(caption(prepared, result, title, what, int(15 * width)), fontsize=8)
    return figure


def draw_quantiles(axes, prepared: Level3Study, finished: Mapping[tuple, CaseResult], what: tuple[str, int, str],
                   style: tuple[str, str | None, str], top: float) -> None:
    """The quantile and interval of a metric per heading, ``what`` = (case, 0 at the case's number
    or 1 the condition above it, metric), ``style`` = (marker, face colour, colour); a quantile
    above ``top`` drawn on it with its value."""
    case, above, metric = what
    marker, fill, colour = style
    search = prepared.search
    headings, values, low, high = [], [], [], []
    for heading in search.headings:
        number = search.outcome((heading, case), finished).number + above
        results = search.seed_results((heading, case), number, finished) if number >= 1 else None
        spread = condition_spreads(results, prepared.setup.criteria)[metric] if results else None
        if spread is not None:
            headings.append(heading)
            values.append(spread.quantile)
            low.append(spread.quantile - spread.low)
            high.append(spread.high - spread.quantile)
    if not headings:
        return
    shown = np.minimum(values, top)
    clipped = np.array(values) > top
    low, high = np.where(clipped, 0.0, low), np.where(clipped, 0.0, np.minimum(high, top - shown))
    axes.errorbar(headings, shown, yerr=[low, high], marker=marker, markerfacecolor=fill,
                  color=colour, linestyle="none", markersize=4, elinewidth=0.8, capsize=2, clip_on=False)
    for heading, value in zip(headings, values):
        if value > top:
            axes.annotate(f"{value:.3g}", (heading, top), xytext=(3, -9), textcoords="offset points", fontsize=6.5,
                          color=colour, annotation_clip=False)


def transients_figure(prepared: Level3Study, result: CapabilityResult, finished: Mapping[tuple, CaseResult],
                      title: str):
    """Per group (a panel) the position excursion [m] against the time since the failure [s] of
    the :func:`representative` run at the case's number, a line per heading (coloured by
    heading), the post-failure limit over its window and the position limit after it, one scale
    (:data:`TRANSIENT_VIEW`); a run that goes above it is marked where it first does and counted."""
    plt = pyplot()
    search, criteria = prepared.search, prepared.setup.criteria
    groups = [case for case in search.cases if case != INTACT]
    columns = max(1, min(3, len(groups)))
    rows = math.ceil(max(1, len(groups)) / columns)
    width = max(4.2 * columns, 8.0)
    figure, grid = plt.subplots(rows, columns, figsize=(width, 3.6 * rows + 2.0), squeeze=False, sharey=True,
                                layout="constrained")
    top = TRANSIENT_VIEW * max(criteria.position_limit, criteria.post_failure_position_limit)
    colour_map = plt.get_cmap("twilight")
    for axes, group in zip(grid.flat, groups):
        above = []
        for heading in search.headings:
            number = search.outcome((heading, group), finished).number
            run = shown_run(prepared, (heading, group), number, finished) if number >= 1 else None
            if run is None:
                continue
            points = np.array(run.track)
            time = np.arange(len(points)) * TRACK_PERIOD - criteria.settle
            excursion = np.hypot(points[:, 0], points[:, 1])
            colour = colour_map(heading / 360.0)
            axes.plot(time, excursion, color=colour, linewidth=0.8)
            over = np.flatnonzero(excursion > top)
            if over.size:
                axes.plot(time[over[0]], top, marker="^", color=colour, clip_on=False)
                above.append(f"{heading:g} deg: {np.max(excursion):.3g} m")
        window = criteria.post_failure_window
        axes.hlines(criteria.post_failure_position_limit, 0.0, window, color="tab:purple", linestyle="--",
                    linewidth=1.0)
        axes.hlines(criteria.position_limit, window, criteria.duration, color="tab:red", linewidth=1.0)
        axes.axvline(0.0, color="0.4", linewidth=0.7, linestyle=":")
        if above:
            axes.text(0.98, 0.97, "above the view:\n" + "\n".join(above), transform=axes.transAxes, fontsize=6,
                      ha="right", va="top", bbox=dict(facecolor="white", alpha=0.7, linewidth=0))
        axes.set_ylim(0.0, top)
        axes.set_xlim(-min(criteria.settle, 0.1 * criteria.duration), criteria.duration)
        axes.set_title(f"loss of {group}, at each heading's number", fontsize=9)
        axes.set_xlabel("time since the failure [s]", fontsize=8)
        axes.set_ylabel("position excursion [m]", fontsize=8)
        axes.tick_params(labelsize=7)
    for axes in list(grid.flat)[len(groups):]:
        axes.axis("off")
    if not groups:
        grid[0, 0].text(0.5, 0.5, "no redundancy group", ha="center", transform=grid[0, 0].transAxes)
    mappable = plt.cm.ScalarMappable(cmap=colour_map, norm=plt.Normalize(0.0, 360.0))
    figure.colorbar(mappable, ax=grid, location="right", label="heading [deg]", shrink=0.8)
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color="tab:purple", linestyle="--",
                      label=f"post-failure limit {criteria.post_failure_position_limit:g} m for {window:g} s"),
               Line2D([], [], color="tab:red", label=f"position limit {criteria.position_limit:g} m"),
               Line2D([], [], color="0.3", marker="^", linestyle="none", label="goes above the view here")]
    figure.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=8, frameon=False)
    what = "Position excursion after the group's failure, the seed nearest the quantile, samples every 1 s."
    figure.suptitle(caption(prepared, result, title, what, int(15 * width)), fontsize=8)
    return figure
