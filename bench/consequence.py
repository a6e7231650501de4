"""What the consequence analysis costs a sample: the node's sample time (allocate and publish,
``AllocationRuntime._sample`` timed by the wall clock around it, GIL waits included) with the
analysis on and off, and what one analysis takes.

``allocator_node`` on the DP vessel (its two redundancy groups) at ``--rate`` Hz runs in this
process, spun by rclpy's EventsExecutor (the node's own) in a thread, while the main thread
sends a wrench that turns slowly in the horizontal plane (an analysis of it solves every group's
programmes, some of them past what a group's loss leaves). Rounds alternate the analysis off
(``consequence.rate`` 0) and on (``--consequence-rate``, from 1 Hz, the analysis' lowest, to
10 Hz, its highest); each figure is over every sample of its kind.

    .venv/bin/python bench/consequence.py [--rate 100] [--consequence-rate 1 10] [--seconds 10] [--rounds 2]
                                          [--out bench/results/consequence.json]
"""

from __future__ import annotations

import os

from allocator_pkg.ros.process import dds_environment, namespace_arguments, run_namespace

os.environ.update(dds_environment())

import argparse
import json
import math
import sys
import threading
import time
from pathlib import Path

import numpy as np
import rclpy
from geometry_msgs.msg import Wrench
from rclpy.context import Context
from rclpy.experimental import EventsExecutor
from rclpy.parameter import Parameter

from allocator_pkg import load_vehicle
from allocator_pkg.capability.consequence import Consequence
from allocator_pkg.ros.node import AllocatorNode

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "config" / "dp_vessel.yaml"
WRENCH_RATE = 10.0          # Hz of the wrench sent
AMPLITUDE = 450e3           # N: past the starboard azimuth alone (420 kN) ahead, within the port one (655 kN)
TURN = 20.0                 # s for the wrench to turn once


def wrench_at(t: float) -> Wrench:
    angle = 2.0 * math.pi * t / TURN
    message = Wrench()
    message.force.x, message.force.y = AMPLITUDE * math.cos(angle), 0.3 * AMPLITUDE * math.sin(angle)
    message.torque.z = 2e6 * math.sin(3.0 * angle)
    return message


def sample_times(rate_hz: float, consequence_rate: float, seconds: float) -> tuple[list[float], int]:
    """The wall time [us] of each sample over ``seconds`` (after one second of warm-up), and how
    many analyses were published."""
    context = Context()
    rclpy.init(context=context, args=["--ros-args", *namespace_arguments(run_namespace())])   # a run of its own
    node = AllocatorNode(context=context, cli_args=["--ros-args", "--params-file", str(CONFIG)],
                         parameter_overrides=[Parameter("rate_hz", value=rate_hz),
                                              Parameter("wrench_timeout", value=0.0),
                                              Parameter("consequence.rate", value=consequence_rate)])
    runtime = node.runtime
    times: list[float] = []
    sample = runtime._sample

    def timed(now: int) -> None:
        start = time.perf_counter_ns()
        sample(now)
        times.append((time.perf_counter_ns() - start) * 1e-3)

    runtime._sample = timed
    probe = rclpy.create_node("consequence_bench", context=context)
    publisher = probe.create_publisher(Wrench, "wrench_command", 10)
    analyses = []
    if consequence_rate > 0.0:
        from allocator_msgs.msg import ConsequenceAnalysis
        probe.create_subscription(ConsequenceAnalysis, "thrust_allocator/consequence", analyses.append, 10)
    executor = EventsExecutor(context=context)
    executor.add_node(node)
    probe_executor = EventsExecutor(context=context)
    probe_executor.add_node(probe)
    stop = threading.Event()

    def spin(spinning: EventsExecutor) -> None:
        while not stop.is_set():
            spinning.spin_once(timeout_sec=0.1)

    threads = [threading.Thread(target=spin, args=(e,), daemon=True) for e in (executor, probe_executor)]
    for thread in threads:
        thread.start()
    start = time.monotonic()
    warm = start + 1.0
    counted = 0
    while (now := time.monotonic()) < warm + seconds:
        publisher.publish(wrench_at(now - start))
        if now >= warm and not counted:
            counted = len(times)
            analyses.clear()
        time.sleep(1.0 / WRENCH_RATE)
    stop.set()
    for thread in threads:
        thread.join()
    node.release()
    executor.shutdown()
    probe_executor.shutdown()
    node.destroy_node()
    probe.destroy_node()
    rclpy.try_shutdown(context=context)
    return times[counted:], len(analyses)


def analysis_times(count: int = 200) -> list[float]:
    """[ms] One analysis of the DP vessel (both groups) at loads along the bench's wrench."""
    vehicle = load_vehicle(CONFIG)
    analysis = Consequence(vehicle)
    out = []
    for k in range(count):
        w = wrench_at(TURN * k / count)
        load = [w.force.x, w.force.y, 0.0, 0.0, 0.0, w.torque.z]
        start = time.perf_counter()
        analysis.utilisation(load)
        out.append((time.perf_counter() - start) * 1e3)
    return out


def figures(values: list[float]) -> dict:
    array = np.asarray(values)
    return {"samples": int(array.size), "median": float(np.median(array)), "p99": float(np.percentile(array, 99)),
            "max": float(array.max())}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rate", type=float, default=100.0, help="the node's rate_hz")
    parser.add_argument("--consequence-rate", type=float, nargs="+", default=[1.0, 10.0])
    parser.add_argument("--seconds", type=float, default=10.0, help="measured per round and case")
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--out", type=Path)
    arguments = parser.parse_args()
    cases = [0.0, *arguments.consequence_rate]
    collected: dict[float, list[float]] = {rate: [] for rate in cases}
    published: dict[float, int] = dict.fromkeys(cases, 0)
    for _ in range(arguments.rounds):
        for rate in cases:
            times, count = sample_times(arguments.rate, rate, arguments.seconds)
            collected[rate] += times
            published[rate] += count
    off = figures(collected[0.0])
    report = {"node_rate_hz": arguments.rate, "seconds": arguments.seconds * arguments.rounds,
              "rounds": arguments.rounds,
              "sample_us_off": off, "analysis_ms": figures(analysis_times()), "on": []}
    print(f"sample time [us], node at {arguments.rate:g} Hz, {arguments.rounds} x {arguments.seconds:g} s per case")
    print(f"  off            median {off['median']:7.1f}  p99 {off['p99']:7.1f}  max {off['max']:8.1f}")
    for rate in arguments.consequence_rate:
        on = figures(collected[rate])
        ratio = {key: on[key] / off[key] for key in ("median", "p99")}
        report["on"].append({"consequence_rate_hz": rate, "sample_us": on, "ratio_to_off": ratio,
                             "analyses_published": published[rate]})
        print(f"  on at {rate:4g} Hz  median {on['median']:7.1f}  p99 {on['p99']:7.1f}  max {on['max']:8.1f}   "
              f"ratio median {ratio['median']:.3f}, p99 {ratio['p99']:.3f}  ({published[rate]} analyses)")
    analysis = report["analysis_ms"]
    print(f"one analysis (both groups) [ms]: median {analysis['median']:.2f}, p99 {analysis['p99']:.2f}, "
          f"max {analysis['max']:.2f}")
    if arguments.out is not None:
        arguments.out.write_text(json.dumps(report, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
