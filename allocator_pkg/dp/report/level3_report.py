"""The outputs of a DNV-ST-0111 Level 3 study (``allocator-capability --dnv-level3``), named
``<vehicle>_dp_l3...`` in the output folder:

- ``_number.png`` / ``_wind.png``: intact and worst single failure; ``_groups_number.png`` /
  ``_groups_wind.png``: each group's loss (the Level 1 plots, :mod:`.capability_plots`);
- ``_vs_l1_l2_number.png`` / ``_vs_l1_l2_wind.png``: Level 1, 2 and 3 of the vessel on one (Level 1
  and 2 as published, at the standard's 10 deg headings, whatever the study's step: the result's
  :attr:`~allocator_pkg.dp.capability_result.CapabilityResult.lower`);
- ``_footprints.png``, ``_quantiles.png``, ``_transients.png`` (:mod:`.level3_plots`);
- ``.csv``, ``_table_a1.csv`` and Tables A-2 to A-5 (:mod:`.summary`) as at Level 1;
  ``_limits.csv``, ``_cases.csv``, ``_quantiles.csv`` (:mod:`.level3_tables`); ``_screening.csv``
  when a screening estimate is given;
- ``.txt``: the DP capability-L3(A, B, C, D) line, the scope, the criteria by key, the assumptions,
  the notes and the Level 1 and 2 lines of the comparison plots;
- ``_report.md``: the summary, the criteria, the assumptions, the quantiles per heading and case,
  the screening estimate (when given) and the plots.

Every one states the criteria and that the result is not verified by DNV.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...capability.report.plotting import pyplot
from ..capability_result import INTACT, WORST, CapabilityResult
from ..level1 import MAX_STEP_DEG
from ..level3.case import CRITERIA_KEYS, CaseResult
from ..level3.statistics import condition_spreads
from ..level3.study import Level3Study
from .capability_plots import Outline, polar_figure, polar_plot
from .level3_plots import footprints_figure, quantiles_figure, save, transients_figure
from .level3_tables import (
    CASE_COLUMNS,
    CASES_TABLE,
    LIMIT_COLUMNS,
    LIMITS_TABLE,
    QUANTILE_COLUMNS,
    QUANTILES_TABLE,
    case_rows,
    limit_rows,
    quantile_rows,
)
from .summary import TABLES, input_tables, write_table
from .tables import groups_of, table_a1

ASSUMPTIONS = (
    "The public transcription of DNV-ST-0111 used here has no Level 3 text: the acceptance criteria (position "
    "and heading limits, the post-failure limits and their window), the time on station before a failure, the "
    "simulated duration, the number of seeds and the quantile that decides a condition are this package's "
    "defaults or the criteria file's, not the standard's.",
    "The mean wind load and wave drift are the standard's [3.5] and [3.7]; the gust spectrum (NPD unless the "
    "base scenario names another), Newman's slowly varying drift with one drift coefficient, the first-order "
    "wave motion's response model and the current's slow variation are this package's choices, the current load "
    "the simulation's hull model's; wind, current and waves come from one heading unless the site gives the "
    "waves' and the current's directions relative to the wind (the notes say which).",
    "The DP system (observer tuning, measurement noise, feed-forward filter) and the controller's gains are this "
    "package's (the notes state them), not the vessel's own.",
    "A redundancy group fails at once, all its actuators and power sources, at the end of the time on station; "
    "an intact case has no post-failure window.",
    "The limiting wind speed is the wind of the number's condition (no bisection in the time domain).",
    "The confidence interval is a percentile bootstrap over the seeds: with few seeds it is wide and it "
    "understates the uncertainty of a high quantile.",
    "Not verified by DNV.",
)
"""What the Level 3 outputs assume where the standard's Level 3 text was not available."""
STATS_COLUMNS = ("case", "heading [deg]", "number", "limited by", "quantile at the number [m] (CI; min, median, "
                 "max)", "quantile at the next condition [m] (CI; min, median, max)")


@dataclass(frozen=True)
class Screening:
    """A screening estimate to show beside the time-domain result (the frequency-domain estimate
    of the environment's effect): a title, its columns and rows."""

    title: str
    columns: tuple[str, ...]
    rows: list[tuple]


def write_level3(prepared: Level3Study, result: CapabilityResult, finished: dict[tuple, CaseResult],
                 out: Path, screening: Screening | None = None) -> list[Path]:
    """Every output of the study into ``out`` (with ``screening``: its table and section); the
    paths written."""
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
    for wind, quantity in ((False, "number"), (True, "wind")):
        paths.append(out / f"{stem}_vs_l1_l2_{quantity}.png")
        levels_plot(paths[-1], (*result.lower, result), title, wind, outline, criteria)
    for name, figure in (("footprints", footprints_figure), ("quantiles", quantiles_figure),
                         ("transients", transients_figure)):
        paths.append(out / f"{stem}_{name}.png")
        save(figure(prepared, result, finished, title), paths[-1])
    scope = f"{result.scope} Criteria: {prepared.setup.criteria.describe()}."
    a1_columns, a1_rows = table_a1(result)
    tables = {**input_tables(prepared.analysis), "table_a1": (a1_columns, a1_rows)}
    for key, (columns, rows) in tables.items():
        paths.append(out / f"{stem}_{key}.csv")
        write_table(paths[-1], TABLES[key], scope, columns, rows)
    for suffix, what, columns, rows in (
            ("", "Level 3 capability number and limiting wind speed [m/s] per case and heading",
             ("case", "heading_deg", "capability_number", "wind_speed_limit"), result.rows()),
            ("_limits", LIMITS_TABLE, LIMIT_COLUMNS, limit_rows(prepared, finished)),
            ("_cases", CASES_TABLE, CASE_COLUMNS, case_rows(prepared, finished)),
            ("_quantiles", QUANTILES_TABLE, QUANTILE_COLUMNS, quantile_rows(prepared, finished))):
        paths.append(out / f"{stem}{suffix}.csv")
        write_table(paths[-1], what, scope, columns, rows)
    if screening is not None:
        paths.append(out / f"{stem}_screening.csv")
        write_table(paths[-1], screening.title, scope, screening.columns, screening.rows)
    paths.append(out / f"{stem}.txt")
    paths[-1].write_text("\n".join(text_lines(prepared, result, title)) + "\n")
    paths.append(out / f"{stem}_report.md")
    paths[-1].write_text(markdown(prepared, result, finished, title, paths, screening))
    return paths


def text_lines(prepared: Level3Study, result: CapabilityResult, title: str) -> list[str]:
    """The ``.txt``: summary, scope, criteria by key, assumptions, notes, the comparison's levels."""
    level1, level2 = result.lower
    compared = (f"The comparison plots (_vs_l1_l2) show Level 1 and Level 2 as published (--dnv-level1, "
                f"--dnv-level2), at the standard's {MAX_STEP_DEG:g} deg headings: {level1.summary_line()}, "
                f"{level2.summary_line()}.")
    criteria = [f"  {name}: {value}" for name, value in prepared.setup.criteria.values()]
    assumed = [f"  - {line}" for line in ASSUMPTIONS]
    return [f"{title}: {result.summary_line()}", "", result.scope, "", "Criteria (criteria file keys):", *criteria,
            "", "Assumed where the standard's Level 3 text was not available:", *assumed, "", *result.notes, compared]


def markdown(prepared: Level3Study, result: CapabilityResult, finished: Mapping[tuple, CaseResult], title: str,
             paths: list[Path], screening: Screening | None) -> str:
    """The ``_report.md``: summary, criteria, assumptions, quantiles, screening estimate, plots."""
    texts = {key.name: key.text for key in CRITERIA_KEYS}
    lines = [f"# {title}: {result.summary_line()}", "", f"**Not verified by DNV.** {result.scope}", "",
             "## Criteria", "", "| key | value | meaning |", "|---|---|---|"]
    lines += [f"| `{name}` | {value} | {texts[name]} |" for name, value in prepared.setup.criteria.values()]
    lines += ["", "## Assumed where the standard's Level 3 text was not available", ""]
    lines += [f"- {line}" for line in ASSUMPTIONS]
    lines += ["", "## Position excursion per heading and case", "",
              f"The {prepared.setup.criteria.quantile:g} quantile over the seeds of each run's largest position "
              "excursion outside the post-failure window.", "", "| " + " | ".join(STATS_COLUMNS) + " |",
              "|" + "---|" * len(STATS_COLUMNS)]
    lines += ["| " + " | ".join(map(str, row)) + " |" for row in stats_rows(prepared, finished)]
    lines += ["", "## Screening estimate", ""]
    if screening is None:
        lines.append("No screening estimate given.")
    else:
        lines += [screening.title, "", "| " + " | ".join(screening.columns) + " |",
                  "|" + "---|" * len(screening.columns)]
        lines += ["| " + " | ".join(map(str, row)) + " |" for row in screening.rows]
    lines += ["", "## Notes", "", *[f"- {note}" for note in result.notes], "", "## Files", ""]
    lines += [f"![{path.stem}]({path.name})" if path.suffix == ".png" else f"- [{path.name}]({path.name})"
              for path in paths if path.suffix in (".png", ".csv", ".txt")]
    return "\n".join(lines) + "\n"


def stats_rows(prepared: Level3Study, finished: Mapping[tuple, CaseResult]) -> list[tuple]:
    """Per chain: case, heading, number, why it stops, and the position quantile (interval;
    spread) at the number and at the next condition (blank where not simulated)."""
    search, criteria = prepared.search, prepared.setup.criteria
    rows = []
    for heading, case in search.chains():
        outcome = search.outcome((heading, case), finished)
        cells = []
        for number in (outcome.number, outcome.number + 1):
            results = search.seed_results((heading, case), number, finished) if number >= 1 else None
            spread = condition_spreads(results, criteria)["steady_position"] if results else None
            cells.append("" if spread is None else
                         f"{spread.quantile:.3g} ({spread.low:.3g}-{spread.high:.3g}; {spread.minimum:.3g}, "
                         f"{spread.median:.3g}, {spread.maximum:.3g})")
        rows.append((case, f"{heading:g}", outcome.number, outcome.reason, *cells))
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
