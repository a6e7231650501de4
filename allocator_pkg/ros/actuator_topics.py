"""Optional per-actuator topics (``per_actuator_topics``): ``thrusters/<name>/thrust`` and,
for rotatable thrusters, ``thrusters/<name>/azimuth``, std_msgs/Float64 each sample, for
drivers and plots that take one number per actuator."""

from __future__ import annotations

from collections.abc import Callable

from rclpy.publisher import Publisher
from rclpy.qos import QoSProfile
from std_msgs.msg import Float64

from ..allocation.allocator import AllocationResult
from ..vehicle.config import Vehicle
from . import qos

CreateOutput = Callable[[type, str, QoSProfile], Publisher]


class ActuatorTopics:
    """The publishers of one vehicle's actuators, until :meth:`close`. ``create`` makes one
    output publisher (message type, topic, QoS) and ``destroy`` frees it: those of
    :class:`~allocator_pkg.ros.outputs.Outputs`, so that on a managed node they are lifecycle
    publishers like the other outputs."""

    def __init__(self, vehicle: Vehicle, create: CreateOutput, destroy: Callable[[Publisher], None]):
        self._destroy = destroy

        def publisher(topic: str) -> Publisher:
            return create(Float64, topic, qos.output())

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
            self._destroy(thrust)
            if azimuth is not None:
                self._destroy(azimuth)
        self._publishers = []
