"""allocator-ctl echo: a live table of what the allocator commands, every sample to CSV, and
the wrench, commands and status recorded as rosbag2 records them.

A CSV row pairs a sample's commands with the status of the same sample (the same stamp); a
sample whose status never comes (``status_rate_hz`` above 0) has its status columns empty.
Rows start once the status subscription has matched the node's publisher, so that the first
ones are not empty for want of a connection. The wrench type (Wrench or WrenchStamped) is
read from the graph while the echo spins, not before, so that no sample is missed waiting
for it."""

from __future__ import annotations

import csv
import math
import time
from typing import TextIO

from geometry_msgs.msg import Wrench, WrenchStamped
from rclpy.node import Node
from rclpy.qos import QoSProfile, ReliabilityPolicy

from allocator_msgs.msg import AllocationStatus, ThrusterCommands

from ..simulation.live_text import wrapped
from .conversions import OUTCOME_NAMES, wrench_to_array
from .node_client import Controller
from .recording import Recording


def format_sample(commands: ThrusterCommands, status: AllocationStatus | None) -> str:
    """A few lines of at most :data:`~..simulation.live_text.WIDTH` characters: every actuator's thrust [N], command
    (set-point) and azimuth [deg] if it has one; then the solver figures; when saturated the
    unallocated wrench, the actuators at a thrust (!) or rate (~) limit, and the supply voltage in
    use; with power sources, the power each gives of what it has [kW], LIMITED when the power
    holds thrust back."""
    parts = []
    for name, thrust, command, azimuth in zip(commands.name, commands.thrust, commands.command, commands.azimuth):
        angle = f" @{math.degrees(azimuth):6.1f}" if azimuth != 0.0 else " " * 8
        parts.append(f"{name} {thrust:9.1f} N cmd {command:8.2f}{angle}")
    lines = wrapped(parts) if parts else []
    if status is not None:
        figures = [f"sat {'YES' if status.saturated else 'no '} {status.solve_time * 1e6:7.0f} us "
                   f"{status.iterations:5d} it {status.solver_status}"]
        if status.saturated:
            figures.append("unallocated " + " ".join(f"{v:.1f}" for v in wrench_to_array(status.unallocated)))
        flagged = [f"{name}{'!' if thrust else ''}{'~' if rate else ''}" for name, thrust, rate
                   in zip(commands.name, status.at_thrust_limit, status.at_rate_limit) if thrust or rate]
        if flagged:
            figures.append(f"at limit (! thrust, ~ rate): {' '.join(flagged)}")
        if status.voltage > 0.0:                     # NaN: no voltage tables
            figures.append(f"{status.voltage:.2f} V")
        if status.power_source:
            figures.append("power " + ", ".join(f"{source} {drawn:.0f}/{available:g} kW" for source, drawn, available
                                                in zip(status.power_source, status.source_power,
                                                       status.source_available))
                           + (" LIMITED" if status.power_limited else ""))
        lines += wrapped(figures, "|| ")
    return "\n".join(line.rstrip() for line in lines)


WRENCH_TYPES = {"geometry_msgs/msg/Wrench": Wrench, "geometry_msgs/msg/WrenchStamped": WrenchStamped}

WRENCH_TYPE_WAIT = 2.0
"""[s] How long the echo looks for the wrench type in the graph before it records Wrench."""

STATUS_COLUMNS = ["saturated", "solve_time", "iterations", "solver_status", "outcome", "voltage"]


def wrench_type_seen(node: Node, topic: str) -> type | None:
    """The wrench type on ``topic`` in the ROS graph (the allocator's ``wrench_type``), or None
    while none is seen."""
    for name, types in node.get_topic_names_and_types():
        found = [WRENCH_TYPES[kind] for kind in types if kind in WRENCH_TYPES]
        if name == topic and found:
            return found[0]
    return None


def csv_header(names: list[str]) -> list[str]:
    header = ["stamp"]
    for name in names:
        header += [f"{name}.thrust", f"{name}.command", f"{name}.azimuth", f"{name}.mode"]
    header += [f"{name}.at_{kind}_limit" for kind in ("thrust", "rate") for name in names]
    return header + STATUS_COLUMNS + [f"unallocated.{axis}" for axis in ("x", "y", "z", "k", "m", "n")]


def csv_row(commands: ThrusterCommands, status: AllocationStatus | None) -> list:
    """One sample: its commands, and its status (empty columns without one)."""
    row = [commands.header.stamp.sec + commands.header.stamp.nanosec * 1e-9]
    for values in zip(commands.thrust, commands.command, commands.azimuth, commands.mode):
        row += list(values)
    if status is None:
        return row + [""] * (2 * len(commands.name) + len(STATUS_COLUMNS) + 6)
    row += list(status.at_thrust_limit) + list(status.at_rate_limit)
    row += [status.saturated, status.solve_time, status.iterations, status.solver_status,
            OUTCOME_NAMES.get(status.outcome, str(status.outcome)), status.voltage]
    return row + wrench_to_array(status.unallocated).tolist()


def same_sample(commands: ThrusterCommands, status: AllocationStatus) -> bool:
    return (commands.header.stamp.sec, commands.header.stamp.nanosec) == (status.header.stamp.sec,
                                                                          status.header.stamp.nanosec)


class Echo:
    """Prints a compact live table of commands and status; optionally writes every sample to CSV,
    and records the wrenches (Wrench or WrenchStamped), commands and status as rosbag2 does.
    :meth:`close` writes the last sample's row."""

    def __init__(self, controller: Controller, out: TextIO, csv_file: TextIO | None = None, rate: float = 2.0,
                 recording: Recording | None = None):
        self.out = out
        self.recording = recording
        self.period = 1.0 / rate if rate > 0 else 0.0
        self.last_print = 0.0
        self.status: AllocationStatus | None = None
        self.writer = csv.writer(csv_file) if csv_file else None
        self.header_done = False
        self._pending: ThrusterCommands | None = None
        node = self.node = controller.node
        self._status = node.create_subscription(AllocationStatus, controller.topic("allocation_status"),
                                                self._on_status, 10)
        self._commands = node.create_subscription(ThrusterCommands, controller.topic("thruster_commands"),
                                                  self._on_commands, 10)
        self._wrench = None
        if recording is not None:
            self._wrench_topic = node.resolve_topic_name(controller.topic("wrench_command"))
            self._wrench_until = time.monotonic() + WRENCH_TYPE_WAIT
            self._wrench_timer = node.create_timer(0.05, self._subscribe_wrench)

    def _subscribe_wrench(self) -> None:
        """Subscribe to the wrench once its type is seen, or as Wrench after WRENCH_TYPE_WAIT."""
        kind = wrench_type_seen(self.node, self._wrench_topic)
        if kind is None and time.monotonic() < self._wrench_until:
            return
        self.node.destroy_timer(self._wrench_timer)
        self._wrench = self.node.create_subscription(kind or Wrench, self._wrench_topic, self._on_wrench,
                                                     QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))

    def _on_wrench(self, message: Wrench | WrenchStamped) -> None:
        self._record(self._wrench.topic_name, message)

    def _record(self, topic: str, message) -> None:
        if topic not in self.recording:
            publishers = self.node.get_publishers_info_by_topic(topic)
            self.recording.add_topic(topic, type(message), [info.qos_profile for info in publishers])
        self.recording.write(topic, message, self.node.get_clock().now().nanoseconds)

    def _on_status(self, message: AllocationStatus) -> None:
        self.status = message
        if self.recording is not None:
            self._record(self._status.topic_name, message)
        if self._pending is not None and same_sample(self._pending, message):
            self._write_csv(self._pending, message)
            self._pending = None

    def _on_commands(self, message: ThrusterCommands) -> None:
        if self.recording is not None:
            self._record(self._commands.topic_name, message)
        if self.writer is not None and self._status.get_publisher_count() > 0:
            if self._pending is not None:
                self._write_csv(self._pending, None)
                self._pending = None
            if self.status is not None and same_sample(message, self.status):
                self._write_csv(message, self.status)
            else:
                self._pending = message
        now = time.monotonic()
        if now - self.last_print >= self.period:
            self.last_print = now
            print(format_sample(message, self.status), file=self.out, flush=True)

    def _write_csv(self, commands: ThrusterCommands, status: AllocationStatus | None) -> None:
        if not self.header_done:
            self.writer.writerow(csv_header(list(commands.name)))
            self.header_done = True
        self.writer.writerow(csv_row(commands, status))

    def close(self) -> None:
        """Write the row of a sample whose status has not come (the last one)."""
        if self._pending is not None:
            self._write_csv(self._pending, None)
            self._pending = None
