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

``--step-costs``: instead, what a simulated step of one case (heading 90 deg, number 6, the loss
of switchboard_a, with the DP system: observer, noise, feed-forward, trip, losses) spends where,
by process time over the run after its warm-up: in ``Allocator.allocate``, in the rest of the
in-process link's step (the node's periodic work: power readings, consequence analysis), in the
control system (measurement, observer, controller, feed-forward), in the simulated thrusters
(lag, rate, losses, their wrench) and in the hull, environment and trace, each per step and as a
ratio to ``allocate``.

    .venv/bin/python bench/dp_level3.py [--settle 60] [--duration 600] [--step-costs]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from dataclasses import replace
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


class Timed:
    """Process time [s] spent in the wrapped methods of an object, summed."""

    def __init__(self) -> None:
        self.seconds = 0.0

    def wrap(self, owner: object, name: str) -> None:
        inner = getattr(owner, name)

        def timed(*args, **kwargs):
            start = time.process_time()
            try:
                return inner(*args, **kwargs)
            finally:
                self.seconds += time.process_time() - start
        setattr(owner, name, timed)


def step_costs(settle: float, duration: float) -> dict:
    """Per simulated step [us] and against allocate(): the allocator, the control system, the
    thrusters and the rest, over one case after its warm-up."""
    import contextlib
    import tempfile

    from allocator_pkg.dp.inputs.particulars import load_particulars
    from allocator_pkg.dp.level3.case import GroupFaultLink, case_scenario
    from allocator_pkg.simulation.closed_loop import ClosedLoop

    particulars = load_particulars(ROOT / "config" / "particulars" / "dp_vessel.yaml")
    setup = replace(case_setup(settle, duration), hull=particulars.hull, frame=particulars.frame,
                    particulars=particulars)
    scenario = case_scenario(setup, Case(90.0, 6, "switchboard_a", 0))
    parts = {name: Timed() for name in ("allocate", "link", "control", "thrusters", "step")}
    links = []

    @contextlib.contextmanager
    def connect(run, out):
        links.append(GroupFaultLink(run, "switchboard_a"))
        yield links[-1]

    with tempfile.TemporaryDirectory() as folder:
        loop = ClosedLoop(scenario, Path(folder), connect, log=lambda _: None)
        for name in ("measure", "wrench", "advance"):
            parts["control"].wrap(loop.control, name)
        for name in ("step", "wrench"):
            parts["thrusters"].wrap(loop.plant.thrusters, name)
        original = loop._steps

        def steps(link, start_ns, live):
            for timed in parts.values():
                timed.seconds = 0.0                                  # the warm-up not counted
            parts["allocate"].wrap(link.allocator, "allocate")
            parts["link"].wrap(link, "step")
            start = time.process_time()
            original(link, start_ns, live)
            parts["step"].seconds = time.process_time() - start
        loop._steps = steps
        loop.run()
    count = round(scenario.duration / loop.period)
    allocate, link = parts["allocate"].seconds, parts["link"].seconds
    simulation = parts["step"].seconds - link
    per_step = {"allocate": allocate, "allocator_link_besides_allocate": link - allocate,
                "control_and_observer": parts["control"].seconds, "thrusters": parts["thrusters"].seconds,
                "hull_environment_trace": simulation - parts["control"].seconds - parts["thrusters"].seconds,
                "simulation_side": simulation, "all_but_allocate": parts["step"].seconds - allocate}
    return {"case": "dp_vessel, 90 deg, number 6, switchboard_a lost", "steps": count,
            "us_per_step": {k: 1e6 * v / count for k, v in per_step.items()},
            "ratio_to_allocate": {k: v / allocate for k, v in per_step.items()},
            "control_observer_thrusters_over_allocate":
                (parts["control"].seconds + parts["thrusters"].seconds) / allocate,
            "load_average": os.getloadavg()[0]}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--settle", type=float, default=60.0, help="[s] on station before the failure (default 60)")
    parser.add_argument("--duration", type=float, default=600.0, help="[s] simulated after settling (default 600)")
    parser.add_argument("--step-costs", action="store_true", help="where one case's simulated step spends its time")
    arguments = parser.parse_args(argv)
    if arguments.step_costs:
        print(json.dumps(step_costs(arguments.settle, arguments.duration), indent=1))
        return 0
    print(json.dumps(measure(arguments.settle, arguments.duration), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
