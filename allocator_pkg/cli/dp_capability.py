"""DP capability Level 1 files: two polar plots, a CSV and the summary (``allocator-capability --dnv-level1``).

:func:`write_level1` reads a vehicle params file and a particulars file, runs
:func:`~allocator_pkg.analysis.dp_capability.level1` and writes, in the output folder,
``<vehicle>_dp_l1_number.png`` (capability number per heading, intact and worst single
failure), ``<vehicle>_dp_l1_wind.png`` (the same in limiting wind speed),
``<vehicle>_dp_l1.csv`` (after a ``#`` comment line saying what is per the standard and what
not, columns ``case``, ``heading_deg``, ``capability_number``, ``wind_speed_limit``) and
``<vehicle>_dp_l1.txt`` (the DP capability-L1(A, B, C, D) line and what the numbers rest on).
Every one of them says what is per DNV-ST-0111 Level 1 and what is not yet, and that it is not
verified by DNV (:data:`~allocator_pkg.analysis.dp_capability.SCOPE`).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from ..analysis.dp_capability import (
    CONDITIONS,
    INTACT,
    NOT_YET,
    SCOPE,
    TOP,
    WORST,
    Level1Result,
    level1,
    load_particulars,
)
from ..configuration.parameters import load_vehicle

CSV_COLUMNS = ("case", "heading_deg", "capability_number", "wind_speed_limit")


def write_level1(vehicle_path: str | Path, particulars_path: str | Path, out: str | Path, step_deg: float = 10.0,
                 method: str | None = None) -> tuple[Level1Result, list[Path]]:
    """Run Level 1 on the two files and write the four outputs; (result, paths written)."""
    vehicle = load_vehicle(vehicle_path)
    particulars = load_particulars(particulars_path)
    result = level1(vehicle, particulars, step_deg, method)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    stem = Path(vehicle_path).stem
    title = particulars.name or stem
    paths = [out / f"{stem}_dp_l1_number.png", out / f"{stem}_dp_l1_wind.png", out / f"{stem}_dp_l1.csv",
             out / f"{stem}_dp_l1.txt"]
    plot(paths[0], result, title, wind=False)
    plot(paths[1], result, title, wind=True)
    write_csv(paths[2], result)
    paths[3].write_text("\n".join([f"{title}: {result.summary_line()}", "", *result.notes]) + "\n")
    return result, paths


def write_csv(path: Path, result: Level1Result) -> None:
    with path.open("w", newline="") as handle:
        handle.write(f"# {SCOPE}\n")
        writer = csv.writer(handle)
        writer.writerow(CSV_COLUMNS)
        for case, heading, number, wind in result.rows():
            writer.writerow([case, f"{heading:g}", number, f"{wind:.2f}"])


def plot(path: Path, result: Level1Result, title: str, wind: bool) -> None:
    """Intact and worst single failure on one polar figure: 0 deg (environment from ahead) at the
    top, clockwise; radius the capability number or the limiting wind speed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    values = result.wind_limits if wind else result.numbers
    figure = plt.figure(figsize=(7.5, 7.5))
    axes = figure.add_subplot(projection="polar")
    angles = np.radians(np.append(result.headings_deg, result.headings_deg[0]))
    for case, style in ((INTACT, dict(color="tab:blue", linewidth=2.4)),
                        (WORST, dict(color="tab:red", linewidth=1.8, linestyle="--"))):
        closed = np.append(values[case], values[case][0])
        axes.plot(angles, closed, label=case, **style)
        axes.fill(angles, closed, alpha=0.12, color=style["color"])
    axes.set_theta_zero_location("N")
    axes.set_theta_direction(-1)
    if wind:
        axes.set_ylim(0.0, CONDITIONS[TOP].wind)
        quantity = "limiting wind speed [m/s]"
    else:
        axes.set_ylim(0, TOP)
        axes.set_yticks(range(TOP + 1))
        quantity = "DP capability number"
    axes.set_title(f"{title}\n{result.summary_line()}: {quantity}\nenvironment from heading (0 = head on)", pad=20)
    axes.legend(loc="upper left", bbox_to_anchor=(0.92, 1.08), fontsize=9)
    figure.tight_layout(rect=(0.0, 0.07, 1.0, 1.0))
    figure.text(0.5, 0.01, "Per DNV-ST-0111 Level 1: loads, thrust, ventilation, [3.11.3] zones.\n"
                f"Not yet: {NOT_YET}.\n"
                "Unclear clauses read as the .txt says. Not verified by DNV.",
                ha="center", va="bottom", fontsize=7, wrap=True)
    figure.savefig(path, dpi=100)
    plt.close(figure)
