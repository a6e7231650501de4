"""Benchmark of the ROS node ``allocator_node``: rate, jitter, latency and CPU over DDS.

For each rate, the node runs in two set-ups: "one process" (AllocatorNode spun by its own
executor in a background thread, the probe in the main thread, one rclpy context) and "two
processes" (``allocator_node`` as a subprocess, the probe here). The probe publishes a slowly
varying wrench at about the node's rate and times the ThrusterCommands and AllocationStatus that
come back. After a warm-up, one measuring window per case gives the achieved rate, the period
jitter from the header stamps, missed periods, the tick-to-receipt and publish-to-commands
latencies and the node's CPU use. Results are written as JSON.

"missed" counts round(interval / period) - 1 for every stamp interval over 1.5 periods, so a
tick late by more than half a period counts even when the timer catches up; "lost" counts the
periods of the stamps' span without a message. Both are seen from the probe, so a message
dropped on the way counts like a tick the node skipped, and a skipped tick counts in both;
jitter includes the intervals around them. "publish_to_commands_ms" (to the arrival of the
ThrusterCommands of the sample whose status echoes the wrench) times only the wrenches the
node used ("matched" of "published"): one replaced by a newer one before the node's tick
never appears in a status. It includes the
wait for the node's next tick, which depends on the phase of the probe's timer against the
node's: at exactly the node's rate that phase would stay where the start left it, so the probe
publishes one wrench more per window ("probe_rate_hz" = rate + 1 / seconds) and the phase
sweeps one whole period over the window.

The "input trigger" cases run ``allocator_node`` with ``trigger: input`` and rate_hz
1000 as a subprocess and publish at 100 Hz and 1 kHz: every wrench is allocated on arrival,
so "publish to commands" has no wait for a tick in it.

    .venv/bin/python bench/node.py [--config config/bluerov2_heavy.yaml] [--rates 50 200 1000]
                                   [--inputs 100 1000]
                                   [--seconds 10 | --quick] [--out bench/results/node.json]
"""

import os

os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
os.environ.setdefault("ROS_DOMAIN_ID", "42")

import argparse
import contextlib
import gc
import json
import math
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO

import numpy as np
import rclpy
from geometry_msgs.msg import Wrench
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.timer import Timer

from allocator_msgs.msg import AllocationStatus, ThrusterCommands
from allocator_pkg.ros.node import AllocatorNode

ROOT = Path(__file__).resolve().parents[1]
NODE_BINARY = Path(sys.executable).parent / "allocator_node"
WARM_UP = 1.0                # s after the first wrench, excluded from the window
DRAIN = 0.2                  # s spun after the window for answers to its last wrenches
START_TIMEOUT = 30.0         # s for the node to appear and answer
STOP_TIMEOUT = 10.0          # s for allocator_node to exit after SIGINT
MISSED_FACTOR = 1.5          # a stamp interval above this many periods has missed periods
QUICK_SECONDS = 2.0
INPUT_NODE_RATE = 1000.0     # Hz: rate_hz of the input-trigger cases, at most one sample per ms
INPUT_RATES = (100.0, 1000.0)
ONE_PROCESS_CPU_NOTE = ("whole benchmark process (allocator node, probe and DDS threads): "
                        "time.process_time delta / wall time")
TWO_PROCESSES_CPU_NOTE = "allocator_node process only: utime+stime from /proc/<pid>/stat / wall time"

WrenchKey = tuple[float, float, float, float, float, float]


def wrench_at(t: float) -> Wrench:
    """A slowly varying, realistic BlueROV2-sized wrench at time ``t`` [s]."""
    wrench = Wrench()
    wrench.force.x = 20.0 * math.sin(t)
    wrench.force.y = 10.0 * math.cos(0.7 * t)
    wrench.force.z = 5.0 * math.sin(0.3 * t)
    wrench.torque.x = 0.5 * math.sin(0.2 * t)
    wrench.torque.y = 0.5 * math.cos(0.25 * t)
    wrench.torque.z = 2.0 * math.sin(0.5 * t)
    return wrench


def stamp_seconds(message) -> float:
    """A message's header stamp [s]."""
    return message.header.stamp.sec + message.header.stamp.nanosec * 1e-9


def wrench_key(wrench: Wrench) -> WrenchKey:
    """The exact values of a wrench, to match a published wrench with the one the node used."""
    return (wrench.force.x, wrench.force.y, wrench.force.z, wrench.torque.x, wrench.torque.y, wrench.torque.z)


class Probe:
    """Publishes the wrench from its own timer at ``rate_hz`` and records what comes back."""

    def __init__(self, context: Context, rate_hz: float) -> None:
        self.period = 1.0 / rate_hz
        self.node = rclpy.create_node("allocator_bench_probe", context=context)
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)
        qos = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)
        self.wrench = self.node.create_publisher(Wrench, "wrench_command", qos)
        self.node.create_subscription(ThrusterCommands, "thruster_commands", self._on_commands, qos)
        self.node.create_subscription(AllocationStatus, "allocation_status", self._on_status, qos)
        self.commands: list[tuple[float, float]] = []      # (receipt, header stamp) [s]
        self.solves: list[tuple[float, float]] = []        # (receipt, solve time) [s]
        self.published: list[float] = []                   # wrench publish times [s]
        self.latencies: list[tuple[float, float]] = []     # (wrench published, its status received) [s]
        self._pending: dict[WrenchKey, float] = {}
        self._sequence = 0
        self._timer: Timer | None = None

    def _on_commands(self, message: ThrusterCommands) -> None:
        """Record the receipt time and header stamp of a command."""
        self.commands.append((time.time(), stamp_seconds(message)))

    def _on_status(self, message: AllocationStatus) -> None:
        """Record the solve time; for the first status that echoes a published wrench, time
        the arrival of the commands of the same sample (published just before the status)."""
        now = time.time()
        self.solves.append((now, message.solve_time))
        published = self._pending.pop(wrench_key(message.requested), None)
        if published is not None:
            stamp = stamp_seconds(message)
            receipt, command_stamp = self.commands[-1] if self.commands else (now, None)
            self.latencies.append((published, receipt if command_stamp == stamp else now))

    def _publish(self) -> None:
        """Publish the next wrench of the sequence and remember when."""
        wrench = wrench_at(self._sequence * self.period)
        self._sequence += 1
        now = time.time()
        self.published.append(now)
        self._pending[wrench_key(wrench)] = now
        self.wrench.publish(wrench)

    def start_publishing(self) -> None:
        """Start the wrench timer."""
        self._timer = self.node.create_timer(self.period, self._publish)

    def stop_publishing(self) -> None:
        """Stop the wrench timer."""
        self._timer.cancel()

    def spin_for(self, seconds: float) -> None:
        """Spin the probe for ``seconds`` of wall time."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=min(0.05, max(0.0, deadline - time.monotonic())))

    def wait_for_node(self) -> None:
        """Spin until the node subscribes to the wrench and has published a command."""
        deadline = time.monotonic() + START_TIMEOUT
        while self.wrench.get_subscription_count() == 0 or not self.commands:
            if time.monotonic() > deadline:
                raise TimeoutError(f"allocator node did not answer within {START_TIMEOUT:g} s")
            self.executor.spin_once(timeout_sec=0.05)

    def wait_for_input_node(self) -> None:
        """With the input trigger nothing comes before a wrench: send one until commands answer."""
        deadline = time.monotonic() + START_TIMEOUT
        while not self.commands:
            if time.monotonic() > deadline:
                raise TimeoutError(f"allocator node did not answer within {START_TIMEOUT:g} s")
            if self.wrench.get_subscription_count():
                self.wrench.publish(Wrench())
            self.executor.spin_once(timeout_sec=0.05)

    def close(self) -> None:
        """Shut the executor down and destroy the node."""
        self.executor.shutdown()
        self.node.destroy_node()


@contextmanager
def ros_context() -> Iterator[Context]:
    """A fresh rclpy context, shut down on exit."""
    context = Context()
    rclpy.init(context=context)
    try:
        yield context
    finally:
        rclpy.try_shutdown(context=context)


@contextmanager
def probe_in(context: Context, rate_hz: float) -> Iterator[Probe]:
    """A probe in ``context``, closed on exit."""
    probe = Probe(context, rate_hz)
    try:
        yield probe
    finally:
        probe.close()


@contextmanager
def node_in_thread(context: Context, config: Path, rate_hz: float) -> Iterator[AllocatorNode]:
    """AllocatorNode in ``context``, spun by its own SingleThreadedExecutor in a background thread."""
    node = AllocatorNode(context=context, cli_args=["--ros-args", "--params-file", str(config)],
                         parameter_overrides=[Parameter("rate_hz", value=float(rate_hz)),
                                              Parameter("wrench_timeout", value=0.0)])
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    stop = threading.Event()

    def spin() -> None:
        while not stop.is_set():
            executor.spin_once(timeout_sec=0.1)

    thread = threading.Thread(target=spin, name="allocator_node", daemon=True)
    thread.start()
    try:
        yield node
    finally:
        stop.set()
        thread.join()
        executor.shutdown()
        node.destroy_node()


@contextmanager
def node_process(config: Path, rate_hz: float, output: IO[str] | None = None,
                 parameters: tuple[str, ...] = ("wrench_timeout:=0.0",)) -> Iterator[subprocess.Popen]:
    """``allocator_node`` as a subprocess with ``rate_hz`` and ``parameters`` (``name:=value``);
    stopped with SIGINT (killed if it hangs) and reaped on exit. Its output goes to the file
    ``output`` (a temporary one by default: a pipe nobody reads would block the node once
    full); an error raised inside gets that output as a note."""
    with contextlib.ExitStack() as stack:
        log = output or stack.enter_context(tempfile.TemporaryFile("w+"))
        process = subprocess.Popen(
            [str(NODE_BINARY), "--ros-args", "--params-file", str(config), "-p", f"rate_hz:={float(rate_hz)!r}",
             *(argument for parameter in parameters for argument in ("-p", parameter))],
            env=os.environ, stdout=log, stderr=subprocess.STDOUT, text=True)
        try:
            yield process
        except Exception as error:
            stop_process(process)
            if log.readable() and log.seekable():
                log.seek(0)
                error.add_note(f"allocator_node output:\n{log.read()}")
            raise
        finally:
            stop_process(process)


def stop_process(process: subprocess.Popen) -> None:
    """SIGINT, wait, kill if needed (no-op if it has already been reaped)."""
    if process.returncode is not None:
        return
    process.send_signal(signal.SIGINT)
    try:
        process.wait(timeout=STOP_TIMEOUT)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()
    if process.returncode != 0:
        print(f"bench: allocator_node exited with {process.returncode}", file=sys.stderr)


def process_cpu_seconds(pid: int) -> float:
    """User plus system CPU time [s] of process ``pid``, all threads, from /proc/<pid>/stat."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")   # utime, stime (fields 14, 15)


def percentiles(values: list[float], *quantiles: float, maximum: bool = False) -> dict[str, float | None]:
    """The given percentiles (and the maximum) of ``values``, in the same unit; None without values."""
    keys = [f"p{q:g}" for q in quantiles] + (["max"] if maximum else [])
    if not values:
        return dict.fromkeys(keys)
    figures = [*np.percentile(values, quantiles), max(values)] if maximum else np.percentile(values, quantiles)
    return {key: round(float(value), 4) for key, value in zip(keys, figures)}


def summarise(probe: Probe, rate_hz: float, window: tuple[float, float], cpu_percent: float) -> dict:
    """The figures of one case from what the probe recorded; ``window`` is (start, end) wall time [s]."""
    start, end = window
    period = 1.0 / rate_hz
    received = [(receipt, stamp) for receipt, stamp in probe.commands if start <= receipt < end]
    receipts = np.array([receipt for receipt, _ in received])
    stamps = np.array([stamp for _, stamp in received])
    intervals = np.diff(stamps)
    if len(received) < 2:
        expected = max(1, round((end - start) / period))
        missed = lost = expected - len(received)
    else:
        late = intervals[intervals > MISSED_FACTOR * period]
        missed = int(np.sum(np.round(late / period) - 1))
        expected = round(float(np.sum(intervals)) / period)
        lost = expected - len(intervals)
    latencies = [receipt - published for published, receipt in probe.latencies if start <= published < end]
    solves = [solve for receipt, solve in probe.solves if start <= receipt < end]
    return {
        "achieved_hz": round(len(received) / (end - start), 2),
        "jitter_ms": percentiles(list(np.abs(intervals - period) * 1e3), 50, 99),
        "missed": missed,
        "missed_percent": round(100.0 * missed / expected, 2),
        "lost": lost,
        "lost_percent": round(100.0 * lost / expected, 2),
        "tick_to_receipt_ms": percentiles(list((receipts - stamps) * 1e3), 50, 90, 99, maximum=True),
        "publish_to_commands_ms": {
            **percentiles([latency * 1e3 for latency in latencies], 50, 99),
            "matched": len(latencies),
            "published": sum(start <= published < end for published in probe.published),
        },
        "solve_ms": percentiles([solve * 1e3 for solve in solves], 50, 99),
        "cpu_percent": round(cpu_percent, 1),
    }


def measure(probe: Probe, rate_hz: float, seconds: float, cpu_seconds: Callable[[], float]) -> dict:
    """Wait for the node, publish, warm up, then measure one window of ``seconds``.
    ``cpu_seconds`` gives the cumulative CPU time [s] whose share of the window is reported."""
    probe.wait_for_node()
    probe.start_publishing()
    probe.spin_for(WARM_UP)
    start, cpu_start, clock_start = time.time(), cpu_seconds(), time.perf_counter()
    probe.spin_for(seconds)
    end, cpu_end, clock_end = time.time(), cpu_seconds(), time.perf_counter()
    probe.stop_publishing()
    probe.spin_for(DRAIN)
    cpu_percent = 100.0 * (cpu_end - cpu_start) / (clock_end - clock_start)
    return summarise(probe, rate_hz, (start, end), cpu_percent)


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
