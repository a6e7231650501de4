"""Where a simulated step of a DNV-ST-0111 Level 3 case spends its time, against
``Allocator.allocate``: one case of dp_vessel (heading 90 deg, capability number 6, the loss of
switchboard_a at the end of ``--settle``) with the DP system of :mod:`allocator_pkg.dp.level3.dp_system`
(observer, noise, wind feed-forward, trip, thrust losses), timed by process time over the run
after its warm-up: in ``Allocator.allocate``, in the rest of the in-process link's step (the
node's periodic work: power readings, consequence analysis), in the control system
(measurement, observer, controller, feed-forward), in the simulated thrusters (lag, rate,
losses, their wrench) and in the hull, environment and trace; each per step [us] and as a ratio
to ``allocate`` (the timing wrappers' own cost, a few us per call, falls on the parts timed).

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

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.level3.case import Case, CaseSetup, Criteria, GroupFaultLink, case_scenario
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS
from allocator_pkg.simulation.closed_loop import ClosedLoop
from allocator_pkg.simulation.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]


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
    scenario = load_scenario(ROOT / "config" / "scenarios" / "dp_station_keeping.yaml")
    particulars = load_particulars(ROOT / "config" / "particulars" / "dp_vessel.yaml")
    groups = {g.name: tuple(g.actuators) for g in load_vehicle(scenario.vehicle).redundancy_groups}
    setup = CaseSetup(scenario, WEATHER_CONDITIONS, groups, frozenset(groups),
                      Criteria(settle=settle, duration=duration), particulars.hull, particulars.frame,
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
    parser.add_argument("--duration", type=float, default=240.0, help="[s] simulated after settling (default 240)")
    arguments = parser.parse_args(argv)
    print(json.dumps(step_costs(arguments.settle, arguments.duration), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
