"""make demo: watch the allocator keep a vessel on station while an actuator fails.

Starts ``allocator_node`` with a vehicle (the DP vessel by default) as its own process, and
plays a controller against it over DDS on loopback: the wrench that holds position against an
environmental force turning slowly round the vessel, with a slowly varying yaw moment. Midway
one actuator FAILS and later recovers (through the fault service). A compact live table
shows thrust, azimuth, saturation and solve time; at the end a timeline PNG (thrust and
azimuth of every actuator against time, fault interval shaded) is written and its path
printed.

    python -m allocator_pkg.cli.demo [--config config/dp_vessel.yaml] [--duration 40] [--out FILE]
"""

from __future__ import annotations

import argparse
import math
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import rclpy
from rclpy.executors import SingleThreadedExecutor

from allocator_msgs.msg import AllocationStatus, ThrusterCommands

from ..configuration.parameters import load_vehicle
from ..effectiveness.model import Model
from ..ros.conversions import array_to_wrench
from ..vehicle.config import DOF_NAMES, Vehicle
from .ctl import Controller, format_sample


@dataclass
class Timeline:
    """What the demo saw: one row per ThrusterCommands message."""

    names: list[str] = field(default_factory=list)
    time: list[float] = field(default_factory=list)
    thrust: list[list[float]] = field(default_factory=list)
    azimuth: list[list[float]] = field(default_factory=list)
    saturated: list[bool] = field(default_factory=list)
    solve_time: list[float] = field(default_factory=list)

    def add(self, now: float, commands: ThrusterCommands, status: AllocationStatus | None) -> None:
        self.names = list(commands.name)
        self.time.append(now)
        self.thrust.append(list(commands.thrust))
        self.azimuth.append(list(commands.azimuth))
        self.saturated.append(bool(status.saturated) if status else False)
        self.solve_time.append(status.solve_time if status else 0.0)


def station_keeping(vehicle: Vehicle, t: float, duration: float) -> np.ndarray:
    """The controller's wrench against an environmental force that builds up over the first
    tenth of the run and turns half round the vessel in ``duration`` (from ahead to astern,
    through starboard), sized to the vehicle: a fifth of its weaker horizontal authority,
    with a slowly varying yaw moment."""
    model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
    authority = dict(zip(vehicle.dofs, model.authority))
    build_up = min(1.0, t / (0.1 * duration))
    force = 0.2 * build_up * min(authority.get("surge", 0.0), authority.get("sway", authority.get("surge", 0.0)))
    heading = math.pi * t / duration
    tau = np.zeros(6)
    tau[DOF_NAMES.index("surge")] = force * math.cos(heading)
    tau[DOF_NAMES.index("sway")] = force * math.sin(heading)
    tau[DOF_NAMES.index("yaw")] = 0.05 * build_up * authority.get("yaw", 0.0) * math.sin(2.0 * heading)
    return tau


def plot_timeline(path: Path, timeline: Timeline, fault: tuple[float, float], failed: str, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = np.array(timeline.time) - timeline.time[0]
    thrust = np.array(timeline.thrust)
    azimuth = np.degrees(np.unwrap(np.array(timeline.azimuth), axis=0))
    figure, (top, middle, bottom) = plt.subplots(3, 1, figsize=(10, 8.5), sharex=True,
                                                 gridspec_kw={"height_ratios": [3, 2, 1]})
    for i, name in enumerate(timeline.names):
        top.plot(t, thrust[:, i] / 1e3, label=name)
        if np.any(azimuth[:, i] != 0.0):
            middle.plot(t, azimuth[:, i], label=name)
    bottom.plot(t, np.array(timeline.solve_time) * 1e3, color="black", linewidth=0.8, label="solve time")
    bottom.fill_between(t, 0, np.max(np.array(timeline.solve_time) * 1e3) * np.array(timeline.saturated),
                        step="mid", color="tab:red", alpha=0.2, label="saturated")
    for axes in (top, middle, bottom):
        axes.axvspan(fault[0] - timeline.time[0], fault[1] - timeline.time[0], color="grey", alpha=0.2)
        axes.grid(True)
    top.set_ylabel("thrust [kN]")
    top.set_title(f"{title}: station keeping, {failed} FAILED in the shaded interval")
    top.legend(loc="upper right", fontsize=8)
    middle.set_ylabel("azimuth [deg]")
    middle.legend(loc="upper right", fontsize=8)
    bottom.set_ylabel("solve [ms]")
    bottom.set_xlabel("time [s]")
    bottom.legend(loc="upper right", fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="allocator-demo", description=__doc__.split("\n\n")[0])
    parser.add_argument("--config", default="config/dp_vessel.yaml", help="vehicle params file")
    parser.add_argument("--duration", type=float, default=40.0, help="seconds of station keeping")
    parser.add_argument("--fail", default=None, help="actuator to fail midway (default: the first one)")
    parser.add_argument("--out", default="build/demo_timeline.png", help="timeline PNG")
    arguments = parser.parse_args(argv)
    vehicle = load_vehicle(arguments.config)
    failed = arguments.fail or vehicle.actuators[0].name
    out = Path(arguments.out)
    out.parent.mkdir(parents=True, exist_ok=True)

    # A local show: DDS discovery stays on this machine unless the caller chose otherwise.
    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    os.environ.setdefault("ROS_DOMAIN_ID", "42")
    binary = os.path.join(os.path.dirname(sys.executable), "allocator_node")
    node_process = subprocess.Popen([binary, "--ros-args", "--params-file", arguments.config, "-p",
                                     f"wrench_timeout:={max(1.0, 5.0 / vehicle.rate_hz)}"],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    rclpy.init()
    node = rclpy.create_node("allocator_demo")
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    controller = Controller(node)
    timeline = Timeline()
    latest: dict[str, AllocationStatus] = {}
    printed = [0.0]

    def on_status(message: AllocationStatus) -> None:
        latest["status"] = message

    def on_commands(message: ThrusterCommands) -> None:
        now = time.monotonic()
        timeline.add(now, message, latest.get("status"))
        if now - printed[0] >= 0.5:
            printed[0] = now
            print(f"{now - start:5.1f} s  " + format_sample(message, latest.get("status")), flush=True)

    node.create_subscription(AllocationStatus, "allocation_status", on_status, 10)
    node.create_subscription(ThrusterCommands, "thruster_commands", on_commands, 10)
    start = time.monotonic()
    try:
        while controller.wrench.get_subscription_count() == 0 or not timeline.time:
            executor.spin_once(timeout_sec=0.05)
            if time.monotonic() - start > 30.0 or node_process.poll() is not None:
                print("demo: allocator_node did not start", file=sys.stderr)
                return 1
        print(f"demo: {Path(arguments.config).stem}, {arguments.duration:g} s; {failed} fails at 40 % and "
              "recovers at 70 %", flush=True)
        timeline = Timeline()
        start = time.monotonic()
        fault = [math.inf, math.inf]
        period = 1.0 / vehicle.rate_hz
        published = 0
        next_publish = start
        while (now := time.monotonic()) - start < arguments.duration:
            elapsed = now - start
            if now >= next_publish:
                controller.wrench.publish(array_to_wrench(station_keeping(vehicle, elapsed, arguments.duration)))
                published += 1
                next_publish = start + published * period
            if elapsed >= 0.4 * arguments.duration and fault[0] == math.inf:
                fault[0] = now
                print(f"demo: {controller.set_fault(failed, 'failed').message}", flush=True)
            if elapsed >= 0.7 * arguments.duration and fault[1] == math.inf:
                fault[1] = now
                print(f"demo: {controller.clear_faults().message}", flush=True)
            executor.spin_once(timeout_sec=min(0.02, max(0.0, next_publish - time.monotonic())))
        plot_timeline(out, timeline, (fault[0], fault[1]), failed, Path(arguments.config).stem)
        saturated = 100.0 * np.mean(timeline.saturated)
        print(f"demo: {len(timeline.time)} samples, {saturated:.0f} % saturated, median solve time "
              f"{np.median(timeline.solve_time) * 1e3:.2f} ms")
        print(f"demo: timeline written to {out.resolve()}")
        return 0
    finally:
        node_process.send_signal(signal.SIGTERM)
        try:
            node_process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            node_process.kill()
        executor.shutdown()
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    sys.exit(main())
