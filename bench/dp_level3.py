"""What a DNV-ST-0111 Level 3 case costs on this machine, and what a second worker gives.

A fixed set of cases of dp_vessel (``config/scenarios/dp_station_keeping.yaml``'s controller and
variations, the standard's hull of the particulars for the mean loads, their thrust losses, the
spectra and the DP system, as a study has them): headings 0, 90, 180 and 270 deg, capability
numbers 4 and 6, intact and after the loss of switchboard_a, seed 0, each ``--settle`` +
``--duration`` simulated seconds. They run

- one after another in this process (the case cost: wall and CPU time per case, cases per
  minute, simulated seconds per wall second);
- on the Level 3 process pool (:class:`allocator_pkg.dp.level3.engine.PoolEngine`) with 1 and
  with 2 workers, timed by the wall clock; the speed-up is the 1-worker time over the 2-worker
  time (target 1.8), and the three sets of results must be equal bit for bit;
- a short study (``--study``): the rising search of dp_vessel every 90 deg on the Level 2 site
  of the tests, ``--seeds`` seeds a condition, on 1 and on 2 pool workers
  (:func:`~allocator_pkg.dp.level3.engine.run_search`, its journal included), the same ratio,
  and the two journals must be equal byte for byte.

The load average before each part is printed with it: other work on the machine shares its cores.

    .venv/bin/python bench/dp_level3.py [--settle 60] [--duration 600] [--study] [--seeds 3]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.dp.capability_result import INTACT
from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.level3.case import Case, CaseResult, CaseSetup, Criteria, run_case
from allocator_pkg.dp.level3.engine import PoolEngine, run_search
from allocator_pkg.dp.level3.journal import Journal
from allocator_pkg.dp.level3.study import Level3Inputs, prepare
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS
from allocator_pkg.simulation.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]
TARGET_SPEEDUP = 1.8
CASES = [Case(heading, number, group, 0) for heading in (0.0, 90.0, 180.0, 270.0) for number in (4, 6)
         for group in (INTACT, "switchboard_a")]


def case_setup(settle: float, duration: float) -> CaseSetup:
    """The cases' set-up as a study of dp_vessel has it: the standard's hull for the mean loads, the
    particulars' thrust losses, the spectra and the DP system."""
    scenario = load_scenario(ROOT / "config" / "scenarios" / "dp_station_keeping.yaml")
    particulars = load_particulars(ROOT / "config" / "particulars" / "dp_vessel.yaml")
    groups = {g.name: tuple(g.actuators) for g in load_vehicle(scenario.vehicle).redundancy_groups}
    return CaseSetup(scenario, WEATHER_CONDITIONS, groups, frozenset(groups),
                     Criteria(settle=settle, duration=duration), particulars.hull, particulars.frame,
                     particulars=particulars)


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


STUDY = Level3Inputs(ROOT / "config" / "dp_vessel.yaml", ROOT / "config" / "particulars" / "dp_vessel.yaml",
                     site=ROOT / "test" / "data" / "sites" / "level3_site.yaml", heading_step=90.0)


def study_search(settle: float, duration: float, seeds: int) -> dict:
    """The short study's search on 1 and on 2 pool workers: wall times [s], ratio, runs, and
    whether the two journals are equal byte for byte."""
    prepared = prepare(replace(STUDY, criteria=replace(STUDY.criteria, settle=settle, duration=duration,
                                                       seeds=seeds)))
    walls, journals, loads = {}, {}, {}
    with tempfile.TemporaryDirectory(prefix="l3_bench_") as folder:
        for workers in (1, 2):
            path = Path(folder) / f"{workers}" / "cases.jsonl"
            loads[workers] = os.getloadavg()[0]
            start = time.perf_counter()
            with PoolEngine(workers) as engine:
                finished = run_search(prepared.search, prepared.setup, Journal(path, {"bench": "1"}, False), engine,
                                      progress=False)
            walls[workers] = time.perf_counter() - start
            journals[workers] = path.read_bytes()
    return {"runs": len(finished), "seeds": seeds, "simulated_s_per_run": settle + duration,
            "pool_1_worker": {"wall_s": walls[1], "load_average": loads[1]},
            "pool_2_workers": {"wall_s": walls[2], "load_average": loads[2]},
            "speedup_2_over_1": walls[1] / walls[2], "target_speedup": TARGET_SPEEDUP,
            "identical_journals": journals[1] == journals[2]}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--settle", type=float, default=60.0, help="[s] on station before the failure (default 60)")
    parser.add_argument("--duration", type=float, default=600.0, help="[s] simulated after settling (default 600)")
    parser.add_argument("--study", action="store_true", help="the short study's search in place of the fixed cases")
    parser.add_argument("--seeds", type=int, default=3, help="--study: seeds a condition (default 3)")
    arguments = parser.parse_args(argv)
    if arguments.study:
        print(json.dumps(study_search(arguments.settle, arguments.duration, arguments.seeds), indent=1))
    else:
        print(json.dumps(measure(arguments.settle, arguments.duration), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
