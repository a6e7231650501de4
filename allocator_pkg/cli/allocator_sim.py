"""allocator-sim: the real ``allocator_node`` holding a simulated vehicle on station, in
lock-step on ROS 2 sim time.

    allocator-sim SCENARIO --out DIR [--seed N] [--method M] [--duration-scale S] [--live [SECONDS]]
                  [--no-verdict] [--in-process]
    allocator-sim compare SCENARIO --methods qp lp ... --out DIR [--duration-scale S] [--no-verdict]
                  [--no-baseline] [--in-process]

The node runs as its own process, unchanged, with ``use_sim_time`` and ``trigger: input``.
This process publishes ``/clock``, the vehicle's ``odometry``, its ``battery_state``, the power
plant's ``power_available`` (once a scenario's ``power`` event has come) and the controller's
``wrench_command``, and integrates the vehicle on the ``thruster_commands`` it
gets back. The clock advances one step (1 / rate_hz) only when the node has answered the
step's wrench (its ``allocation_status`` stamped with the step's time and echoing the
wrench), so a run is deterministic for a seed and runs as fast as the node answers.

Prints the metrics with their units over the run and its windows, the figures of each
set-point step, and the verdict against the bounds the scenario holds the method to (its
``bounds``, or a method's own under ``methods``; ``compare``: one line per method, PASS, FAIL
naming each bound broken, or RUN FAILED for a run that crashed, which has no verdict). Exit
status (:data:`EXIT_HELD` ...): 0 every bound held, 1 a method broke a bound, 2 the scenario or
the command line refused, 3 a run failed (``--no-verdict``: the data only, no verdict).
Writes ``metrics.json``, ``run.mcap`` (every topic, for Foxglove and ``ros2 bag play``),
``footprint.png`` and ``timeline.png`` into DIR; ``compare`` writes one such folder per method,
``compare.md`` and ``compare.png``. Frames: odometry and set-point in NED (frame_id ``ned``),
the body in FRD (``base_link``), as the models are written.

``--in-process`` puts the allocator library in the loop in place of the node, in this process
and without ROS (:mod:`allocator_pkg.simulation.in_process`): the same trace, metrics and
figures, hundreds of times faster than real time, and no ``run.mcap`` or ``node.log``.

The loop is :mod:`allocator_pkg.simulation.closed_loop`; ``sim_loop`` starts the node and
``sim_link`` is its ROS side, ``sim_metrics`` recomputes the metrics from ``run.mcap``,
``sim_report`` writes the text and ``sim_plots`` draws the figures.
"""

from __future__ import annotations

import argparse
import os
import sys
import traceback
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from ..configuration.parameters import load_vehicle
from ..methods import METHODS
from ..ros.process import dds_environment
from ..simulation.closed_loop import ClosedLoop
from ..simulation.in_process import in_process_link
from ..simulation.report import figures as sim_plots
from ..simulation.report import verdict_text as sim_report
from ..simulation.run_setup import RunResult, SimulationError
from ..simulation.scenario import Scenario, ScenarioError, load_scenario


def run(scenario: Scenario, out: Path, live: float = 0.0, log: Callable[[str], None] = print,
        in_process: bool = False) -> RunResult:
    """One closed-loop run of ``scenario`` with the node as a process (``in_process``: the
    allocator library in this process); outputs into ``out``; with ``live`` > 0 a line of the
    live table every ``live`` simulated seconds."""
    if in_process:
        return ClosedLoop(scenario, out, in_process_link, log).run(live)
    os.environ.update(dds_environment())
    from ..ros.sim_loop import node_link  # rclpy loads here, in the DDS environment just set

    return ClosedLoop(scenario, out, node_link, log).run(live)


def in_process_run(scenario: Scenario, out: Path, live: float = 0.0,
                   log: Callable[[str], None] = print) -> RunResult:
    """:func:`run` with the allocator library in the loop."""
    return run(scenario, out, live, log, in_process=True)


IN_PROCESS_HELP = "the allocator library in the loop, in this process, in place of the node (no run.mcap)"


def _scenario(arguments: argparse.Namespace) -> Scenario:
    scenario = load_scenario(arguments.scenario)
    if arguments.duration_scale != 1.0:
        scenario = scenario.scaled(arguments.duration_scale)
    if getattr(arguments, "seed", None) is not None:
        scenario = replace(scenario, seed=arguments.seed)
    return scenario


EXIT_HELD, EXIT_BROKEN, EXIT_REFUSED, EXIT_FAILED = 0, 1, 2, 3
"""Exit status: every bound held (or ``--no-verdict``); a method broke a bound; the scenario or
the command line was refused before anything ran; a run failed (the node died or did not answer,
or the loop raised), whatever the other methods did."""
EXIT_TEXT = ("exit status: 0 every bound held (or --no-verdict), 1 a method broke a bound, 2 the scenario or "
             "the command line refused, 3 a run failed (no verdict for it)")
USAGE = ("%(prog)s SCENARIO --out DIR [--seed N] [--method M] [--duration-scale S] [--live [SECONDS]] "
         "[--no-verdict] [--in-process]\n"
         "       %(prog)s compare SCENARIO --methods M [M ...] --out DIR [--seed N] [--duration-scale S] "
         "[--no-baseline] [--no-verdict] [--in-process]")


def _failure(method: str, error: Exception) -> str:
    """One line of a run that failed; a traceback on stderr when it is not the loop's own error."""
    if not isinstance(error, (SimulationError, ScenarioError)):
        traceback.print_exception(error, file=sys.stderr)
    return f"{method}: RUN FAILED, {type(error).__name__}: {error} (no verdict)"


def compare(arguments: argparse.Namespace) -> int:
    """``allocator-sim compare``: the scenario under each method, side by side; one verdict line
    per method (PASS, FAIL naming the bounds broken, or RUN FAILED) and the exit status of the
    worst (:data:`EXIT_FAILED` over :data:`EXIT_BROKEN`)."""
    runner = in_process_run if arguments.in_process else run
    try:
        scenario = _scenario(arguments)
        vehicle = load_vehicle(scenario.vehicle)
        for method in arguments.methods:
            if method not in METHODS:
                raise ValueError(f"--methods: {method!r} is not one of {', '.join(METHODS)}")
    except (ScenarioError, ValueError) as error:
        print(f"allocator-sim: {error}", file=sys.stderr)
        return EXIT_REFUSED
    out = Path(arguments.out)
    results, nominals, chosen, failed = {}, {}, {}, {}
    for method in arguments.methods:
        unfit = METHODS[method].problems(vehicle)
        if unfit:
            print(f"sim: {method} left out: it cannot serve this vehicle: {'; '.join(unfit)}", flush=True)
            continue
        try:
            chosen[method] = scenario.with_method(method)
        except ScenarioError as error:               # the scenario's parameters ask what it lacks
            print(f"sim: {method} left out: {error}", flush=True)
            continue
        print(f"sim: {scenario.name} with {method}", flush=True)
        try:
            result = runner(chosen[method], out / method)
            nominal = None if arguments.no_baseline else \
                sim_plots.nominal_run(chosen[method], out / method / "nominal", runner)
            sim_plots.plot_run(out / method, result, chosen[method], nominal)
        except Exception as error:                   # one method's failure is its verdict
            failed[method] = _failure(method, error)
            print(f"sim: {failed[method]}", flush=True)
            continue
        results[method] = result
        if nominal is not None:
            nominals[method] = nominal
    if results:
        table = sim_plots.compare_table(scenario, {m: r.metrics for m, r in results.items()},
                                        {m: r.metrics for m, r in nominals.items()})
        (out / "compare.md").write_text(table)
        sim_plots.plot_compare(out / "compare.png", scenario, results, nominals)
        print(table)
        print(f"sim: comparison written to {out.resolve()}")
    verdicts = {} if arguments.no_verdict else \
        {m: sim_report.method_verdict(chosen[m], m, r.report) for m, r in results.items()}
    for method in arguments.methods:
        if method in verdicts or method in failed:
            print(f"sim: {verdicts[method][1] if method in verdicts else failed[method]}")
    broke = [m for m, (passed, _) in verdicts.items() if not passed]
    print(f"sim: {scenario.name}: " + sim_report.compare_summary(list(verdicts), broke, list(failed),
                                                                    arguments.no_verdict))
    if failed:
        return EXIT_FAILED
    return EXIT_BROKEN if broke else EXIT_HELD


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["compare"]:
        parser = argparse.ArgumentParser(prog="allocator-sim compare", epilog=EXIT_TEXT,
                                         description="The same scenario under several methods, side by side.")
        parser.add_argument("scenario")
        parser.add_argument("--methods", nargs="+", required=True)
        parser.add_argument("--out", required=True)
        parser.add_argument("--seed", type=int, default=None)
        parser.add_argument("--duration-scale", type=float, default=1.0)
        parser.add_argument("--no-baseline", action="store_true",
                            help="skip each method's nominal run (same seed, no failure; doubles the run time)")
        parser.add_argument("--no-verdict", action="store_true", help="no verdict against the bounds")
        parser.add_argument("--in-process", action="store_true", help=IN_PROCESS_HELP)
        return compare(parser.parse_args(argv[1:]))

    parser = argparse.ArgumentParser(
        prog="allocator-sim", usage=USAGE, formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__.split("\n\n")[0] + "\n\n" + "compare: the same scenario under several methods, side "
        "by side, one verdict per method (allocator-sim compare --help).",
        epilog=EXIT_TEXT)
    parser.add_argument("scenario", help="scenario file (config/scenarios/*.yaml)")
    parser.add_argument("--out", required=True, help="output folder")
    parser.add_argument("--seed", type=int, default=None, help="environment seed (default: the scenario's)")
    parser.add_argument("--method", default=None, help="allocation method (default: the scenario's)")
    parser.add_argument("--duration-scale", type=float, default=1.0,
                        help="scale the duration and every event time (short runs)")
    parser.add_argument("--live", type=float, nargs="?", const=1.0, default=0.0, metavar="SECONDS",
                        help="a live table, one line every SECONDS of simulated time (default 1)")
    parser.add_argument("--no-verdict", action="store_true",
                        help="no verdict against the scenario's bounds (exit status 0 unless refused or failed)")
    parser.add_argument("--in-process", action="store_true", help=IN_PROCESS_HELP)
    arguments = parser.parse_args(argv)
    try:
        scenario = _scenario(arguments)
        if arguments.method:
            scenario = scenario.with_method(arguments.method)
    except (ScenarioError, ValueError) as error:
        print(f"allocator-sim: {error}", file=sys.stderr)
        return EXIT_REFUSED
    out = Path(arguments.out)
    print(f"sim: {scenario.name}, {scenario.method}, {scenario.duration:g} s, seed {scenario.seed}", flush=True)
    try:
        result = run(scenario, out, live=arguments.live, log=lambda text: print(text, flush=True),
                     in_process=arguments.in_process)
    except Exception as error:                       # a failed run, told apart from a broken bound
        print(f"allocator-sim: {_failure(scenario.method, error)}", file=sys.stderr)
        return EXIT_FAILED
    sim_plots.plot_run(out, result, scenario)
    for line in sim_report.metrics_lines(result.report) + sim_report.steps_lines(result.report):
        print(f"sim: {line}")
    print(f"sim: outputs written to {out.resolve()}")
    if arguments.no_verdict:
        return EXIT_HELD
    passed, lines = sim_report.verdict(scenario, result.report)
    for line in lines:
        print(f"sim: {line}")
    return EXIT_HELD if passed else EXIT_BROKEN


if __name__ == "__main__":
    sys.exit(main())
