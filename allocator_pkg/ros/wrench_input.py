"""The wrench input: which message type, what is accepted, and publishers of the wrong type.

:func:`accept` checks one message against the node's settings and gives the wrench in FRD;
:func:`foreign_publishers` finds, in the ROS graph, publishers on the topic whose type is not
the one subscribed (they never connect, and DDS says nothing about it)."""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from geometry_msgs.msg import Wrench, WrenchStamped
from rclpy.node import Node

from ..vehicle.frames import wrench_between
from ..vehicle.node_settings import WRENCH_STAMPED, NodeSettings

TYPE_NAMES = {Wrench: "geometry_msgs/msg/Wrench", WrenchStamped: "geometry_msgs/msg/WrenchStamped"}


def message_type(settings: NodeSettings) -> type:
    """The message class of ``wrench_command``."""
    return WrenchStamped if settings.wrench_type == WRENCH_STAMPED else Wrench


class Verdict(NamedTuple):
    """The wrench in FRD, or why the message was rejected (``kind`` ``frame`` or ``values``); a
    named tuple, which costs less to make than a frozen dataclass (one per wrench received)."""

    wrench: np.ndarray | None
    kind: str = ""
    reason: str = ""


def accept(message: Wrench | WrenchStamped, settings: NodeSettings) -> Verdict:
    """A stamped wrench must be in ``base_frame``; every value must be finite. The wrench in FRD
    (:func:`~allocator_pkg.vehicle.frames.wrench_between` from the node's ``frame``)."""
    if isinstance(message, WrenchStamped):
        if message.header.frame_id != settings.base_frame:
            return Verdict(None, "frame", f"rejected a wrench in frame '{message.header.frame_id}': this node "
                                          f"takes '{settings.base_frame}' (base_frame) only")
        message = message.wrench
    force, torque = message.force, message.torque
    values = [force.x, force.y, force.z, torque.x, torque.y, torque.z]
    if not all(map(math.isfinite, values)):
        return Verdict(None, "values", f"rejected a wrench with non-finite values {values}")
    return Verdict(wrench_between(values, settings.frame))


def foreign_publishers(node: Node, topic: str, expected: str) -> list[str]:
    """'<node> (<type>)' of every publisher on ``topic`` (a resolved name) whose type is not ``expected``."""
    found = []
    for info in node.get_publishers_info_by_topic(topic):
        if info.topic_type != expected:
            namespace = info.node_namespace.rstrip("/")
            found.append(f"{namespace}/{info.node_name} ({info.topic_type})")
    return sorted(found)
