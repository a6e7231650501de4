"""allocator-capability: the capability envelope of a vehicle as a plot and a table.

``allocator-capability config.yaml [--out folder]`` writes ``<vehicle>_capability.png`` (the
largest request held per direction in a plane of two controlled DOFs, polar for surge and
sway, for the nominal vehicle and every single-actuator failure) and ``<vehicle>_capability.csv``
(the same numbers); ``--all-methods`` adds ``<vehicle>_<method>_capability.png`` and ``.csv``
for each group of registered methods whose constraints give another capability than the
file's method. The numbers come from :class:`~allocator_pkg.analysis.capability.Capability`.

``allocator-capability --dnv-level1 VESSEL.yaml PARTICULARS.yaml [--out folder]`` writes the
DNV-ST-0111 Level 1 DP capability report of :mod:`.dp_capability` (plots, tables, summary);
``--dnv-level2`` the same at Level 2 with a plot of Level 1 against it; ``--site SITE.yaml`` gives
Level 2 a site environment in place of Table 2-1 (:mod:`~allocator_pkg.analysis.dnv_site`);
``--dnv-level3`` the time-domain Level 3 of :mod:`.dp_level3` (closed-loop runs on a process pool
or a Dask cluster).
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np

from ..allocation.allocator import Allocator
from ..analysis.capability import FORCE_DOFS, Capability, Envelope, differing_methods, reachable
from ..configuration.parameters import load_vehicle
from ..effectiveness.faults import FaultMode
from ..methods import METHODS
from ..vehicle.config import DOF_NAMES
from .dp_capability import write_report
from .dp_level3_report import add_level3_arguments, level3_command


def write_csv(path: Path, plane: tuple[str, str], cases: dict[str, Envelope]) -> None:
    """One row per direction: each case's two components in the plane and its magnitude."""
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        header = ["direction_deg"]
        for case in cases:
            header += [f"{case}.{plane[0]}", f"{case}.{plane[1]}", f"{case}.magnitude"]
        writer.writerow(header)
        first = next(iter(cases.values()))
        for k, direction in enumerate(first.directions):
            row = [f"{math.degrees(direction):.1f}"]
            for envelope in cases.values():
                x, y = envelope.points[k]
                row += [f"{x:.6g}", f"{y:.6g}", f"{envelope.magnitude[k]:.6g}"]
            writer.writerow(row)


def plot(path: Path, title: str, plane: tuple[str, str], cases: dict[str, Envelope], polar: bool) -> None:
    """The envelopes as a PNG: polar (surge ahead, sway to starboard) or in the plane's axes."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure = plt.figure(figsize=(8.5, 7.5))
    axes = figure.add_subplot(projection="polar" if polar else None)
    for name, envelope in cases.items():
        style = dict(linewidth=2.4, color="black") if name == "nominal" else dict(linewidth=1.2)
        if polar:
            closed = np.append(envelope.directions, envelope.directions[0])
            axes.plot(closed, np.append(envelope.magnitude, envelope.magnitude[0]) / 1e3, label=name, **style)
        else:
            points = np.vstack([envelope.points, envelope.points[:1]])
            axes.plot(points[:, 0], points[:, 1], label=name, **style)
    if polar:
        axes.set_theta_zero_location("N")           # surge ahead, sway to starboard (clockwise)
        axes.set_theta_direction(-1)
        axes.set_title(f"{title}\nlargest {plane[0]}/{plane[1]} force [kN] held per direction", pad=18)
    else:
        axes.set_xlabel(f"{plane[0]} [{_unit(plane[0])}]")
        axes.set_ylabel(f"{plane[1]} [{_unit(plane[1])}]")
        axes.grid(True)
        axes.set_title(f"{title}\nlargest request held per direction ({plane[0]}, {plane[1]})")
    axes.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def _unit(dof: str) -> str:
    return "N" if dof in FORCE_DOFS else "N m"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="allocator-capability", description=__doc__.split("\n\n")[0])
    parser.add_argument("config", nargs="?", help="vehicle params file")
    parser.add_argument("--out", default=".", help="folder for <vehicle>_capability.png and .csv")
    parser.add_argument("--step", type=float, default=5.0, help="degrees between directions (default %(default)s)")
    parser.add_argument("--yaw-moment", type=float, default=0.0, help="yaw moment held [N m] (default 0)")
    parser.add_argument("--speed", type=float, default=2.0, help="surge speed for control surfaces [m/s]")
    parser.add_argument("--method", choices=list(METHODS), help="default: the file's")
    parser.add_argument("--plane", nargs=2, metavar=("X", "Y"), choices=DOF_NAMES,
                        help="the two DOFs of the plot (default: surge sway, else the first two controlled)")
    parser.add_argument("--all-methods", action="store_true",
                        help="also <vehicle>_<method>_capability.png and .csv for each group of registered methods "
                             "whose constraints give another capability than the file's method")
    parser.add_argument("--dnv-level1", nargs=2, metavar=("VESSEL", "PARTICULARS"),
                        help="DNV-ST-0111 Level 1 DP capability report of a vehicle params file and a particulars "
                             "file (config/particulars/): <vehicle>_dp_l1_report.md, plots, tables")
    parser.add_argument("--dnv-level2", nargs=2, metavar=("VESSEL", "PARTICULARS"),
                        help="the same at Level 2 with the vessel's own data (<vehicle>_dp_l2...), and a plot of "
                             "Level 1 against Level 2")
    parser.add_argument("--site", metavar="SITE",
                        help="with --dnv-level2 or --dnv-level3: a site environment file (wind, hs, tp or tz, "
                             "current over the capability numbers) in place of Table 2-1 and of the particulars' "
                             "level2.site")
    parser.add_argument("--heading-step", "--headings", type=float, default=10.0,
                        help="degrees between headings for --dnv-level1/2/3 (default %(default)s)")
    add_level3_arguments(parser)
    arguments = parser.parse_args(argv)
    if arguments.site and not (arguments.dnv_level2 or arguments.dnv_level3):
        parser.error("--site goes with --dnv-level2 or --dnv-level3")
    if arguments.dnv_level3:
        return level3_command(parser, arguments)
    if arguments.dnv_level1 or arguments.dnv_level2:
        return _dnv(arguments)
    if arguments.config is None:
        parser.error("a vehicle params file, or --dnv-level1/--dnv-level2 VESSEL PARTICULARS")
    vehicle = load_vehicle(arguments.config)
    plane = tuple(arguments.plane) if arguments.plane else None
    try:
        capability = Capability(vehicle, arguments.method, arguments.speed, plane)
    except ValueError as error:
        print(f"allocator-capability: {error}", file=sys.stderr)
        return 2
    for warning in Allocator(reachable(vehicle), method=capability.method).warnings:
        print(f"allocator-capability: warning: {warning}", file=sys.stderr)
    stem = Path(arguments.config).stem
    _write(capability, Path(arguments.out), stem, "", capability.method, arguments.step, arguments.yaw_moment)
    if arguments.all_methods:
        for names in differing_methods(vehicle, capability.method):
            other = Capability(vehicle, names[0], arguments.speed, plane)
            _write(other, Path(arguments.out), stem, f"_{names[0]}", ", ".join(names), arguments.step,
                   arguments.yaw_moment)
    return 0


def _write(capability: Capability, out: Path, stem: str, suffix: str, title: str, step: float,
           yaw_moment: float) -> None:
    """The nominal envelope and every single-actuator failure as <stem><suffix>_capability.png
    and .csv, titled with the vehicle and ``title`` (the methods)."""
    vehicle = capability.vehicle
    cases = {"nominal": capability.envelope(step, yaw_moment)}
    for actuator in vehicle.actuators:
        cases[f"{actuator.name} failed"] = capability.envelope(step, yaw_moment, {actuator.name: FaultMode.FAILED})
    out.mkdir(parents=True, exist_ok=True)
    write_csv(out / f"{stem}{suffix}_capability.csv", capability.plane, cases)
    polar = all(d in ("surge", "sway") for d in capability.plane)
    held = "" if "yaw" in capability.plane or "yaw" not in vehicle.dofs else f", yaw moment {yaw_moment:g} N m held"
    plot(out / f"{stem}{suffix}_capability.png", f"{stem} ({title}{held})", capability.plane, cases, polar)
    print(out / f"{stem}{suffix}_capability.png")
    print(out / f"{stem}{suffix}_capability.csv")


def _dnv(arguments: argparse.Namespace) -> int:
    """--dnv-level1/2: the report of cli/dp_capability.py, the summary and scope lines on stdout."""
    level = 1 if arguments.dnv_level1 else 2
    vessel, particulars = arguments.dnv_level1 or arguments.dnv_level2
    try:
        result, paths = write_report(vessel, particulars, arguments.out, arguments.heading_step, arguments.method,
                                     level, arguments.site)
    except ValueError as error:                 # a ConfigError too
        print(f"allocator-capability: {error}", file=sys.stderr)
        return 2
    print(result.summary_line())
    print(result.scope)
    for path in paths:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
