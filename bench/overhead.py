"""The node's own cost, as a ratio to a bare rclpy node measured in the same run.

Every node runs in a process of its own; the probe here drives it over Fast DDS on loopback.

Input-driven cases: a WrenchStamped on ``wrench_command`` at each input rate (100 and 500 Hz),
answered by ``bench/bare.py echo`` (one message back at once) and by ``allocator_node`` with
``trigger: input`` and ``wrench_type: wrench_stamped`` on the BlueROV2 Heavy and the DP vessel
(``rate_hz`` 1000, so that every wrench is allocated on arrival), AllocationStatus published
every sample; and the DP vessel again with ``status_rate_hz`` 50. For each: the CPU the process
spends per answered sample (utime + stime from /proc/<pid>/stat over the window, divided by the
answers received), its share of a core, publish -> answer latency p50/p99 (the echo's
message; the allocator's ThrusterCommands of the sample that used that wrench), and for the
allocator the p50 of ``allocate`` in the node (AllocationStatus.solve_time, its wall time) with
its share of the CPU per sample, and the CPU per sample beyond ``allocate`` (the CPU per sample
less ``allocate``'s mean wall time in the window): what the node spends on everything but the
maths, against the bare node's CPU per sample.

Timer cases: ``allocator_node`` with ``trigger: timer`` at 50 and 500 Hz (no wrench input, the
watchdog off) against ``bench/bare.py timer`` at the same rate: CPU per tick.

Cases run in rounds, alternating the nodes of a rate, so that the machine's drift hits all of
them; each figure is the median over rounds, and every ratio is taken against the bare node of
the same rate. Prints a table and writes JSON.

    .venv/bin/python bench/overhead.py [--seconds 10] [--rounds 3] [--out bench/results/overhead.json]
"""

import os

from allocator_pkg.ros.process import dds_environment

os.environ.update(dds_environment())

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
import rclpy
from figures import process_cpu_seconds
from geometry_msgs.msg import WrenchStamped
from probe import RUN, reported_process, ros_context
from rclpy.executors import SingleThreadedExecutor
from rclpy.qos import QoSProfile, ReliabilityPolicy

from allocator_msgs.msg import AllocationStatus, ThrusterCommands
from allocator_pkg.ros.process import namespace_arguments, node_command

ROOT = Path(__file__).resolve().parents[1]
VEHICLES = {"bluerov2_heavy": ROOT / "config" / "bluerov2_heavy.yaml", "dp_vessel": ROOT / "config" / "dp_vessel.yaml"}
AMPLITUDE = {"bluerov2_heavy": 40.0, "dp_vessel": 2.0e5}
"""[N] The horizontal force the probe asks of each vehicle: about 40 % of its authority."""
INPUT_RATES = (100.0, 500.0)
TIMER_RATES = (50.0, 500.0)
STATUS_RATE = 50.0
"""[Hz] ``status_rate_hz`` of the DP vessel's extra rows: its status at most this often."""
WARM_UP = 2.0             # s of input before the window (discovery settles, caches fill)
START_TIMEOUT = 30.0      # s for a node to answer
TARGET = 1.2
"""The target: CPU per sample and publish -> commands p50 at most this many times the bare node's."""


def allocator_command(config: Path, *parameters: str) -> list[str]:
    """``allocator_node`` on ``config`` in this benchmark's namespace."""
    return node_command(config, *namespace_arguments(RUN), parameters=("wrench_timeout:=0.0", *parameters))


def bare_command(*arguments: str) -> list[str]:
    """``bench/bare.py`` with ``arguments``, in this benchmark's namespace."""
    return [sys.executable, str(ROOT / "bench" / "bare.py"), *arguments, "--ros-args", *namespace_arguments(RUN)]


TAG = 1e-6
"""[N m] The roll moment that numbers each wrench (k * TAG for the k-th): too small to matter to
any allocation, exact through the node's frame conversion (roll is the same in FRD and FLU)."""
PERIOD = 5.0
"""[s] Period of the slowly turning request the probe sends."""


class Probe:
    """Publishes numbered wrenches, a request of ``amplitude`` turning slowly in the horizontal
    plane, and times the answers: the echo's, or the allocator's commands of the sample whose
    status carries the number."""

    def __init__(self, context, allocator: bool, amplitude: float = 0.0):
        self.node = rclpy.create_node("overhead_probe", context=context)
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)
        self.wrench = self.node.create_publisher(WrenchStamped, "wrench_command",
                                                 QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT))
        qos = QoSProfile(depth=100)
        self.published: dict[int, float] = {}
        self.answers: list[tuple[float, float]] = []      # (receipt, latency) [s]
        self.allocate_times: list[float] = []              # [s] AllocationStatus.solve_time: allocate in the node
        self.received = 0
        self._commands: tuple[float, object] | None = None
        if allocator:
            self.node.create_subscription(ThrusterCommands, "thruster_commands", self._on_commands, qos)
            self.node.create_subscription(AllocationStatus, "allocation_status", self._on_status, qos)
        else:
            self.node.create_subscription(WrenchStamped, "echo", self._on_echo, qos)
        self.message = WrenchStamped()
        self.message.header.frame_id = "base_link"
        self.amplitude = amplitude
        self.sequence = 0

    def _answer(self, tag: float, receipt: float) -> None:
        published = self.published.pop(round(tag / TAG), None)
        if published is not None:
            self.answers.append((receipt, receipt - published))

    def _on_echo(self, message: WrenchStamped) -> None:
        self.received += 1
        self._answer(message.wrench.torque.x, time.monotonic())

    def _on_commands(self, message: ThrusterCommands) -> None:
        self.received += 1
        self._commands = (time.monotonic(), message.header.stamp)

    def _on_status(self, message: AllocationStatus) -> None:
        receipt = time.monotonic()
        self.allocate_times.append(message.solve_time)
        if self._commands is not None and self._commands[1] == message.header.stamp:
            receipt = self._commands[0]
        self._answer(message.requested.torque.x, receipt)

    def publish(self) -> None:
        self.sequence += 1
        now = time.monotonic()
        wrench = self.message.wrench
        angle = 2.0 * math.pi * now / PERIOD
        wrench.force.x, wrench.force.y = self.amplitude * math.cos(angle), self.amplitude * math.sin(angle)
        wrench.torque.x = self.sequence * TAG
        self.published[self.sequence] = now
        self.wrench.publish(self.message)

    def drive(self, rate_hz: float, seconds: float) -> None:
        """Publish at ``rate_hz`` for ``seconds``, deadlines by index, spinning in between."""
        start = time.monotonic()
        for k in range(round(rate_hz * seconds)):
            while (now := time.monotonic()) < start + k / rate_hz:
                self.executor.spin_once(timeout_sec=max(0.0, start + k / rate_hz - now))
            self.publish()
        self.spin(0.2)

    def spin(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while (now := time.monotonic()) < end:
            self.executor.spin_once(timeout_sec=end - now)

    def wait(self, input_driven: bool) -> None:
        """Until the node answers (a wrench, or its timer's first message)."""
        end = time.monotonic() + START_TIMEOUT
        while not self.received:
            if time.monotonic() > end:
                raise TimeoutError("the node under test did not answer")
            if input_driven and self.wrench.get_subscription_count():
                self.publish()
            self.spin(0.05)

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()


def measure(command: list[str], allocator: bool, rate_hz: float, seconds: float, input_driven: bool,
            amplitude: float = 0.0) -> dict:
    """One node process: CPU per answer and latency over one window after the warm-up."""
    with reported_process(command) as child, ros_context() as context:
        probe = Probe(context, allocator, amplitude)
        try:
            probe.wait(input_driven)
            if input_driven:
                probe.drive(rate_hz, WARM_UP)
            else:
                probe.spin(WARM_UP)
            probe.answers.clear()
            probe.allocate_times.clear()
            received, cpu, clock = probe.received, process_cpu_seconds(child.pid), time.monotonic()
            if input_driven:
                probe.drive(rate_hz, seconds)
            else:
                probe.spin(seconds)
            received, cpu, clock = (probe.received - received, process_cpu_seconds(child.pid) - cpu,
                                    time.monotonic() - clock)
        finally:
            probe.close()
    samples = received if input_driven else rate_hz * clock
    return window_figures(cpu, clock, samples, received, [latency for _, latency in probe.answers],
                          probe.allocate_times)


def window_figures(cpu: float, clock: float, samples: float, answered: int, latencies: list[float],
                   allocate_times: list[float]) -> dict:
    """One window's figures from its CPU seconds, wall seconds, samples, answers, the answers'
    latencies [s] and ``allocate``'s wall times [s] (empty for a bare node)."""
    latencies_ms = [latency * 1e3 for latency in latencies]
    allocate_ms = [seconds * 1e3 for seconds in allocate_times]
    cpu_per_sample = 1e3 * cpu / max(samples, 1)
    return {"cpu_ms_per_sample": cpu_per_sample, "cpu_percent": 100.0 * cpu / clock,
            "answered": answered,
            "allocate_ms_p50": float(np.percentile(allocate_ms, 50)) if allocate_ms else None,
            "beyond_allocate_ms": cpu_per_sample - float(np.mean(allocate_ms)) if allocate_ms else None,
            "latency_ms_p50": float(np.percentile(latencies_ms, 50)) if latencies_ms else None,
            "latency_ms_p99": float(np.percentile(latencies_ms, 99)) if latencies_ms else None}


def cases() -> list[tuple[str, str, float, list[str], bool, bool, float]]:
    """(kind, name, rate, command, allocator, input-driven, amplitude) of every case."""
    found = []
    for rate in INPUT_RATES:
        found.append(("input", "bare echo", rate, bare_command("echo"), False, True, 0.0))
        inputs = [(name, name, ()) for name in VEHICLES]
        inputs.append((f"dp_vessel, status {STATUS_RATE:g} Hz", "dp_vessel", (f"status_rate_hz:={STATUS_RATE}",)))
        for label, name, extra in inputs:
            found.append(("input", label, rate, allocator_command(VEHICLES[name], "trigger:=input", "rate_hz:=1000.0",
                                                                  "wrench_type:=wrench_stamped", *extra), True, True,
                          AMPLITUDE[name]))
    for rate in TIMER_RATES:
        found.append(("timer", "bare timer", rate, bare_command("timer", str(rate)), False, False, 0.0))
        found.append(("timer", "bluerov2_heavy", rate, allocator_command(VEHICLES["bluerov2_heavy"], "trigger:=timer",
                                                                          f"rate_hz:={rate}"), True, False, 0.0))
    return found


def median(values: list[float | None]) -> float | None:
    values = [v for v in values if v is not None]
    return float(np.median(values)) if values else None


def summarise(rounds: list[dict]) -> list[dict]:
    """Medians over rounds, and each allocator case's ratios to the bare node of its rate."""
    rows = []
    for key in rounds[0]:
        kind, name, rate = key.split("|")
        figures = {field: median([r[key].get(field) for r in rounds])
                   for field in ("cpu_ms_per_sample", "cpu_percent", "latency_ms_p50", "latency_ms_p99",
                                 "allocate_ms_p50", "beyond_allocate_ms")}
        rows.append({"kind": kind, "node": name, "rate_hz": float(rate), **figures,
                     "rounds": [r[key]["cpu_ms_per_sample"] for r in rounds]})
    for row in rows:
        bare = next(r for r in rows if r["kind"] == row["kind"] and r["rate_hz"] == row["rate_hz"]
                    and r["node"].startswith("bare"))
        row["cpu_ratio"] = row["cpu_ms_per_sample"] / bare["cpu_ms_per_sample"]
        if row["latency_ms_p50"] is not None and bare["latency_ms_p50"]:
            row["latency_ratio"] = row["latency_ms_p50"] / bare["latency_ms_p50"]
        if row["allocate_ms_p50"] is not None:
            row["allocate_share"] = row["allocate_ms_p50"] / row["cpu_ms_per_sample"]
        if row["beyond_allocate_ms"] is not None:
            row["beyond_allocate_ratio"] = row["beyond_allocate_ms"] / bare["cpu_ms_per_sample"]
    return rows


def print_rows(rows: list[dict]) -> None:
    print(f"{'case':>6} {'node':>24} {'rate':>6} {'CPU/sample':>11} {'core':>6} {'p50':>7} {'p99':>7} "
          f"{'CPU x':>6} {'p50 x':>6} {'allocate':>9} {'beyond x':>8}")
    for row in rows:
        p50 = "" if row["latency_ms_p50"] is None else f"{row['latency_ms_p50']:.3f}"
        p99 = "" if row["latency_ms_p99"] is None else f"{row['latency_ms_p99']:.3f}"
        allocate = "" if row["allocate_ms_p50"] is None else \
            f"{row['allocate_ms_p50']:.3f} ({100 * row['allocate_share']:.0f} %)"
        print(f"{row['kind']:>6} {row['node']:>24} {row['rate_hz']:6g} {row['cpu_ms_per_sample']:9.3f}ms "
              f"{row['cpu_percent']:5.1f}% {p50:>7} {p99:>7} {row['cpu_ratio']:6.2f} "
              f"{row.get('latency_ratio', float('nan')):6.2f} {allocate:>9} "
              f"{row.get('beyond_allocate_ratio', float('nan')):8.2f}", flush=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=10.0, help="measuring window per case [s] (default: 10)")
    parser.add_argument("--rounds", type=int, default=3, help="rounds over every case (default: 3)")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "overhead.json")
    arguments = parser.parse_args(argv)
    rounds = []
    for _ in range(arguments.rounds):
        figures = {}
        for kind, name, rate, command, allocator, input_driven, amplitude in cases():
            figures[f"{kind}|{name}|{rate}"] = measure(command, allocator, rate, arguments.seconds, input_driven,
                                                       amplitude)
        rounds.append(figures)
    rows = summarise(rounds)
    print_rows(rows)
    result = {"seconds": arguments.seconds, "rounds": arguments.rounds, "target_ratio": TARGET,
              "cpu_count": os.cpu_count(), "rows": rows}
    arguments.out.parent.mkdir(parents=True, exist_ok=True)
    arguments.out.write_text(json.dumps(result, indent=1) + "\n")
    print(f"bench: results written to {arguments.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
