"""DP capability report (``allocator-capability --dnv-level1`` / ``--dnv-level2``): plots, tables,
summary.

:func:`write_report` reads a vehicle params file and a particulars file, runs
:class:`~allocator_pkg.dp.level1.Level1` (or
:class:`~allocator_pkg.dp.level2.Level2`) and writes, in the output folder, files named
``<vehicle>_dp_l1...`` (``_dp_l2...``):

- ``_number.png`` / ``_wind.png``: intact and worst single failure (Figure A-1), capability number
  and limiting wind speed [m/s], a marker per heading in the colour of the worst group;
- ``_groups_number.png`` / ``_groups_wind.png``: every redundancy group's loss on one (Figure A-2);
- ``_<group>_number.png`` / ``_<group>_wind.png``: one per group (its failed thrusters crossed);
- ``.csv``: ``case``, ``heading_deg``, ``capability_number``, ``wind_speed_limit`` after a ``#``
  line with the scope;
- ``_table_a1.csv`` to ``_table_a10.csv`` (Tables A-2 to A-5 the inputs; A-9 and A-10 the power
  per thruster and per switchboard), ``_table_a6_losses.csv`` (the [3.11.4]/[3.11.5] loss
  sectors beside Table A-6), ``_loads.csv`` (:mod:`.dp_report`);
- ``.txt``: the DP capability-L1(A, B, C, D) line and what the numbers rest on;
- ``_report.md``: the one-page summary;
- at Level 2, ``_vs_l1_number.png`` / ``_vs_l1_wind.png``: Level 1 and Level 2 on one.

Every one says what is per DNV-ST-0111 and what is not yet, and that it is not verified by DNV
(:data:`~allocator_pkg.dp.level1.SCOPE`, :data:`~allocator_pkg.dp.level2.SCOPE_L2`).
"""

from __future__ import annotations

import csv
from pathlib import Path

from ...configuration.parameters import load_vehicle
from ..inputs.particulars import load_particulars
from ..inputs.site import load_site
from ..level1 import INTACT, WORST, Level1, Level1Result
from ..level2 import Level2
from .capability_plots import Outline, comparison_plot, polar_plot
from .summary import write_summary, write_tables
from .tables import balances, groups_of

CSV_COLUMNS = ("case", "heading_deg", "capability_number", "wind_speed_limit")


def write_level1(vehicle_path: str | Path, particulars_path: str | Path, out: str | Path, step_deg: float = 10.0,
                 method: str | None = None) -> tuple[Level1Result, list[Path]]:
    """Run Level 1 on the two files and write the report; (result, paths written)."""
    return write_report(vehicle_path, particulars_path, out, step_deg, method, level=1)


def write_report(vehicle_path: str | Path, particulars_path: str | Path, out: str | Path, step_deg: float = 10.0,
                 method: str | None = None, level: int = 1,
                 site_path: str | Path | None = None) -> tuple[Level1Result, list[Path]]:
    """Run Level 1 or 2 on the two files (Level 2: with the site environment file ``site_path``
    if given) and write the report; (result, paths written)."""
    vehicle_path, particulars_path = Path(vehicle_path), Path(particulars_path)
    vehicle, particulars = load_vehicle(vehicle_path), load_particulars(particulars_path)
    if level == 1:
        analysis = Level1(vehicle, particulars, method)
    else:
        analysis = Level2(vehicle, particulars, method, load_site(site_path) if site_path else None)
    result = analysis.run(step_deg)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    stem = f"{vehicle_path.stem}_dp_l{level}"
    title = analysis.particulars.name or vehicle_path.stem
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
    if level == 2:
        level1_result = Level1(vehicle, particulars, method).run(step_deg)
        for wind, quantity in ((False, "number"), (True, "wind")):
            paths.append(out / f"{stem}_vs_l1_{quantity}.png")
            comparison_plot(paths[-1], level1_result, result, title, wind, outline)
    paths.append(out / f"{stem}.csv")
    write_csv(paths[-1], result)
    balanced = balances(analysis, result)
    paths += write_tables(out, stem, analysis, result, balanced)
    paths.append(out / f"{stem}.txt")
    paths[-1].write_text("\n".join([f"{title}: {result.summary_line()}", "", *result.notes]) + "\n")
    paths.append(out / f"{stem}_report.md")
    write_summary(paths[-1], analysis, result, vehicle_path, particulars_path, paths[:-1], balanced)
    return result, paths


def write_csv(path: Path, result: Level1Result) -> None:
    with path.open("w", newline="") as handle:
        handle.write(f"# {result.scope}\n")
        writer = csv.writer(handle)
        writer.writerow(CSV_COLUMNS)
        for case, heading, number, wind in result.rows():
            writer.writerow([case, f"{heading:g}", number, f"{wind:.2f}"])
