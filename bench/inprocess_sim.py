"""How fast the in-process closed loop runs on this machine, against the node in the loop.

One run is that of ``allocator-sim --in-process`` on a scenario (by default
``config/scenarios/dp_station_keeping.yaml``, the DP vessel at 10 Hz for 300 s) without its
figures: the allocator library in the loop, in this process (``simulation/in_process.py``).
Three real-time factors (simulated seconds per second) per run:

- ``loop``: the scenario's duration over the wall time of its steps (metrics.json's
  ``realtime_factor``);
- ``run``: the duration over the whole run's wall time, set-up, the warm-up (20 s of
  equilibrium wrench for the DP vessel) and ``metrics.json`` included: what a batch of seeded
  runs gets;
- ``run_cpu``: the same over the CPU time spent, this process's and its children's (the node's
  process), what one core gives when other processes share the cores.

Each is the median over the repeats. In the same run, one node-in-the-loop run (``allocator-sim``
with the real ``allocator_node`` as a process) gives its factors, and the ratio
in-process / node of each. The in-process target is at least ``TARGET`` times real time on one
core, judged on ``run_cpu`` (the whole run; wall-clock figures drop when other processes share
the cores, and the output gives the load average).

    .venv/bin/python bench/inprocess_sim.py [--scenario FILE] [--repeats 5] [--no-node]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from allocator_pkg.cli.allocator_sim import run
from allocator_pkg.simulation.run_setup import RunResult
from allocator_pkg.simulation.scenario import Scenario, load_scenario

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / "config" / "scenarios" / "dp_station_keeping.yaml"
TARGET = 300.0
"""[x real time] A whole in-process run of the DP vessel should run at least this fast on one core."""


def cpu_time() -> float:
    """[s] of CPU this process and its ended children have used."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def timed(scenario: Scenario, runner: Callable[[Path], RunResult]) -> dict[str, float]:
    """The loop and whole-run real-time factors of one run into a folder of its own."""
    with tempfile.TemporaryDirectory() as folder:
        start, cpu = time.perf_counter(), cpu_time()
        result = runner(Path(folder))
        wall, cpu = time.perf_counter() - start, cpu_time() - cpu
    return {"loop": result.metrics["realtime_factor"], "run": scenario.duration / wall,
            "run_cpu": scenario.duration / cpu, "wall_s": wall}


def measure(path: Path = SCENARIO, repeats: int = 5, node: bool = True) -> dict:
    """The in-process factors of ``repeats`` runs and their medians, one node run's, the ratios."""
    scenario = load_scenario(path)
    quiet = {"log": lambda _: None}
    runs = [timed(scenario, lambda out: run(scenario, out, in_process=True, **quiet)) for _ in range(repeats)]
    in_process = {kind: statistics.median(r[kind] for r in runs) for kind in ("loop", "run", "run_cpu")}
    result = {"scenario": scenario.name, "duration_s": scenario.duration, "method": scenario.method,
              "cpu_count": os.cpu_count(), "load_average": os.getloadavg(), "repeats": repeats, "in_process_runs": runs,
              "in_process": in_process, "target": TARGET, "meets_target": in_process["run_cpu"] >= TARGET}
    if node:
        factors = timed(scenario, lambda out: run(scenario, out, **quiet))
        result["node"] = factors
        result["ratio"] = {kind: in_process[kind] / factors[kind] for kind in ("loop", "run", "run_cpu")}
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenario", type=Path, default=SCENARIO, help="scenario file (default: dp_station_keeping)")
    parser.add_argument("--repeats", type=int, default=5, help="in-process runs timed (default: 5)")
    parser.add_argument("--no-node", action="store_true", help="skip the node-in-the-loop run")
    arguments = parser.parse_args(argv)
    print(json.dumps(measure(arguments.scenario, arguments.repeats, not arguments.no_node), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
