"""Azimuth settling sweep: a constant request held from rest, judged over its last samples.

For every vessel with rotatable thrusters (the shipped ones, and the DP vessel without rate
limits or forbidden sectors), the methods whose settling the spec judges (``qp``, ``nonlinear``;
``lp``, ``dynamic`` and ``svd_filter`` are not swept), and
requests in every direction of the surge/sway plane at magnitudes from 0.5 to 1.5 times the
vessel's capability in that direction (an independent LP, Capability with the thrust circle):
hold the request for 400 samples from rest and judge the last 100:

- the azimuths come to rest: peak-to-peak angle change <= 0.1 deg;
- no fallback once settled; fallbacks over the whole sweep as a share of its samples;
- the settled wrench against an independent optimum of the same static problem (the closest
  wrench the actuators can give, SLSQP over every combination of convex pieces,
  ``bench/optimum.py``), per DOF as a fraction of its authority;
- every limit kept in every sample (turning and thrust rates, thrust limits, sectors),
  checked here with arithmetic of its own;
- time per sample (median, p99).

``make bench`` runs the full sweep (``--full``); ``test/allocation/test_settling.py`` a small one;
``--off-grid`` the directions between the full sweep's (every 5 deg from 2.5, at the same
magnitudes; about 20 minutes on one core, ``--vessels`` splits it). The
output names the commit of the ``allocator_pkg`` it ran, so the sweep can measure any checkout:
``PYTHONPATH=<checkout> python bench/settling.py --full --note "..."``.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from optimum import best_attainable_wrench

import allocator_pkg
from allocator_pkg import Allocator, read_parameters, vehicle_from_parameters
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.effectiveness.faults import FaultSet, static_ranges
from allocator_pkg.effectiveness.model import Model

ROOT = Path(__file__).resolve().parents[1]

SAMPLES = 400
JUDGED = 100
SETTLED_DEG = 0.1
METHODS = ("qp", "nonlinear")


def free_dp_vessel():
    """The DP vessel with no turning or thrust rate limits and no forbidden sectors."""
    parameters = read_parameters(ROOT / "config" / "dp_vessel.yaml")
    for name in parameters["actuators.names"]:
        parameters[f"actuators.{name}.thrust_rate_max"] = 0.0
        if parameters[f"actuators.{name}.type"] == "azimuth":
            parameters[f"actuators.{name}.azimuth_rate_max"] = 0.0
            parameters.pop(f"actuators.{name}.forbidden_sectors", None)
            parameters.pop(f"actuators.{name}.protects", None)
    return vehicle_from_parameters(parameters)


VESSELS = {
    "dp_vessel": lambda: vehicle_from_parameters(read_parameters(ROOT / "config" / "dp_vessel.yaml")),
    "example1_rov": lambda: vehicle_from_parameters(read_parameters(ROOT / "config" / "example1_rov.yaml")),
    "dp_vessel, free": free_dp_vessel,
}


@dataclass
class Case:
    """One held request and what became of it."""

    direction_deg: float
    magnitude: float
    angle_spread_deg: float
    fallbacks: int
    late_fallbacks: int
    deviation: float
    violations: list[str] = field(default_factory=list)
    times: list[float] = field(default_factory=list, repr=False)

    @property
    def settled(self) -> bool:
        return self.angle_spread_deg <= SETTLED_DEG and self.late_fallbacks == 0


def _violations(vehicle, dt: float, previous, result) -> list[str]:
    """Every limit a sample breaks, by arithmetic of this module's own."""
    found = []
    for i, actuator in enumerate(vehicle.actuators):
        thrust, angle = float(result.thrust[i]), float(result.azimuth[i])
        if not (actuator.thrust_min - 1e-6 <= thrust <= actuator.thrust_max + 1e-6):
            found.append(f"{actuator.name} thrust {thrust:g}")
        if actuator.thrust_rate_max > 0 and abs(thrust - previous.thrust[i]) > actuator.thrust_rate_max * dt + 1e-6:
            found.append(f"{actuator.name} thrust rate")
        if not actuator.rotatable:
            continue
        rotation = actuator.rotation
        turned = abs(math.remainder(angle - float(previous.azimuth[i]), 2.0 * math.pi))
        if rotation.rate_max > 0 and turned > rotation.rate_max * dt + 1e-9:
            found.append(f"{actuator.name} turned {turned:g} rad")
        for start, end in rotation.forbidden_sectors:
            inside = (angle - start) % (2.0 * math.pi)
            if 1e-9 < inside < (end - start) % (2.0 * math.pi) - 1e-9 and abs(thrust) > 1e-6:
                found.append(f"{actuator.name} pushes at {angle:g} rad, in a forbidden sector")
    return found


def hold(vehicle, method: str, tau: np.ndarray, reference: np.ndarray, samples: int = SAMPLES) -> Case:
    """The request held from rest; the last JUDGED samples judged."""
    allocator = Allocator(vehicle, method=method)
    model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
    rotatable = [i for i, a in enumerate(vehicle.actuators) if a.rotatable]
    previous = allocator.stop()
    angles, times, fallbacks, violations = [], [], [], []
    for _ in range(samples):
        begin = time.perf_counter()
        result = allocator.allocate(tau)
        times.append(time.perf_counter() - begin)
        angles.append(result.azimuth[rotatable])
        fallbacks.append(result.status.startswith("fallback"))
        violations += _violations(vehicle, allocator.dt, previous, result)
        previous = result
    tail = np.unwrap(np.array(angles[-JUDGED:]), axis=0)
    spread = float(np.max(np.ptp(tail, axis=0))) if rotatable else 0.0
    deviation = float(np.max(np.abs(result.achieved[model.dof_index] - reference) / model.dof_scale))
    return Case(direction_deg=0.0, magnitude=0.0, angle_spread_deg=math.degrees(spread),
                fallbacks=int(sum(fallbacks)), late_fallbacks=int(sum(fallbacks[-JUDGED:])), deviation=deviation,
                violations=violations[:5], times=times)


def requests(vehicle, directions_deg, magnitudes) -> list[tuple[float, float, np.ndarray, np.ndarray]]:
    """(direction, magnitude, tau, reference wrench) of every case on one vessel."""
    capability = Capability(vehicle, method="nonlinear")
    model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
    low, high = static_ranges(vehicle, FaultSet(vehicle), 0.0)
    weights = model.slack_weights(model.weight)
    cases = []
    for direction in directions_deg:
        unit = np.zeros(6)
        unit[0], unit[1] = math.cos(math.radians(direction)), math.sin(math.radians(direction))
        scale = capability.scale(unit)
        for magnitude in magnitudes:
            tau = unit * scale * magnitude
            cases.append((direction, magnitude, tau, best_attainable_wrench(vehicle, tau, weights, low, high)))
    return cases


def sweep(vehicle, methods, directions_deg, magnitudes) -> dict[str, list[Case]]:
    """Every method on every case of one vessel."""
    cases = requests(vehicle, directions_deg, magnitudes)
    result = {}
    for method in methods:
        held = []
        for direction, magnitude, tau, reference in cases:
            case = hold(vehicle, method, tau, reference)
            case.direction_deg, case.magnitude = direction, magnitude
            held.append(case)
        result[method] = held
    return result


def summary(cases: list[Case]) -> dict:
    """The figures of one method on one vessel."""
    times = np.concatenate([case.times for case in cases]) * 1e6
    samples = len(times)
    return {
        "cases": len(cases),
        "moving_or_falling_back": sum(not case.settled for case in cases),
        "fallback_share": sum(case.fallbacks for case in cases) / samples,
        "worst_deviation": max(case.deviation for case in cases),
        "largest_spread_deg": max(case.angle_spread_deg for case in cases),
        "violations": sum(len(case.violations) for case in cases),
        "time_us": {"median": float(np.median(times)), "p99": float(np.percentile(times, 99)),
                    "max": float(np.max(times))},
        "unsettled": [(case.direction_deg, case.magnitude, round(case.angle_spread_deg, 3), case.late_fallbacks)
                      for case in cases if not case.settled][:10],
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    grid = parser.add_mutually_exclusive_group()
    grid.add_argument("--full", action="store_true", help="every 15 deg, magnitudes 0.5 to 1.5 by 0.1")
    grid.add_argument("--off-grid", action="store_true",
                      help="every 5 deg from 2.5 (between the full sweep's directions), magnitudes 0.5 to 1.5 by 0.1")
    parser.add_argument("--vessels", nargs="+", choices=list(VESSELS), default=list(VESSELS), metavar="VESSEL",
                        help=f"which of {', '.join(VESSELS)} (default: all)")
    parser.add_argument("--out", type=Path, default=None)
    parser.add_argument("--note", default="", help="what the measured code is (kept in the output)")
    arguments = parser.parse_args(argv)
    if arguments.off_grid:
        directions = np.arange(2.5, 360.0, 5.0)
    else:
        directions = np.arange(0.0, 360.0, 15.0 if arguments.full else 45.0)
    magnitudes = np.round(np.arange(0.5, 1.51, 0.1 if arguments.full or arguments.off_grid else 0.5), 2)
    report = {"samples": SAMPLES, "judged": JUDGED, "directions_deg": directions.tolist(),
              "magnitudes": magnitudes.tolist(), "commit": _commit(), "date": datetime.date.today().isoformat(),
              "note": arguments.note, "vessels": {}}
    for name in arguments.vessels:
        swept = sweep(VESSELS[name](), METHODS, directions, magnitudes)
        report["vessels"][name] = {method: summary(cases) for method, cases in swept.items()}
        print(f"settling: {name} done", file=sys.stderr, flush=True)
    text = json.dumps(report, indent=1)
    if arguments.out:
        arguments.out.write_text(text)
    else:
        print(text)
    return 0


def _commit() -> str:
    """The commit of the allocator_pkg this sweep imported (with "+changes" if its tree differs)."""
    tree = Path(allocator_pkg.__file__).resolve().parents[1]
    def git(*args: str) -> str:
        return subprocess.run(["git", "-C", str(tree), *args], capture_output=True, text=True).stdout.strip()
    commit = git("rev-parse", "--short", "HEAD") or "unknown"
    return commit + ("+changes" if git("status", "--porcelain", "--untracked-files=no", "allocator_pkg") else "")


if __name__ == "__main__":
    sys.exit(main())
