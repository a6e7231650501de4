"""Where a simulated step of a DNV-ST-0111 Level 3 case spends its time, against
``Allocator.allocate``: one case of dp_vessel (heading 90 deg, capability number 6, the loss of
switchboard_a at the end of ``--settle``) with the DP system of :mod:`allocator_pkg.dp.level3.dp_system`
(observer, noise, wind feed-forward, trip, thrust losses), timed by process time over the run
after its warm-up, the case run twice in one process:

- the ratio: only ``Allocator.allocate`` timed; everything but ``allocate()`` is the run's steps
  less that, so it holds the in-process link's own per-sample work (the node's work beside the
  solve: supply voltage, available power, the status's power per source, the consequence
  analysis when on, the watchdog, the answer), the control system, the thrusters, the hull,
  the environment, the events and the trace. The two clock reads of that one wrapper per step
  (``timer_us_per_call``) fall partly on each side;
- the split: also the rest of the link's step (``InProcessLink.step`` less ``allocate``), the
  control system (measurement, observer, controller, feed-forward), the simulated thrusters
  (lag, rate, losses, their wrench) and the hull, environment and trace (the rest); each timed
  call's clock reads (``timer_us_per_call``, about 4 us on a virtual machine) fall on the parts
  that hold it, so the split's sum exceeds the ratio's run.

    .venv/bin/python bench/dp_step_costs.py [--settle 60] [--duration 240]
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import sys
import tempfile
import time
from pathlib import Path

from dp_level3 import case_setup

from allocator_pkg.dp.level3.case import Case, GroupFaultLink, case_scenario
from allocator_pkg.simulation.closed_loop import ClosedLoop


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


def timer_cost(calls: int = 20000) -> float:
    """[s] one :class:`Timed` call adds to a call of a function doing nothing."""
    class Idle:
        def call(self) -> None:
            return None

    idle = Idle()
    bare = idle.call
    start = time.process_time()
    for _ in range(calls):
        bare()
    plain = time.process_time() - start
    Timed().wrap(idle, "call")
    start = time.process_time()
    for _ in range(calls):
        idle.call()
    return max(0.0, time.process_time() - start - plain) / calls


def case_run(settle: float, duration: float, split: bool) -> tuple[dict[str, float], int]:
    """[s] in each timed part over one case after its warm-up, and the steps: ``allocate`` and
    ``step`` (the run's steps) always, with ``split`` the link, control and thrusters too."""
    scenario = case_scenario(case_setup(settle, duration), Case(90.0, 6, "switchboard_a", 0))
    parts = {name: Timed() for name in ("allocate", "link", "control", "thrusters", "step")}

    @contextlib.contextmanager
    def connect(run, out):
        yield GroupFaultLink(run, "switchboard_a")

    with tempfile.TemporaryDirectory() as folder:
        loop = ClosedLoop(scenario, Path(folder), connect, log=lambda _: None)
        if split:
            for name in ("measure", "wrench", "advance"):
                parts["control"].wrap(loop.control, name)
            for name in ("step", "wrench"):
                parts["thrusters"].wrap(loop.plant.thrusters, name)
        original = loop._steps

        def steps(link, start_ns, live):
            for timed in parts.values():
                timed.seconds = 0.0                                  # the warm-up not counted
            parts["allocate"].wrap(link.allocator, "allocate")
            if split:
                parts["link"].wrap(link, "step")
            start = time.process_time()
            original(link, start_ns, live)
            parts["step"].seconds = time.process_time() - start
        loop._steps = steps
        loop.run()
    return {name: timed.seconds for name, timed in parts.items()}, round(scenario.duration / loop.period)


def step_costs(settle: float, duration: float) -> dict:
    """Per simulated step [us] and against allocate(): everything but allocate() from a run
    timing allocate() alone, then the split from a run timing each part."""
    timer = timer_cost()
    whole, count = case_run(settle, duration, split=False)
    parts, _ = case_run(settle, duration, split=True)
    allocate, link = parts["allocate"], parts["link"]
    simulation = parts["step"] - link
    split = {"allocate": allocate, "allocator_link_besides_allocate": link - allocate,
             "control_and_observer": parts["control"], "thrusters": parts["thrusters"],
             "hull_environment_trace": simulation - parts["control"] - parts["thrusters"],
             "simulation_side": simulation}
    rest = whole["step"] - whole["allocate"]
    return {"case": "dp_vessel, 90 deg, number 6, switchboard_a lost", "steps": count,
            "allocate_us": 1e6 * whole["allocate"] / count, "all_but_allocate_us": 1e6 * rest / count,
            "all_but_allocate_over_allocate": rest / whole["allocate"], "target_ratio": 1.0,
            "timer_us_per_call": 1e6 * timer,
            "split_us_per_step": {k: 1e6 * v / count for k, v in split.items()},
            "split_ratio_to_allocate": {k: v / allocate for k, v in split.items()},
            "load_average": os.getloadavg()[0]}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--settle", type=float, default=60.0, help="[s] on station before the failure (default 60)")
    parser.add_argument("--duration", type=float, default=240.0, help="[s] simulated after settling (default 240)")
    arguments = parser.parse_args(argv)
    print(json.dumps(step_costs(arguments.settle, arguments.duration), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
