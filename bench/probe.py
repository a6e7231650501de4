"""The node benchmarks' library: a probe that publishes wrenches at a rate and records what comes
back, an rclpy context, the node in a thread of this process or as a child process, and the
figures of one measuring window (``summarise``, ``measure``).

"missed" counts round(interval / period) - 1 for every stamp interval over 1.5 periods
(``figures.MISSED_FACTOR``), so a tick late by more than half a period counts even when the
timer catches up; "lost" counts the periods of the stamps' span without a message. Both are
seen from the probe, so a message dropped on the way counts like a tick the node skipped, and a
skipped tick counts in both; jitter includes the intervals around them. "publish_to_commands_ms"
(to the arrival of the ThrusterCommands of the sample whose status echoes the wrench) times
only the wrenches the node used ("matched" of "published"): one replaced by a newer one before
the node's tick never appears in a status.
"""

import math
import shlex
import sys
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import rclpy
from figures import MISSED_FACTOR, percentiles
from geometry_msgs.msg import Wrench
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.timer import Timer

from allocator_msgs.msg import AllocationStatus, ThrusterCommands
from allocator_pkg.ros.node import AllocatorNode
from allocator_pkg.ros.process import ChildProcess, child_process, namespace_arguments, node_command, run_namespace

RUN = run_namespace()
"""The namespace of this benchmark process's nodes, the probes' and the node processes' (``/clock``
and ``/diagnostics`` in it too): benchmarks beside each other, or beside any other run, never
take each other's messages."""

WARM_UP = 1.0                # s after the first wrench, excluded from the window
DRAIN = 0.2                  # s spun after the window for answers to its last wrenches
START_TIMEOUT = 30.0         # s for the node to appear and answer

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
    """A fresh rclpy context, its nodes in this benchmark's namespace (``RUN``), shut down on exit."""
    context = Context()
    rclpy.init(context=context, args=["--ros-args", *namespace_arguments(RUN)])
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
def reported_process(command: list[str], output: Path | None = None) -> Iterator[ChildProcess]:
    """``command`` as a child process (``allocator_pkg.ros.process.child_process``: its output in
    the file ``output``, a temporary one by default; stopped with SIGINT, killed if it hangs, and
    reaped on exit); its exit code on stderr when it is not 0."""
    with child_process(command, output) as process:
        try:
            yield process
        finally:
            if process.stop() != 0:
                print(f"bench: {shlex.join(command)} exited with {process.returncode}", file=sys.stderr)


@contextmanager
def node_process(config: Path, rate_hz: float, output: Path | None = None,
                 parameters: tuple[str, ...] = ("wrench_timeout:=0.0",)) -> Iterator[ChildProcess]:
    """``allocator_node`` as a child process (``reported_process``) in this benchmark's namespace
    (``RUN``) with ``rate_hz`` and ``parameters`` (``name:=value``)."""
    with reported_process(node_command(config, *namespace_arguments(RUN),
                                       parameters=(f"rate_hz:={float(rate_hz)!r}", *parameters)), output) as process:
        yield process


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
