"""How long a full DNV-ST-0111 Level 1 run takes on this machine.

One run is that of ``allocator-capability --dnv-level1`` on dp_vessel without its files: a fresh
:class:`~allocator_pkg.dp.level1.Level1` (nothing cached) run over every heading
(every 10 deg: 36), intact and for every redundancy group, to its complete result (the numbers
and the allocation behind Tables A-8 to A-10 of each case and heading). Each run is timed by the
wall clock and by the user CPU time of the process (every thread); the figures are the medians over the repeats. A
balance is one call of ``Level1.balanced`` (one condition, heading and case), counted by a
subclass; ``ms_per_balance`` is the median wall time over the balances of a run (the allocation
of the tables included).

    .venv/bin/python bench/dp_capability.py [--repeats 3] [--heading-step 10]
"""

from __future__ import annotations

import argparse
import json
import resource
import statistics
import sys
import time
from pathlib import Path

from allocator_pkg import load_vehicle
from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.level1 import Level1

ROOT = Path(__file__).resolve().parents[1]
VESSEL = "dp_vessel"
TARGET_S = 5.0
"""[s] A full run (36 headings, intact and every group) should take less."""


class CountedLevel1(Level1):
    """Level 1 that counts its balances."""

    def __init__(self, *args, **kwargs):
        self.balances = 0
        super().__init__(*args, **kwargs)

    def balanced(self, level: float, direction: float, failed: tuple[str, ...] = ()) -> bool:
        self.balances += 1
        return super().balanced(level, direction, failed)


def _user_cpu() -> float:
    """[s] user CPU time of this process so far, every thread's."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_utime


def measure(repeats: int = 3, step_deg: float = 10.0) -> dict:
    """Wall time [s] of each run, their median, the balances of one run and its summary."""
    vehicle = load_vehicle(ROOT / "config" / f"{VESSEL}.yaml")
    particulars = load_particulars(ROOT / "config" / "particulars" / f"{VESSEL}.yaml")
    times, cpu, balances, summary = [], [], 0, ""
    for _ in range(repeats):
        start, start_cpu = time.perf_counter(), _user_cpu()
        analysis = CountedLevel1(vehicle, particulars)
        result = analysis.run(step_deg)
        times.append(time.perf_counter() - start)
        cpu.append(_user_cpu() - start_cpu)
        balances, summary = analysis.balances, result.summary_line()
    wall = statistics.median(times)
    return {"vessel": VESSEL, "heading_step_deg": step_deg, "headings": round(360.0 / step_deg),
            "cases": 1 + len(analysis.groups), "repeats": repeats, "wall_s": times, "wall_s_median": wall,
            "user_cpu_s": cpu, "user_cpu_s_median": statistics.median(cpu), "balances": balances,
            "ms_per_balance": 1e3 * wall / balances, "summary": summary, "target_s": TARGET_S}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=3, help="full runs timed (default: 3)")
    parser.add_argument("--heading-step", type=float, default=10.0, help="[deg] between headings (default: 10)")
    arguments = parser.parse_args(argv)
    print(json.dumps(measure(arguments.repeats, arguments.heading_step), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
