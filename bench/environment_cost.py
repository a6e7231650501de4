"""What the Level 3 environment costs per simulated step against allocate(), in one run.

A Level 3 case of dp_vessel (number 6, heading 45 deg, intact, the standard's mean loads, NPD
gusts and a JONSWAP sea) runs in the in-process closed loop with a link that times each
``Allocator.allocate`` call; the rest of the step (the link's own per-sample work, plant,
environment, controller, trace) is the run's time less that (bench/dp_step_costs.py splits it).
Apart from it, the environment alone per step (``step``, ``hull_load``,
``wave_motion``, ``wind_feedforward``), its series' generation spread over the case's steps, and the
first-order environment (no spectra) for comparison. Ratios within this one run; the target is
everything but allocate() at most allocate() (a ratio <= 1).

    .venv/bin/python bench/environment_cost.py [--duration 300]
"""

from __future__ import annotations

import argparse
import contextlib
import json
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from allocator_pkg.dp.capability_result import INTACT
from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.level3.case import Case, CaseSetup, Criteria, case_scenario
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS
from allocator_pkg.simulation.closed_loop import ClosedLoop
from allocator_pkg.simulation.environment import Environment
from allocator_pkg.simulation.in_process import InProcessLink
from allocator_pkg.simulation.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]


class TimedLink(InProcessLink):
    """The in-process link adding up the wall time of its ``Allocator.allocate`` calls alone (the
    link's own per-sample work, the power drawn per source and the consequence analysis among it, is the
    node's work beside the solve and counts in the rest)."""

    def __init__(self, scenario) -> None:
        super().__init__(scenario)
        self.spent, self.calls = 0.0, 0
        inner = self.allocator.allocate

        def allocate(wrench):
            start = time.perf_counter()
            try:
                return inner(wrench)
            finally:
                self.spent += time.perf_counter() - start
                self.calls += 1
        self.allocator.allocate = allocate


def environment_step_cost(scenario, steps: int, period: float) -> tuple[float, float]:
    """(per step [s] of the environment's per-step calls, generation [s])."""
    start = time.perf_counter()
    environment = Environment(scenario.environment, scenario.seed, scenario.particulars, scenario.duration)
    built = time.perf_counter() - start
    start = time.perf_counter()
    for _ in range(steps):
        environment.step(period)
        environment.hull_load(0.01)
        environment.wave_motion()
        environment.wind_feedforward(0.01)
    return (time.perf_counter() - start) / steps, built


def measure(duration: float) -> dict:
    particulars = load_particulars(ROOT / "config" / "particulars" / "dp_vessel.yaml")
    base = replace(load_scenario(ROOT / "config" / "scenarios" / "dp_station_keeping.yaml"),
                   particulars=particulars.vessel)
    setup = CaseSetup(base, WEATHER_CONDITIONS, {}, frozenset(), Criteria(50.0, 30.0, 60.0, duration),
                      particulars.hull, particulars.frame)
    scenario = case_scenario(setup, Case(45.0, 6, INTACT, 0))
    links: list[TimedLink] = []

    @contextlib.contextmanager
    def connect(run, out):
        links.append(TimedLink(run))
        yield links[-1]

    with tempfile.TemporaryDirectory(prefix="bench_env_") as folder:
        start = time.perf_counter()
        loop = ClosedLoop(scenario, Path(folder), connect, log=lambda _: None)
        trace = loop.run().trace
        total = time.perf_counter() - start
    link = links[0]
    allocate = link.spent / link.calls
    rest = (total - link.spent) / link.calls
    steps = len(trace.time)
    spectral, generation = environment_step_cost(scenario, steps, trace.period)
    first_order, _ = environment_step_cost(case_scenario(replace(setup, spectra=False), Case(45.0, 6, INTACT, 0)),
                                           steps, trace.period)
    return {"case": "dp_vessel number 6, heading 45 deg, intact", "simulated_s": 60.0 + duration,
            "steps": link.calls, "allocate_us": 1e6 * allocate, "rest_of_step_us": 1e6 * rest,
            "rest_over_allocate": rest / allocate,
            "environment_us": 1e6 * spectral, "environment_generation_s": generation,
            "environment_generation_per_step_us": 1e6 * generation / max(link.calls, 1),
            "environment_over_allocate": (spectral + generation / max(link.calls, 1)) / allocate,
            "first_order_environment_us": 1e6 * first_order, "target_ratio": 1.0,
            "mean_position_error_m": float(np.mean(trace.position_errors()))}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=300.0, help="[s] simulated after settling (default 300)")
    arguments = parser.parse_args(argv)
    print(json.dumps(measure(arguments.duration), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
