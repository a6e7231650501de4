"""``run.mcap`` of an ``allocator-sim`` run: what the loop writes (:mod:`.sim_link`), and what
Foxglove's 3-D panel needs to place the vehicle and draw its thrust: ``/tf`` from every odometry
written, the node's ``~/thrust_markers`` and its ``/diagnostics``, as they arrive.

Frames (one tree, every frame the recording names):

- ``map``: the world in ENU (REP-103: x east, y north, z up), as Foxglove and RViz draw it;
- ``ned``: the same origin in NED, the frame of ``/odometry`` and ``/setpoint``;
- ``base_link``: the body in FRD, the odometry's child frame and the frame of the node's outputs
  and markers (the node runs with ``frame: frd``; its markers' points are FRD).

Every ``/tf`` message (tf2_msgs/msg/TFMessage, :data:`~.recording.TF_MESSAGE`) carries map ->
ned (a constant rotation, in every message so that a seek anywhere finds it) and ned ->
base_link (the odometry's pose), stamped with the odometry. The markers and diagnostics are
logged at their header stamps, from the run's first step on.

Times are the run's: the node's sim time less that of the run's first step (:meth:`RunRecording.start`;
the node's clock starts before the warm-up, which is not recorded), in every log and publish time
and in every time the messages carry (each ``header.stamp``, ``/clock``), so that the recording
starts at 0 s as the scenario's events, ``metrics.json`` and the figures do: a fault at 100 s is
at 100 s in Foxglove.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from diagnostic_msgs.msg import DiagnosticArray
from nav_msgs.msg import Odometry
from rclpy.node import Node
from rclpy.qos import QoSProfile, ReliabilityPolicy
from visualization_msgs.msg import MarkerArray

from ..vehicle.node_settings import NODE_NAME
from . import qos
from .recording import TF_MESSAGE, Recording, fields, type_name

WORLD, NED, BODY = "map", "ned", "base_link"
TOPICS = {"tf": "/tf", "markers": f"/{NODE_NAME}/thrust_markers", "diagnostics": "/diagnostics"}
NED_IN_MAP = {"x": math.sqrt(0.5), "y": math.sqrt(0.5), "z": 0.0, "w": 0.0}
"""The rotation from NED to ENU (x, y, z, w): half a turn about the axis (1, 1, 0) / sqrt(2),
which swaps north and east and turns down into up."""


def _stamp(nanoseconds: int) -> dict[str, int]:
    sec, nanosec = divmod(nanoseconds, 1_000_000_000)
    return {"sec": sec, "nanosec": nanosec}


def _nanoseconds(stamp) -> int:
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def _transform(parent: str, child: str, t_ns: int, translation: dict[str, float],
               rotation: dict[str, float]) -> dict[str, Any]:
    return {"header": {"stamp": _stamp(t_ns), "frame_id": parent}, "child_frame_id": child,
            "transform": {"translation": translation, "rotation": rotation}}


def transforms(odometry: Odometry) -> dict[str, Any]:
    """The ``/tf`` message (the fields of a tf2_msgs/msg/TFMessage) of an odometry in ``ned``:
    map -> ned, and ned -> the odometry's child frame at its pose."""
    t_ns = _nanoseconds(odometry.header.stamp)
    p, q = odometry.pose.pose.position, odometry.pose.pose.orientation
    return {"transforms": [
        _transform(WORLD, NED, t_ns, {"x": 0.0, "y": 0.0, "z": 0.0}, NED_IN_MAP),
        _transform(odometry.header.frame_id, odometry.child_frame_id, t_ns, {"x": p.x, "y": p.y, "z": p.z},
                   {"x": q.x, "y": q.y, "z": q.z, "w": q.w})]}


def shifted(fields: Any, origin: int, stamps: tuple[str, ...] = ("stamp",)) -> Any:
    """A message as a mapping of its fields (:func:`~.recording.fields`) with every time under
    a key of ``stamps`` (``builtin_interfaces/Time``: sec, nanosec) ``origin`` [ns] earlier, at
    any depth; durations (a marker's ``lifetime``) stay as they are."""
    if isinstance(fields, dict):
        return {key: _stamp(_nanoseconds_of(value) - origin) if key in stamps and isinstance(value, dict)
                else shifted(value, origin, stamps) for key, value in fields.items()}
    if isinstance(fields, list):
        return [shifted(item, origin, stamps) for item in fields]
    return fields


def _nanoseconds_of(time: dict[str, int]) -> int:
    return time["sec"] * 1_000_000_000 + time["nanosec"]


class RunRecording(Recording):
    """A :class:`~.recording.Recording` of a run, on the run's time (:meth:`start`): writes
    ``/tf`` after each ``/odometry`` and records the node's thrust markers and diagnostics, which
    ``node`` subscribes to (the node builds its markers only while someone subscribes) in its
    namespace, the run's; they are recorded under the names of ``TOPICS``, the same in every run."""

    def __init__(self, path: str | Path, node: Node) -> None:
        super().__init__(path)
        self.origin: int | None = None
        """Sim time [ns] of the run's first step: 0 s of the recording (None before :meth:`start`)."""
        self.add_topic(TOPICS["tf"], TF_MESSAGE)
        self.add_topic(TOPICS["markers"], MarkerArray, [qos.output()])
        self.add_topic(TOPICS["diagnostics"], DiagnosticArray, [qos.diagnostics()])
        received = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
        node.create_subscription(MarkerArray, TOPICS["markers"].lstrip("/"), self._on_markers, received)
        node.create_subscription(DiagnosticArray, TOPICS["diagnostics"], self._on_diagnostics, received)

    def start(self, t_ns: int) -> None:
        """The run's first step is at sim time ``t_ns`` [ns]: 0 s of the recording."""
        self.origin = t_ns

    def write(self, topic: str, message: Any, log_time: int, publish_time: int | None = None) -> None:
        """:meth:`Recording.write` of ``message`` at sim time ``log_time`` [ns], every time of it
        on the run's time (:func:`shifted`); after an ``/odometry``, its ``/tf``."""
        if self.origin is None:
            raise ValueError("the recording has no start (RunRecording.start) to put its times on")
        if topic not in self:
            self.add_topic(topic, type(message))
        if type(message) is not dict and type_name(type(message)) != self._topics[topic].type:
            raise ValueError(f"{topic} carries {self._topics[topic].type}, not {type_name(type(message))}")
        stamps = ("stamp", "clock") if topic == "/clock" else ("stamp",)
        super().write(topic, shifted(fields(message), self.origin, stamps), log_time - self.origin,
                      None if publish_time is None else publish_time - self.origin)
        if topic == "/odometry":
            super().write(TOPICS["tf"], shifted(transforms(message), self.origin), log_time - self.origin)

    def _record_stamped(self, topic: str, message: Any, t_ns: int) -> None:
        """``message`` at its stamp ``t_ns``, once the run has begun (not the warm-up's)."""
        if self.origin is not None and t_ns >= self.origin:
            self.write(topic, message, t_ns)

    def _on_markers(self, message: MarkerArray) -> None:
        if message.markers:
            self._record_stamped(TOPICS["markers"], message, _nanoseconds(message.markers[0].header.stamp))

    def _on_diagnostics(self, message: DiagnosticArray) -> None:
        self._record_stamped(TOPICS["diagnostics"], message, _nanoseconds(message.header.stamp))
