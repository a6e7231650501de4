"""What ``allocate`` costs when the core idles between samples, as a node's core does.

The solver bench calls ``allocate`` back to back; a node calls it once per wrench and sleeps in
between. The same work then takes more CPU: caches and branch predictors lose what the last
sample left there (and a virtual machine's idle vCPU may run elsewhere). This bench measures
that multiple on this machine, with no ROS in the way: per vehicle, the same 400 samples of a
request that turns in the horizontal plane (the node-cost probe's: ``overhead.AMPLITUDE``, one
turn in ``overhead.PERIOD``, here at 100 Hz with ``dt`` 0.01 s), from an allocator warmed up
by 300 samples, timed by the thread's CPU clock around each ``allocate``: back to back, and
after sleeping each gap before every sample. Gaps alternate in rounds; each figure is the
median over rounds.

    .venv/bin/python bench/idle_core.py [--rounds 3] [--samples 400]
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from overhead import AMPLITUDE, PERIOD

from allocator_pkg import Allocator, load_vehicle

ROOT = Path(__file__).resolve().parents[1]
GAPS_MS = (0.0, 2.0, 10.0)
"""[ms] Idle time before each sample: back to back, a 500 Hz node's, a 100 Hz node's."""
RATE_HZ = 100.0
WARM_UP = 300


def requests(amplitude: float, count: int) -> list[np.ndarray]:
    """The turning horizontal force, one request per sample at RATE_HZ."""
    out = []
    for k in range(count):
        angle = 2.0 * math.pi * k / (RATE_HZ * PERIOD)
        tau = np.zeros(6)
        tau[0], tau[1] = amplitude * math.cos(angle), amplitude * math.sin(angle)
        out.append(tau)
    return out


def cpu_per_sample(vehicle_name: str, gap_ms: float, samples: int) -> list[float]:
    """Thread CPU [us] of each of ``samples`` allocations after the warm-up, each after ``gap_ms`` idle."""
    allocator = Allocator(load_vehicle(ROOT / "config" / f"{vehicle_name}.yaml"), dt=1.0 / RATE_HZ)
    sequence = requests(AMPLITUDE[vehicle_name], WARM_UP + samples)
    for tau in sequence[:WARM_UP]:
        allocator.allocate(tau)
    gap = gap_ms * 1e-3
    times = []
    for tau in sequence[WARM_UP:]:
        if gap:
            time.sleep(gap)
        start = time.thread_time_ns()
        allocator.allocate(tau)
        times.append((time.thread_time_ns() - start) * 1e-3)
    return times


def measure(rounds: int, samples: int) -> dict:
    """Per vehicle and gap: the medians over rounds of each round's p50 and mean CPU per sample
    [us], and their multiple of the back-to-back figure."""
    figures: dict[str, dict[float, list[tuple[float, float]]]] = {name: {gap: [] for gap in GAPS_MS}
                                                                  for name in AMPLITUDE}
    for _ in range(rounds):
        for name in AMPLITUDE:
            for gap in GAPS_MS:
                times = cpu_per_sample(name, gap, samples)
                figures[name][gap].append((float(np.percentile(times, 50)), float(np.mean(times))))
    result = {"rounds": rounds, "samples": samples, "rate_hz": RATE_HZ, "vehicles": {}}
    for name, by_gap in figures.items():
        rows = []
        for gap in GAPS_MS:
            p50 = float(np.median([p for p, _ in by_gap[gap]]))
            mean = float(np.median([m for _, m in by_gap[gap]]))
            rows.append({"gap_ms": gap, "cpu_us_p50": p50, "cpu_us_mean": mean})
        back_to_back = rows[0]
        for row in rows:
            row["p50_multiple"] = row["cpu_us_p50"] / back_to_back["cpu_us_p50"]
            row["mean_multiple"] = row["cpu_us_mean"] / back_to_back["cpu_us_mean"]
        result["vehicles"][name] = rows
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=3, help="rounds over every vehicle and gap (default: 3)")
    parser.add_argument("--samples", type=int, default=400, help="timed samples per case (default: 400)")
    arguments = parser.parse_args(argv)
    print(json.dumps(measure(arguments.rounds, arguments.samples), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
