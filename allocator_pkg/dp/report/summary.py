"""The tables and the one-page summary of a DNV-ST-0111 Level 1 report (App. A.3).

:func:`appendix_tables` gives every table of a complete result once: those of
:mod:`allocator_pkg.dp.report.input_tables` (A-2 to A-5), :mod:`allocator_pkg.dp.report.tables`
(A-1, A-6 and its loss sectors, A-7, A-8) and :mod:`allocator_pkg.dp.report.power_tables` (A-9,
A-10); :func:`write_tables` writes them as CSV, each after two ``#`` lines (what the table is, with
its units; the scope); :func:`write_summary` the Markdown summary from the same tables: the vessel,
the inputs and where they come from, Tables A-2 to A-5, the DP capability-L1 notation, the tables'
headlines (the power per switchboard too), the scope and "Not verified by DNV"."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from ..capability_result import INTACT, WORST, CapabilityResult
from ..level1 import Level1
from ..vessel_files import VesselFiles
from .input_tables import (
    A2_COLUMNS,
    A3_COLUMNS,
    A4_COLUMNS,
    a5_columns,
    table_a2,
    table_a3,
    table_a4,
    table_a5,
)
from .power_tables import A10_COLUMNS, a9_columns, table_a9, table_a10
from .tables import (
    A6_COLUMNS,
    A7_COLUMNS,
    A8_COLUMNS,
    LOAD_COLUMNS,
    LOSS_COLUMNS,
    groups_of,
    load_table,
    loss_sector_table,
    table_a1,
    table_a6,
    table_a7,
    table_a8,
    worst_groups,
)

TABLES = {
    "table_a2": "Table A-2: hull data; x [m] forward of Lpp/2 (the frame of [2.8.2]); from the particulars file",
    "table_a3": "Table A-3: actuator data; position [3.8.3] in the frame of [2.8.2] (x [m] forward of Lpp/2, y [m] "
                "to port, z [m] above the keel) from the vehicle file; type, D [m], P_B [kW], pitch, duct, "
                "contra-rotation, permanent magnet, tunnel inlet from the particulars file; nominal thrust [3.9.2] "
                "forward and reversed [kN] (0: the vehicle file does not reverse it)",
    "table_a4": "Table A-4: rudder data [3.10] per rudder behind a shaft line (the particulars' rudders): its "
                "propeller, profile (Table 3-5), A_r [m^2], k1 (Table 3-5), k2 (Table 3-6), the largest rudder angle "
                "[3.10.1] uses [deg] (the vehicle file's, at most 30) and the side force there at the propeller's "
                "forward T_nominal [3.9.2], T_nominal C_Y alpha [kN]",
    "table_a5": "Table A-5: thruster power configuration from the vehicle file: per thruster its P_B [kW] and, per "
                "switchboard or prime mover, its share [%] and the power it can consume from there [kW]; then "
                "each source's available power [kW] and its usable power after the 10 % reserve [3.12.3] [kW]",
    "table_a1": "Table A-1: capability number per heading (deg, environment from; 0 ahead, 90 from starboard) "
                "intact, after the loss of each redundancy group, combined (the lowest over the groups) and "
                "the group whose loss is worst there",
    "table_a6": "Table A-6: forbidden zones in force per case ([3.11.3] at Level 1, the vehicle file's sectors at "
                "Level 2); thrust angles [deg] in the body frame (0 forward, 90 to starboard), the thruster whose "
                "race the zone protects",
    "table_a6_losses": "Beside Table A-6 (whose layout has forbidden zones only): the sectors of reduced thrust per "
                       "case, flushing a dead thruster [3.11.4] and a skeg [3.11.5] combined [3.11.6] (at Level 2 the "
                       "vessel's own tables over the thrust direction, level2.thrust_loss); thrust "
                       "angles [deg] in the body frame (0 forward, 90 to starboard) from and to the directions at "
                       "full thrust, the lowest factor and its angle; the factor linear between the corners of "
                       "[3.11.4]/[3.11.5] or of the table's chords",
    "table_a7": "Table A-7: per case and heading the capability number, the limiting wind speed [m/s] and the "
                "unfactored wind, current and wave loads of the number's Table 2-1 condition in the frame of "
                "[2.8.2] (x forward, y to port; Fx, Fy [kN]; Mz [kN m] about Lpp/2, bow to port positive)",
    "table_a8": "Table A-8: per case, heading and working thruster at the heading's number: thrust [kN] "
                "(signed for a fixed thruster), its angle [deg, body frame], the effective thrust available "
                "that way [kN] and the utilisation [%]; one allocation that holds the load, whose largest "
                "utilisation is the least possible",
    "table_a9": "Table A-9 (its columns as read here: the transcription names the content, not the columns): per "
                "case, heading and working thruster at the heading's number, in Table A-8's allocation: the thrust "
                "fraction r (of what it can give that way), the power it draws, s P_B r^(3/2) [kW] ([3.9.2] turned "
                "around; s its working feed shares), and per switchboard or prime mover what it draws from there [kW]",
    "table_a10": "Table A-10 (its columns as read here): per case, heading and working switchboard or prime mover at "
                 "the heading's number, in Table A-8's allocation: available power, the 10 % reserved [3.12.3], the "
                 "usable rest, what its thrusters draw [kW] and that as a share of the usable power [%]",
    "loads": "Loads per source for every heading and number 1-11 (condition: wind [m/s], Hs [m], Tp [s], "
             "current [m/s]), unfactored, and their sum times 1.25; frame of [2.8.2], Fx, Fy [kN], Mz [kN m]",
}


def _cell(value) -> str:
    if isinstance(value, float):
        return f"{value:.6g}" if abs(value) < 1e6 else f"{value:.1f}"
    return str(value)


def write_table(path: Path, what: str, scope: str, columns, rows) -> None:
    with path.open("w", newline="") as handle:
        handle.write(f"# {what}\n# {scope}\n")
        writer = csv.writer(handle)
        writer.writerow(columns)
        writer.writerows([_cell(v) for v in row] for row in rows)


Table = tuple[tuple[str, ...], list[tuple]]
"""(columns, rows) of one table."""


def appendix_tables(analysis: Level1, result: CapabilityResult) -> dict[str, Table]:
    """Every CSV table of a Level 1 or 2 report by key (:data:`TABLES`), in the order written:
    Tables A-2 to A-5, A-1, A-6 and its loss sectors, A-7 to A-10, the loads."""
    return {**input_tables(analysis),
            "table_a1": table_a1(result), "table_a6": (A6_COLUMNS, table_a6(analysis)),
            "table_a6_losses": (LOSS_COLUMNS, loss_sector_table(analysis)),
            "table_a7": (A7_COLUMNS, table_a7(analysis, result)),
            "table_a8": (A8_COLUMNS, table_a8(result)),
            "table_a9": (a9_columns(analysis), table_a9(analysis, result)),
            "table_a10": (A10_COLUMNS, table_a10(analysis, result)),
            "loads": (LOAD_COLUMNS, load_table(analysis, result))}


def write_tables(out: Path, stem: str, scope: str, tables: dict[str, Table]) -> list[Path]:
    """Each table as ``<stem>_<key>.csv`` after its two ``#`` lines; the paths written."""
    paths = []
    for key, (columns, rows) in tables.items():
        path = out / f"{stem}_{key}.csv"
        write_table(path, TABLES[key], scope, columns, rows)
        paths.append(path)
    return paths


INPUT_TABLES = ("table_a2", "table_a3", "table_a4", "table_a5")


def input_tables(analysis: Level1) -> dict[str, Table]:
    """(columns, rows) of Tables A-2 to A-5 by key."""
    return {"table_a2": (A2_COLUMNS, table_a2(analysis)), "table_a3": (A3_COLUMNS, table_a3(analysis)),
            "table_a4": (A4_COLUMNS, table_a4(analysis)), "table_a5": (a5_columns(analysis), table_a5(analysis))}


def markdown_table(columns, rows) -> list[str]:
    """A Markdown table of the CSV cells."""
    return [f"| {' | '.join(columns)} |", "|" + "---|" * len(columns),
            *(f"| {' | '.join(_cell(value) for value in row)} |" for row in rows)]


def _headings(result: CapabilityResult, case: str, value: int) -> str:
    where = result.headings_deg[result.numbers[case] == value]
    return ", ".join(f"{h:g}" for h in where)


def write_summary(path: Path, analysis: Level1, result: CapabilityResult, files: VesselFiles, written: list[Path],
                  tables: dict[str, Table]) -> None:
    """The one-page Markdown summary of the result, its input files, the files ``written`` and the
    ``tables`` of :func:`appendix_tables`."""
    vehicle_path, particulars_path = files.vehicle_path, files.particulars_path
    title = analysis.particulars.name or vehicle_path.stem
    a, b, c, d = result.summary()
    groups = groups_of(result)
    lines = [
        f"# DP capability Level {result.level}: {title}",
        "",
        f"**{result.summary_line()}** per DNV-ST-0111 (edition December 2021) Level {result.level}"
        + (" as read here (the transcription used has no Level 2 text)" if result.level == 2 else "")
        + ". **Not verified by DNV.**",
        "",
        f"- A = {a}: intact, lowest within +-30 deg of the bow; B = {b}: intact, lowest over 360 deg "
        f"(at {_headings(result, INTACT, b)} deg).",
        f"- C = {c}, D = {d}: the same for the worst single failure (D at {_headings(result, WORST, d)} deg).",
        "",
        "## Inputs",
        "",
        f"- Vehicle file `{vehicle_path}`: each thruster's position, type, direction and azimuth range; the power "
        "sources, feeds (Table A-5) and redundancy groups.",
        f"- Particulars file `{particulars_path}`: the hull (Table A-2) and each thruster's Table A-3 row.",
        *_power_lines(analysis),
        "- Redundancy groups (lost together): " + "; ".join(f"{g}: {', '.join(analysis.groups[g])}"
                                                             for g in groups) + ".",
        "",
    ]
    if files.stated:
        lines += ["| input | value | unit, source (as the particulars file states) |", "|---|---|---|",
                  *(f"| `{key}` | {value} | {comment} |" for key, value, comment in files.stated), ""]
    for key in INPUT_TABLES:
        columns, rows = tables[key]
        title, what = TABLES[key].split(": ", 1)
        lines += [f"## {title}", "", what[0].upper() + what[1:] + ".", "",
                  *(markdown_table(columns, rows) if rows else ["(none)"]), ""]
    lines += [f"## Results (headings every {_step(result):g} deg, environment from)", "",
              "| case | lowest number | at heading [deg] | lowest limiting wind [m/s] |", "|---|---|---|---|"]
    for case in (INTACT, *groups, WORST):
        low = int(np.min(result.numbers[case]))
        label = case if case in (INTACT, WORST) else f"loss of {case}"
        lines.append(f"| {label} | {low} | {_headings(result, case, low)} | "
                     f"{float(np.min(result.wind_limits[case])):.1f} |")
    worst = worst_groups(result)
    counts = ", ".join(f"{g} at {worst.count(g)}" for g in groups)
    lines += ["", f"Worst single failure per heading (Table A-1): {counts} of {len(worst)} headings.", "",
              *_power_headline(analysis, tables["table_a10"][1])]
    lines += ["## Files", "", *(f"- `{p.name}`" for p in written), "",
              "## Scope", "", *(f"- {note}" for note in result.notes), ""]
    path.write_text("\n".join(lines))


def _power_headline(analysis: Level1, a10_rows: list[tuple]) -> list[str]:
    """Per case and source the highest share of its usable power its thrusters draw at a heading's
    number (the rows of Table A-10)."""
    if not analysis.capacities:
        return []
    highest: dict[tuple[str, str], tuple[float, float]] = {}
    for case, heading, _, source, *_, share in a10_rows:
        if (case, source) not in highest or share > highest[case, source][0]:
            highest[case, source] = (share, heading)
    return ["## Power per switchboard (Tables A-9, A-10)", "",
            "Highest share of the usable power (after the 10 % reserve) the thrusters draw at a heading's number, "
            "in Table A-8's allocation:", "", "| case | source | highest [%] | at heading [deg] |", "|---|---|---|---|",
            *(f"| {case} | {source} | {share:.1f} | {heading:g} |"
              for (case, source), (share, heading) in highest.items()), ""]


def _power_lines(analysis: Level1) -> list[str]:
    vehicle = analysis.vehicle
    if not vehicle.power_sources:
        return ["- Power sources: none given (each group loses its actuators only)."]
    feeds = "; ".join(f"{a.name} " + ", ".join(f"{f} {100.0 * s:g} %" for f, s in zip(a.feeds, a.feed_shares))
                      for a in vehicle.actuators if a.feeds)
    return ["- Power sources: " + ", ".join(f"{s.name} {s.capacity:g} kW" for s in vehicle.power_sources)
            + f"; feeds: {feeds}."]


def _step(result: CapabilityResult) -> float:
    headings = result.headings_deg
    return float(headings[1] - headings[0]) if len(headings) > 1 else 360.0

