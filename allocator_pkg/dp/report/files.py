"""DP capability report (``allocator-capability --dnv-level1`` / ``--dnv-level2``): plots, tables,
summary.

:func:`write_report` writes a complete
:class:`~allocator_pkg.dp.capability_result.CapabilityResult` of
:class:`~allocator_pkg.dp.level1.Level1` (or :class:`~allocator_pkg.dp.level2.Level2`) on the
:class:`~allocator_pkg.dp.vessel_files.VesselFiles` it was computed from; it solves no balance and
reads no file. In the output folder, files named ``<vehicle>_dp_l1...`` (``_dp_l2...``):

- ``_number.png`` / ``_wind.png``: intact and worst single failure (Figure A-1), capability number
  and limiting wind speed [m/s], a marker per heading in the colour of the worst group;
- ``_groups_number.png`` / ``_groups_wind.png``: every redundancy group's loss on one (Figure A-2);
- ``_<group>_number.png`` / ``_<group>_wind.png``: one per group (its failed thrusters crossed);
- ``.csv``: ``case``, ``heading_deg``, ``capability_number``, ``wind_speed_limit`` after a ``#``
  line with the scope;
- ``_table_a1.csv`` to ``_table_a10.csv`` (Tables A-2 to A-5 the inputs; A-9 and A-10 the power
  per thruster and per switchboard), ``_table_a6_losses.csv`` (the [3.11.4]/[3.11.5] loss
  sectors beside Table A-6), ``_loads.csv`` (:mod:`.summary`);
- ``.txt``: the DP capability-L1(A, B, C, D) line and what the numbers rest on;
- ``_report.md``: the one-page summary;
- at Level 2, ``_vs_l1_number.png`` / ``_vs_l1_wind.png``: the result's Level 1
  (:attr:`~allocator_pkg.dp.capability_result.CapabilityResult.lower`) and Level 2 on one.

Every one says what is per DNV-ST-0111 and what is not yet, and that it is not verified by DNV
(:data:`~allocator_pkg.dp.capability_result.SCOPES`).
"""

from __future__ import annotations

import csv
from pathlib import Path

from ..capability_result import INTACT, WORST, CapabilityResult
from ..level1 import Level1
from ..vessel_files import VesselFiles
from .capability_plots import Outline, comparison_plot, polar_plot
from .summary import appendix_tables, write_summary, write_tables
from .tables import groups_of

CSV_COLUMNS = ("case", "heading_deg", "capability_number", "wind_speed_limit")


def write_report(out: str | Path, files: VesselFiles, analysis: Level1, result: CapabilityResult) -> list[Path]:
    """Every output of a Level 1 or 2 result into ``out``; the paths written."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    stem = f"{files.vehicle_path.stem}_dp_l{result.level}"
    title = analysis.particulars.name or files.vehicle_path.stem
    paths = write_plots(out, stem, title, analysis, result)
    paths.append(out / f"{stem}.csv")
    write_csv(paths[-1], result)
    tables = appendix_tables(analysis, result)
    paths += write_tables(out, stem, result.scope, tables)
    paths.append(out / f"{stem}.txt")
    paths[-1].write_text("\n".join([f"{title}: {result.summary_line()}", "", *result.notes]) + "\n")
    paths.append(out / f"{stem}_report.md")
    write_summary(paths[-1], analysis, result, files, paths[:-1], tables)
    return paths


def write_plots(out: Path, stem: str, title: str, analysis: Level1, result: CapabilityResult) -> list[Path]:
    """The polar plots (Figures A-1 and A-2, one per group) and, with a lower level in the result,
    the plots of it against this one; the paths written."""
    outline = Outline.of(analysis)
    paths = []
    figures = [("", "intact and worst single failure", [INTACT, WORST], (), True),
               ("_groups", "loss of each redundancy group", groups_of(result), (), False)]
    figures += [(f"_{group}", f"loss of {group} (failed: x)", [group], tuple(analysis.groups[group]), False)
                for group in groups_of(result)]
    for suffix, caption, cases, failed, mark in figures:
        for wind, quantity in ((False, "number"), (True, "wind")):
            path = out / f"{stem}{suffix}_{quantity}.png"
            polar_plot(path, result, title, caption, wind, cases, outline, failed, mark)
            paths.append(path)
    for lower in result.lower:
        for wind, quantity in ((False, "number"), (True, "wind")):
            paths.append(out / f"{stem}_vs_l{lower.level}_{quantity}.png")
            comparison_plot(paths[-1], lower, result, title, wind, outline)
    return paths


def write_csv(path: Path, result: CapabilityResult) -> None:
    """The numbers and limiting wind speeds per case and heading after a ``#`` line with the scope."""
    with path.open("w", newline="") as handle:
        handle.write(f"# {result.scope}\n")
        writer = csv.writer(handle)
        writer.writerow(CSV_COLUMNS)
        for case, heading, number, wind in result.rows():
            writer.writerow([case, f"{heading:g}", number, f"{wind:.2f}"])
