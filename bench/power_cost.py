"""The cost of the power rows (docs/power.md, "Power rows"), as ratios of one run: the DP vessel
without power sources, with them at capacity (the rows held, no source short), and power-limited
(single feeds with switchboard A at 1000 kW and B at 1500 kW; the 70/30 split feed with A at
1200 kW and B at 2000 kW), each fed the same requests (random, each held ten samples) sample by
sample in turn, so that the load of the machine falls on all alike. Prints JSON: the mean and
median sample time [ms] of each and

- ``limited_over_unlimited``: a power-limited sample over one at capacity (target <= 1.3);
- ``rows_over_without``: a sample with the rows at capacity over one without sources (target <= 1.2);
- ``limited_over_without``: a power-limited sample over one without sources.

    python bench/power_cost.py [--samples 3000]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from allocator_pkg import Allocator, read_parameters, vehicle_from_parameters
from allocator_pkg.vehicle.config import DOF_NAMES

ROOT = Path(__file__).resolve().parents[1]
DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
HELD = 10
"""Samples each request is held."""


def allocators() -> dict[str, Allocator]:
    """The cases, by name."""
    parameters = read_parameters(DP_VESSEL)
    plain = {k: v for k, v in parameters.items()
             if not k.startswith(("power.", "redundancy_groups.")) and not k.endswith((".feeds", ".feed_shares"))}
    split = {**parameters, "actuators.azimuth_stbd.feeds": ["swbd_a", "swbd_b"],
             "actuators.azimuth_stbd.feed_shares": [0.7, 0.3]}
    cases = {"without": Allocator(vehicle_from_parameters(plain)),
             "at_capacity": Allocator(vehicle_from_parameters(parameters)),
             "limited": Allocator(vehicle_from_parameters(parameters)),
             "limited_split": Allocator(vehicle_from_parameters(split))}
    cases["limited"].set_available_power({"swbd_a": 1000.0, "swbd_b": 1500.0})
    cases["limited_split"].set_available_power({"swbd_a": 1200.0, "swbd_b": 2000.0})
    return cases


def run(samples: int, seed: int = 3) -> dict:
    cases = allocators()
    first = next(iter(cases.values()))
    rows = [DOF_NAMES.index(d) for d in first.vehicle.dofs]
    scale = first.model.dof_scale
    rng = np.random.default_rng(seed)
    times: dict[str, list[float]] = {name: [] for name in cases}
    limited = dict.fromkeys(cases, 0)
    tau = np.zeros(6)
    for k in range(samples):
        if k % HELD == 0:
            tau = np.zeros(6)
            tau[rows] = rng.normal(size=len(rows)) * scale * rng.choice([0.1, 0.3, 0.6])
        for name, allocator in cases.items():
            start = time.perf_counter()
            result = allocator.allocate(tau)
            times[name].append(time.perf_counter() - start)
            limit = allocator.power_limit
            limited[name] += limit is not None and allocator.power.reading(result.thrust, limit).limited
    mean = {name: 1e3 * float(np.mean(t)) for name, t in times.items()}
    median = {name: 1e3 * float(np.median(t)) for name, t in times.items()}
    power_limited = 0.5 * (mean["limited"] + mean["limited_split"])
    return {"samples": samples, "mean_ms": mean, "median_ms": median,
            "power_limited_share": {name: count / samples for name, count in limited.items()},
            "limited_over_unlimited": power_limited / mean["at_capacity"],
            "rows_over_without": mean["at_capacity"] / mean["without"],
            "limited_over_without": power_limited / mean["without"],
            "setups": {name: allocator.stats.solver_setups for name, allocator in cases.items()}}


def section(run: dict) -> list[str]:
    """The docs/performance.md section of a run."""
    mean, median = run["mean_ms"], run["median_ms"]
    lines = ["## Power rows", "",
             f"`bench/power_cost.py`, {run['samples']} samples of the DP vessel per case, the cases in turn "
             "sample by sample (docs/power.md, power rows).", "",
             "| case | mean [ms] | median [ms] | samples power-limited |", "|---|---|---|---|"]
    lines += [f"| {name} | {mean[name]:.3f} | {median[name]:.3f} | {100 * run['power_limited_share'][name]:.0f} % |"
              for name in mean]
    lines += ["", f"A power-limited sample costs {run['limited_over_unlimited']:.2f}x one at capacity (target <= 1.3); "
              f"a sample with the rows {run['rows_over_without']:.2f}x one without sources (target <= 1.2); "
              f"a power-limited one {run['limited_over_without']:.2f}x one without sources."]
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=3000)
    arguments = parser.parse_args()
    print(json.dumps(run(arguments.samples), indent=1))


if __name__ == "__main__":
    main()
