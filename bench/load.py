"""make load: ``allocator_node`` under load. Another process floods wrench_command at 10 kHz and
a third keeps one core busy, for a minute per trigger (``timer`` and ``input``); this process
listens. Passes when the node keeps rate_hz within 5 %, nothing it publishes is older than two
periods when it arrives, the wrench it uses does not age over the run (no queue grows) and
its resident memory grows by less than 5 MB after the warm-up.

The flood writes its own send time (modulo 10 s) into force.x (0 to 10 N, within the
vehicle's reach), so that the status of every sample tells how old the wrench it used was.

    .venv/bin/python bench/load.py [--seconds 60] [--config config/bluerov2_heavy.yaml] [--out bench/results/load.json]
"""

import os

from allocator_pkg.ros.process import dds_environment, namespace_arguments

os.environ.update(dds_environment())

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import rclpy
from figures import memory_mb, percentiles, process_cpu_seconds
from geometry_msgs.msg import Wrench
from probe import RUN, node_process, ros_context, stamp_seconds
from rclpy.executors import SingleThreadedExecutor
from rclpy.qos import QoSProfile, ReliabilityPolicy

from allocator_msgs.msg import AllocationStatus, ThrusterCommands
from allocator_pkg import load_vehicle

ROOT = Path(__file__).resolve().parents[1]
FLOOD_HZ = 10000.0
WARM_UP = 10.0               # s excluded from every figure
RSS_PERIOD = 5.0             # s between samples of the node's memory
RATE_TOLERANCE = 0.05
STALE_PERIODS = 2.0
RSS_LIMIT_MB = 5.0
WRAP = 10.0                  # s: force.x carries the send time modulo this
TRIGGERS = ("timer", "input")


def flood(rate_hz: float, seconds: float, namespace: str) -> int:
    """The flooding process: publish wrenches at ``rate_hz`` for ``seconds`` in ``namespace`` (the
    node's); print how many."""
    rclpy.init(args=["--ros-args", *namespace_arguments(namespace)])
    node = rclpy.create_node("load_flood")
    publisher = node.create_publisher(Wrench, "wrench_command", QoSProfile(depth=1,
                                                                           reliability=ReliabilityPolicy.BEST_EFFORT))
    wrench = Wrench()
    wrench.torque.z = 1.0
    period = 1.0 / rate_hz
    start = time.monotonic()
    sent = 0
    while (now := time.monotonic()) < start + seconds:
        next_time = start + sent * period           # by index: no drift from adding the period
        if now < next_time:
            time.sleep(min(next_time - now, 0.001))
            continue
        wrench.force.x = time.time() % WRAP
        publisher.publish(wrench)
        sent += 1
    print(json.dumps({"sent": sent, "achieved_hz": sent / seconds}))
    node.destroy_node()
    rclpy.try_shutdown()
    return 0


class Listener:
    """Receipt times and stamps of the node's commands; stamp and wrench age of its statuses."""

    def __init__(self, context) -> None:
        self.node = rclpy.create_node("load_listener", context=context)
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)
        qos = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)
        self.commands: list[tuple[float, float]] = []
        self.ages: list[tuple[float, float]] = []
        self.node.create_subscription(ThrusterCommands, "thruster_commands",
                                      lambda m: self.commands.append((time.time(), stamp_seconds(m))), qos)
        self.node.create_subscription(AllocationStatus, "allocation_status", self._on_status, qos)

    def _on_status(self, message: AllocationStatus) -> None:
        stamp = stamp_seconds(message)
        if message.solver_status.startswith("stale") or message.requested.force.x == 0.0:
            return
        self.ages.append((stamp, (stamp - message.requested.force.x) % WRAP))

    def spin_for(self, seconds: float) -> None:
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.01)

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()


def case(config: Path, trigger: str, rate_hz: float, seconds: float, log: Path) -> dict:
    """One trigger under the flood and the busy core."""
    period = 1.0 / rate_hz
    total = WARM_UP + seconds
    memory: list[tuple[float, float]] = []
    with node_process(config, rate_hz, output=log, parameters=("wrench_timeout:=0.5", f"trigger:={trigger}")) \
            as process, ros_context() as context:
        listener = Listener(context)
        busy = subprocess.Popen([sys.executable, "-c", "while True: pass"])
        flooder = subprocess.Popen([sys.executable, __file__, "--flood", str(FLOOD_HZ), "--seconds", str(total + 2.0),
                                    "--namespace", RUN], stdout=subprocess.PIPE, text=True)
        try:
            begin = time.monotonic()
            listener.spin_for(WARM_UP)
            start, cpu_start = time.time(), process_cpu_seconds(process.pid)
            while time.monotonic() < begin + total:
                memory.append((time.monotonic() - begin, memory_mb(process.pid)["VmRSS"]))
                listener.spin_for(RSS_PERIOD)
            end, cpu_end = time.time(), process_cpu_seconds(process.pid)
            flood_figures = json.loads(flooder.communicate(timeout=30)[0])
        finally:
            for child in (busy, flooder):
                if child.poll() is None:
                    child.kill()
                    child.wait()
            listener.close()
    received = [(receipt, stamp) for receipt, stamp in listener.commands if start <= receipt < end]
    stamps = np.array([stamp for _, stamp in received])
    output_age = [(receipt - stamp) * 1e3 for receipt, stamp in received]
    ages = [age * 1e3 for stamp, age in listener.ages if start <= stamp < end]
    fifth = max(1, len(ages) // 5)
    achieved = (len(stamps) - 1) / float(stamps[-1] - stamps[0]) if len(stamps) > 1 else 0.0
    rss = [mb for t, mb in memory if t >= WARM_UP]
    result = {
        "trigger": trigger, "rate_hz": rate_hz, "achieved_hz": round(achieved, 2),
        "output_age_ms": percentiles(output_age, 50, 99, maximum=True),
        "wrench_age_first_ms": percentiles(ages[:fifth], 50, 99, maximum=True),
        "wrench_age_last_ms": percentiles(ages[-fifth:], 50, 99, maximum=True),
        "rss_growth_mb": round(rss[-1] - rss[0], 2) if len(rss) > 1 else 0.0,
        "cpu_percent": round(100.0 * (cpu_end - cpu_start) / (end - start), 1),
        "flood_achieved_hz": round(flood_figures["achieved_hz"], 1),
    }
    failures = []
    if abs(achieved - rate_hz) > RATE_TOLERANCE * rate_hz:
        failures.append(f"{achieved:.1f} Hz, not within {100 * RATE_TOLERANCE:g} % of {rate_hz:g}")
    if output_age and max(output_age) > STALE_PERIODS * period * 1e3:
        failures.append(f"an output {max(output_age):.1f} ms old on arrival (> {STALE_PERIODS:g} periods)")
    first, last = result["wrench_age_first_ms"]["p99"], result["wrench_age_last_ms"]["p99"]
    if first is not None and last is not None and last > first + period * 1e3:
        failures.append(f"the wrench used aged from {first:.1f} to {last:.1f} ms (p99): a queue grows")
    if result["rss_growth_mb"] >= RSS_LIMIT_MB:
        failures.append(f"RSS grew {result['rss_growth_mb']} MB")
    return {**result, "failures": failures}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="measured seconds per trigger (default: 60)")
    parser.add_argument("--config", type=Path, default=ROOT / "config" / "bluerov2_heavy.yaml")
    parser.add_argument("--triggers", nargs="+", default=list(TRIGGERS), choices=TRIGGERS)
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "load.json")
    parser.add_argument("--flood", type=float, help=argparse.SUPPRESS)
    parser.add_argument("--namespace", default=RUN, help=argparse.SUPPRESS)
    arguments = parser.parse_args(argv)
    if arguments.flood:
        return flood(arguments.flood, arguments.seconds, arguments.namespace)
    config = arguments.config.resolve()
    rate_hz = load_vehicle(config).rate_hz
    cases = []
    for trigger in arguments.triggers:
        cases.append(case(config, trigger, rate_hz, arguments.seconds, ROOT / "build" / f"load_{trigger}.log"))
        figures = cases[-1]
        print(f"load: trigger {trigger}: {figures['achieved_hz']} Hz of {rate_hz:g}, output age p99/max "
              f"{figures['output_age_ms']['p99']}/{figures['output_age_ms']['max']} ms, wrench age p99 "
              f"{figures['wrench_age_first_ms']['p99']} -> {figures['wrench_age_last_ms']['p99']} ms, RSS "
              f"{figures['rss_growth_mb']:+} MB, CPU {figures['cpu_percent']} %, flood "
              f"{figures['flood_achieved_hz']} Hz", flush=True)
    result = {"config": str(config.relative_to(ROOT)) if config.is_relative_to(ROOT) else str(config),
              "seconds": arguments.seconds, "warm_up_seconds": WARM_UP, "flood_hz": FLOOD_HZ,
              "flood_achieved_hz": min(c["flood_achieved_hz"] for c in cases), "cpu_count": os.cpu_count(),
              "cases": cases}
    arguments.out.parent.mkdir(parents=True, exist_ok=True)
    arguments.out.write_text(json.dumps(result, indent=1) + "\n")
    failed = [f"trigger {c['trigger']}: {reason}" for c in cases for reason in c["failures"]]
    for reason in failed:
        print(f"load: FAIL: {reason}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
