"""QoS of every topic of the node, each overridable with the standard ``qos_overrides``
parameters (rclpy's ``QoSOverridingOptions``): history, depth and reliability, e.g.
``qos_overrides./rov1/wrench_command.subscription.reliability: reliable`` in a params file.
Overrides are read when the topic is created (they are read-only parameters).

Each function returns a new profile: rclpy writes the overrides into the profile it is given."""

from __future__ import annotations

from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from rclpy.qos_overriding_options import QoSOverridingOptions


def wrench() -> QoSProfile:
    """wrench_command: the latest wrench only. A best-effort subscription matches reliable and
    best-effort publishers alike (a reliable one would not match a best-effort publisher)."""
    return QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)


def odometry() -> QoSProfile:
    """odometry: the latest only; matches sensor-data and reliable publishers."""
    return QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)


def battery() -> QoSProfile:
    """battery_state: a sensor stream, latest only (takes best-effort and reliable publishers)."""
    return QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)


def power() -> QoSProfile:
    """power_available: the latest only (takes best-effort and reliable publishers)."""
    return QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)


def output() -> QoSProfile:
    """thruster_commands, allocation_status, per-actuator topics and markers."""
    return QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE)


def diagnostics() -> QoSProfile:
    return QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)


def robot_description() -> QoSProfile:
    """robot_description, as robot_state_publisher offers it (the last one kept for late joiners)."""
    return QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)


def overridable() -> QoSOverridingOptions:
    """History, depth and reliability of one publisher or subscription open to ``qos_overrides``."""
    return QoSOverridingOptions.with_default_policies()
