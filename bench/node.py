"""Benchmark of the ROS node ``allocator_node``: rate, jitter, latency and CPU over DDS.

For each rate, the node runs in two set-ups: "one process" (AllocatorNode spun by its own
executor in a background thread, the probe in the main thread, one rclpy context) and "two
processes" (``allocator_node`` as a subprocess, the probe here). The probe publishes a slowly
varying wrench at about the node's rate and times the ThrusterCommands and AllocationStatus that
come back. After a warm-up, one measuring window per case gives the achieved rate, the period
jitter from the header stamps, missed periods, the tick-to-receipt and publish-to-commands
latencies and the node's CPU use (``probe.py`` says how each is counted). Results are written
as JSON.

"publish_to_commands_ms" includes the wait for the node's next tick, which depends on the phase
of the probe's timer against the node's: at exactly the node's rate that phase would stay where
the start left it, so the probe publishes one wrench more per window ("probe_rate_hz" = rate +
1 / seconds) and the phase sweeps one whole period over the window.

The "input trigger" cases run ``allocator_node`` with ``trigger: input`` and rate_hz
1000 as a subprocess and publish at 100 Hz and 1 kHz: every wrench is allocated on arrival,
so "publish to commands" has no wait for a tick in it.

    .venv/bin/python bench/node.py [--config config/bluerov2_heavy.yaml] [--rates 50 200 1000]
                                   [--inputs 100 1000]
                                   [--seconds 10 | --quick] [--out bench/results/node.json]
"""

import os

from allocator_pkg.ros.process import dds_environment

os.environ.update(dds_environment())

import argparse
import gc
import json
import sys
import time
from pathlib import Path

import rclpy
from figures import process_cpu_seconds
from probe import WARM_UP, measure, node_in_thread, node_process, probe_in, ros_context

ROOT = Path(__file__).resolve().parents[1]
QUICK_SECONDS = 2.0
INPUT_NODE_RATE = 1000.0     # Hz: rate_hz of the input-trigger cases, at most one sample per ms
INPUT_RATES = (100.0, 1000.0)
ONE_PROCESS_CPU_NOTE = ("whole benchmark process (allocator node, probe and DDS threads): "
                        "time.process_time delta / wall time")
TWO_PROCESSES_CPU_NOTE = "allocator_node process only: utime+stime from /proc/<pid>/stat / wall time"


def probe_rate(rate_hz: float, seconds: float) -> float:
    """The probe's rate: the node's and one wrench more per window, to sweep the phase between the timers."""
    return rate_hz + 1.0 / seconds


def one_process(config: Path, rate_hz: float, seconds: float) -> dict:
    """The node in a background thread of this process, the probe in the main thread."""
    rate = probe_rate(rate_hz, seconds)
    with ros_context() as context, node_in_thread(context, config, rate_hz), probe_in(context, rate) as probe:
        figures = measure(probe, rate_hz, seconds, time.process_time)
    return {"setup": "one process", "rate_hz": rate_hz, "probe_rate_hz": rate, **figures,
            "cpu_note": ONE_PROCESS_CPU_NOTE}


def two_processes(config: Path, rate_hz: float, seconds: float) -> dict:
    """``allocator_node`` as a subprocess, the probe in this process."""
    rate = probe_rate(rate_hz, seconds)
    with node_process(config, rate_hz) as process, ros_context() as context, probe_in(context, rate) as probe:
        figures = measure(probe, rate_hz, seconds, lambda: process_cpu_seconds(process.pid))
    return {"setup": "two processes", "rate_hz": rate_hz, "probe_rate_hz": rate, **figures,
            "cpu_note": TWO_PROCESSES_CPU_NOTE}


def input_trigger(config: Path, input_hz: float, seconds: float) -> dict:
    """``allocator_node`` with ``trigger: input`` at rate_hz INPUT_NODE_RATE as a subprocess, the
    probe here publishing at ``input_hz``: every wrench is allocated on arrival, so the
    publish-to-commands latency has no wait for a tick in it."""
    parameters = ("wrench_timeout:=0.0", "trigger:=input")
    with node_process(config, INPUT_NODE_RATE, parameters=parameters) as process, ros_context() as context, \
            probe_in(context, input_hz) as probe:
        probe.wait_for_input_node()
        figures = measure(probe, input_hz, seconds, lambda: process_cpu_seconds(process.pid))
    return {"setup": "two processes", "trigger": "input", "rate_hz": INPUT_NODE_RATE, "input_hz": input_hz,
            **figures, "cpu_note": TWO_PROCESSES_CPU_NOTE}


def rmw_identifier() -> str:
    """The RMW implementation rclpy uses."""
    with ros_context():
        return rclpy.get_rmw_implementation_identifier()


def print_case(case: dict) -> None:
    """One line per case on stdout."""
    trigger = f"input {case['input_hz']:g} Hz" if case.get("trigger") == "input" else "timer"
    print(f"{case['setup']:>13} {trigger:>16} {case['rate_hz']:6g} Hz: {case['achieved_hz']:8.2f} Hz achieved, "
          f"jitter p99 {case['jitter_ms']['p99']} ms, missed {case['missed_percent']} %, "
          f"tick->receipt p50/p99 {case['tick_to_receipt_ms']['p50']}/{case['tick_to_receipt_ms']['p99']} ms, "
          f"publish->commands p50 {case['publish_to_commands_ms']['p50']} ms, CPU {case['cpu_percent']} %",
          flush=True)


def parse_arguments(argv: list[str] | None) -> argparse.Namespace:
    """The command line."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--config", type=Path, default=ROOT / "config" / "bluerov2_heavy.yaml",
                        help="vehicle params file (default: config/bluerov2_heavy.yaml)")
    parser.add_argument("--rates", type=float, nargs="+", default=[50.0, 200.0, 1000.0],
                        help="node rates [Hz] (default: 50 200 1000)")
    duration = parser.add_mutually_exclusive_group()
    duration.add_argument("--seconds", type=float, default=10.0, help="measuring window per case [s] (default: 10)")
    duration.add_argument("--quick", action="store_true", help=f"smoke run: {QUICK_SECONDS:g} s per case")
    parser.add_argument("--inputs", type=float, nargs="*", default=list(INPUT_RATES),
                        help="input rates [Hz] of the trigger: input cases (default: 100 1000; none: skip them)")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "node.json",
                        help="JSON results (default: bench/results/node.json)")
    arguments = parser.parse_args(argv)
    if arguments.quick:
        arguments.seconds = QUICK_SECONDS
    return arguments


def main(argv: list[str] | None = None) -> int:
    """Run every case, print a line for each and write the JSON."""
    arguments = parse_arguments(argv)
    config = arguments.config.resolve()
    cases = []
    for rate_hz in arguments.rates:
        for setup in (one_process, two_processes):
            cases.append(setup(config, rate_hz, arguments.seconds))
            print_case(cases[-1])
    for input_hz in arguments.inputs:
        cases.append(input_trigger(config, input_hz, arguments.seconds))
        print_case(cases[-1])
    results = {
        "config": str(config.relative_to(ROOT)) if config.is_relative_to(ROOT) else str(config),
        "seconds": arguments.seconds,
        "warm_up_seconds": WARM_UP,
        "gc": "enabled" if gc.isenabled() else "disabled",
        "rmw": rmw_identifier(),
        "cpu_count": os.cpu_count(),
        "cases": cases,
    }
    arguments.out.parent.mkdir(parents=True, exist_ok=True)
    arguments.out.write_text(json.dumps(results, indent=2) + "\n")
    print(f"bench: results written to {arguments.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
