"""Settings of the ROS node that are not part of the vehicle: the allocation library never
reads them. Parsed and checked with the vehicle (:func:`allocator_pkg.parameters.parse_parameters`)."""

from __future__ import annotations

from dataclasses import dataclass

NODE_NAME = "thrust_allocator"
"""The allocator node's default name."""

QOS_RELIABILITY = ("reliable", "best_effort")


@dataclass(frozen=True)
class NodeSettings:
    """``wrench_timeout`` [s] of the stale-input watchdog (0 disables it), whether to publish
    one Float64 topic per actuator, and the reliability of the wrench subscription."""

    wrench_timeout: float
    per_actuator_topics: bool
    wrench_qos: str
