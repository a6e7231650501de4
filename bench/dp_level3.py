"""What a DNV-ST-0111 Level 3 case costs on this machine, and what a second worker gives.

A fixed set of cases of dp_vessel (``config/scenarios/dp_station_keeping.yaml``'s controller and
variations): headings 0, 90, 180 and 270 deg, capability numbers 4 and 6, intact and after the loss
of switchboard_a, seed 0, each ``--settle`` + ``--duration`` simulated seconds. They run

- one after another in this process (the case cost: wall and CPU time per case, cases per
  minute, simulated seconds per wall second);
- on the Level 3 process pool (:class:`allocator_pkg.dp.level3.engine.PoolEngine`) with 1 and
  with 2 workers, timed by the wall clock; the speed-up is the 1-worker time over the 2-worker
  time (target 1.8), and the three sets of results must be equal bit for bit.

The load average before each part is printed with it: other work on the machine shares its cores.

    .venv/bin/python bench/dp_level3.py [--settle 60] [--duration 600]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.dp.capability_result import INTACT
from allocator_pkg.dp.level3.case import Case, CaseResult, CaseSetup, Criteria, run_case
from allocator_pkg.dp.level3.engine import PoolEngine
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS
from allocator_pkg.simulation.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]
TARGET_SPEEDUP = 1.8
CASES = [Case(heading, number, group, 0) for heading in (0.0, 90.0, 180.0, 270.0) for number in (4, 6)
         for group in (INTACT, "switchboard_a")]


def case_setup(settle: float, duration: float) -> CaseSetup:
    scenario = load_scenario(ROOT / "config" / "scenarios" / "dp_station_keeping.yaml")
    vehicle = load_vehicle(scenario.vehicle)
    groups = {g.name: tuple(g.actuators) for g in vehicle.redundancy_groups}
    return CaseSetup(scenario, WEATHER_CONDITIONS, groups, frozenset(groups),
                     Criteria(settle=settle, duration=duration))


def on_pool(setup: CaseSetup, workers: int) -> tuple[float, dict[tuple, CaseResult]]:
    """Wall time [s] of the cases on a pool of ``workers`` (its start-up included), and the results."""
    start = time.perf_counter()
    results = {}
    with PoolEngine(workers) as engine:
        engine.start(run_case, setup)
        queue = list(CASES)
        while queue or engine.running:
            while queue and len(engine.running) < 2 * workers:
                engine.submit(queue.pop(0))
            for result in engine.wait():
                results[result.case.key] = result
    return time.perf_counter() - start, results


def measure(settle: float, duration: float) -> dict:
    setup = case_setup(settle, duration)
    load_serial = os.getloadavg()[0]
    wall, cpu = time.perf_counter(), time.process_time()
    serial = {case.key: run_case(case, setup) for case in CASES}
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    load_one = os.getloadavg()[0]
    one, results_one = on_pool(setup, 1)
    load_two = os.getloadavg()[0]
    two, results_two = on_pool(setup, 2)
    simulated = (settle + duration) * len(CASES)
    return {"vessel": "dp_vessel", "cases": len(CASES), "simulated_s_per_case": settle + duration,
            "in_process": {"wall_s": wall, "cpu_s": cpu, "wall_s_per_case": wall / len(CASES),
                           "cpu_s_per_case": cpu / len(CASES), "cases_per_minute": 60.0 * len(CASES) / wall,
                           "realtime_factor_wall": simulated / wall, "realtime_factor_cpu": simulated / cpu,
                           "load_average": load_serial},
            "pool_1_worker": {"wall_s": one, "load_average": load_one},
            "pool_2_workers": {"wall_s": two, "load_average": load_two},
            "speedup_2_over_1": one / two, "target_speedup": TARGET_SPEEDUP,
            "identical": serial == results_one == results_two, "cpu_count": os.cpu_count()}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--settle", type=float, default=60.0, help="[s] on station before the failure (default 60)")
    parser.add_argument("--duration", type=float, default=600.0, help="[s] simulated after settling (default 600)")
    arguments = parser.parse_args(argv)
    print(json.dumps(measure(arguments.settle, arguments.duration), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
