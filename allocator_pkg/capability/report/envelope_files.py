"""The capability envelopes of one vehicle as files: ``<vehicle>_capability.png`` (polar for
surge and sway, else in the plane's axes) and ``<vehicle>_capability.csv`` (the same numbers),
for the nominal vehicle and every single-actuator failure."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from ...effectiveness.faults import FaultMode
from ..envelope import FORCE_DOFS, Capability, Envelope
from .plotting import pyplot


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
    plt = pyplot()

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


def write_envelopes(capability: Capability, out: Path, stem: str, suffix: str, title: str, step: float,
                    yaw_moment: float) -> list[Path]:
    """The nominal envelope and every single-actuator failure as <stem><suffix>_capability.png
    and .csv, titled with the vehicle and ``title`` (the methods); their paths."""
    vehicle = capability.vehicle
    cases = {"nominal": capability.envelope(step, yaw_moment)}
    for actuator in vehicle.actuators:
        cases[f"{actuator.name} failed"] = capability.envelope(step, yaw_moment, {actuator.name: FaultMode.FAILED})
    out.mkdir(parents=True, exist_ok=True)
    write_csv(out / f"{stem}{suffix}_capability.csv", capability.plane, cases)
    polar = all(d in ("surge", "sway") for d in capability.plane)
    held = "" if "yaw" in capability.plane or "yaw" not in vehicle.dofs else f", yaw moment {yaw_moment:g} N m held"
    plot(out / f"{stem}{suffix}_capability.png", f"{stem} ({title}{held})", capability.plane, cases, polar)
    return [out / f"{stem}{suffix}_capability.png", out / f"{stem}{suffix}_capability.csv"]
