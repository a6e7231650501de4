"""QoS of every topic of the node, each overridable with the standard ``qos_overrides``
parameters (rclpy's ``QoSOverridingOptions``): history, depth and reliability, e.g.
``qos_overrides./rov1/wrench_command.subscription.reliability: reliable`` in a params file.
Overrides are read when the topic is created (they are read-only parameters)."""

from __future__ import annotations

from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from rclpy.qos_overriding_options import QoSOverridingOptions

WRENCH = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
"""wrench_command: the latest wrench only. A best-effort subscription matches reliable and
best-effort publishers alike (a reliable one would not match a best-effort publisher)."""

ODOMETRY = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
"""odometry: the latest only; matches sensor-data and reliable publishers."""

OUTPUT = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE)
"""thruster_commands, allocation_status, per-actuator topics and markers."""

DIAGNOSTICS = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)

ROBOT_DESCRIPTION = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                               durability=DurabilityPolicy.TRANSIENT_LOCAL)
"""robot_description, as robot_state_publisher offers it (the last one kept for late joiners)."""


def overridable() -> QoSOverridingOptions:
    """History, depth and reliability of one publisher or subscription open to ``qos_overrides``."""
    return QoSOverridingOptions.with_default_policies()
