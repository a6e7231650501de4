"""How many actuators work under each method: the lp method's vertex solutions against the
QP's, on every shipped vehicle (the table in docs/theory.md, section lp).

Rate limits are removed (thrust, turning and deflection rates; sectors stay) so that every
method settles on its own optimum; each request of the bench's random sequence that the
vehicle can give (Capability.scale >= 1) is held for ``HOLD`` samples and the last one is
counted: an actuator works when its force exceeds 1 % of its range. Run
``.venv/bin/python bench/sparsity.py`` to print the table.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from allocator_pkg import Allocator, read_parameters, vehicle_from_parameters
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.effectiveness.model import Model

ROOT = Path(__file__).resolve().parents[1]
HOLD = 20
WORKING = 0.01
SPEED = 2.0


def without_rates(path: Path):
    """A shipped vehicle with every rate limit removed."""
    parameters = read_parameters(path)
    for name in parameters["actuators.names"]:
        for key in ("thrust_rate_max", "azimuth_rate_max", "deflection_rate_max"):
            if f"actuators.{name}.{key}" in parameters:
                parameters[f"actuators.{name}.{key}"] = 0.0
    return vehicle_from_parameters(parameters)


def requests(vehicle, count: int, seed: int = 1) -> np.ndarray:
    """Independent requests up to half of each DOF's authority that the vehicle can give."""
    model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
    authority = np.zeros(6)
    authority[model.dof_index] = model.authority
    capability = Capability(vehicle, method="qp", speed=SPEED)
    rng = np.random.default_rng(seed)
    drawn = authority * rng.uniform(-0.5, 0.5, size=(4 * count, 6))
    return np.array([tau for tau in drawn if capability.scale(tau) >= 1.0][:count])


def working(vehicle, method: str, sequence: np.ndarray) -> np.ndarray:
    """Actuators working at the end of each held request."""
    model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
    allocator = Allocator(vehicle, method=method)
    allocator.set_speed(SPEED)
    counts = []
    for tau in sequence:
        for _ in range(HOLD):
            result = allocator.allocate(tau)
        counts.append(int(np.sum(np.abs(result.thrust) > WORKING * model.force_scale)))
    return np.array(counts)


def table(count: int, methods: tuple[str, ...] = ("lp", "qp")) -> list[dict]:
    rows = []
    for path in sorted(p for p in (ROOT / "config").glob("*.yaml") if p.stem != "default"):
        vehicle = without_rates(path)
        sequence = requests(vehicle, count)
        row = {"vehicle": path.stem, "actuators": len(vehicle.actuators), "dofs": len(vehicle.dofs),
               "requests": len(sequence)}
        for method in methods:
            counts = working(vehicle, method, sequence)
            row[method] = (float(np.mean(counts)), int(np.max(counts)))
        rows.append(row)
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--requests", type=int, default=100)
    arguments = parser.parse_args(argv)
    print("| vehicle | actuators | controlled DOFs | requests | working, lp: mean / most | working, qp: mean / most |")
    print("|---|---|---|---|---|---|")
    for row in table(arguments.requests):
        print(f"| {row['vehicle']} | {row['actuators']} | {row['dofs']} | {row['requests']} | "
              f"{row['lp'][0]:.2f} / {row['lp'][1]} | {row['qp'][0]:.2f} / {row['qp'][1]} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
