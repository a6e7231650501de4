"""Optional per-actuator topics (``per_actuator_topics``): ``thrusters/<name>/thrust`` and,
for rotatable thrusters, ``thrusters/<name>/azimuth``, std_msgs/Float64 each sample, for
drivers and plots that take one number per actuator."""

from __future__ import annotations

from rclpy.node import Node
from std_msgs.msg import Float64

from ..allocation.allocator import AllocationResult
from ..vehicle.config import Vehicle
from . import qos


class ActuatorTopics:
    """The publishers of one vehicle's actuators on a node, until :meth:`close`."""

    def __init__(self, node: Node, vehicle: Vehicle):
        self._node = node
        def publisher(topic: str):
            return node.create_publisher(Float64, topic, qos.output(), qos_overriding_options=qos.overridable())

        self._publishers = [
            (i, publisher(f"thrusters/{actuator.name}/thrust"),
             publisher(f"thrusters/{actuator.name}/azimuth") if actuator.rotatable else None)
            for i, actuator in enumerate(vehicle.actuators)
        ]

    def publish(self, result: AllocationResult) -> None:
        for i, thrust, azimuth in self._publishers:
            thrust.publish(Float64(data=float(result.thrust[i])))
            if azimuth is not None:
                azimuth.publish(Float64(data=float(result.azimuth[i])))

    def close(self) -> None:
        for _, thrust, azimuth in self._publishers:
            self._node.destroy_publisher(thrust)
            if azimuth is not None:
                self._node.destroy_publisher(azimuth)
        self._publishers = []
