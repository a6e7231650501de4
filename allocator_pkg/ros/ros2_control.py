"""The ros2_control output (``ros2_control.thrust_topic``, ``ros2_control.angle_topic``): each
sample, the thrust [N] of the actuators of ``ros2_control.actuators`` and the azimuth angles
[rad] of the rotatable ones among them, as std_msgs/Float64MultiArray in that order, the
commands a ``forward_command_controller`` forwards to its joints (docs/ros2_control.md)."""

from __future__ import annotations

from collections.abc import Callable

from rclpy.publisher import Publisher
from rclpy.qos import QoSProfile
from std_msgs.msg import Float64MultiArray

from ..allocation.result import AllocationResult
from ..vehicle.config import Vehicle
from ..vehicle.node_settings import NodeSettings
from . import qos
from .conversions import doubles

CreateOutput = Callable[[type, str, QoSProfile], Publisher]


def ros2_control_changed(old: NodeSettings, new: NodeSettings) -> bool:
    """Whether a parameter change touches the ros2_control topics or their actuators."""
    return (old.ros2_control_thrust_topic, old.ros2_control_angle_topic, old.ros2_control_actuators) != \
        (new.ros2_control_thrust_topic, new.ros2_control_angle_topic, new.ros2_control_actuators)


class Ros2ControlOutput:
    """The publishers of the thrust and angle arrays, until :meth:`close`. ``create`` and
    ``destroy`` are those of :class:`~allocator_pkg.ros.outputs.Outputs` (lifecycle publishers
    on a managed node)."""

    def __init__(self, vehicle: Vehicle, settings: NodeSettings, create: CreateOutput,
                 destroy: Callable[[Publisher], None]):
        self._destroy = destroy
        index = {actuator.name: i for i, actuator in enumerate(vehicle.actuators)}
        self._thrust_indices = [index[name] for name in settings.ros2_control_actuators]
        self._angle_indices = [i for i in self._thrust_indices if vehicle.actuators[i].rotatable]
        self._thrust = create(Float64MultiArray, settings.ros2_control_thrust_topic, qos.output()) \
            if settings.ros2_control_thrust_topic else None
        self._angle = create(Float64MultiArray, settings.ros2_control_angle_topic, qos.output()) \
            if settings.ros2_control_angle_topic else None
        self._thrust_message, self._angle_message = Float64MultiArray(), Float64MultiArray()

    @property
    def topics(self) -> list[str]:
        """The resolved names of the topics published."""
        return [publisher.topic_name for publisher in (self._thrust, self._angle) if publisher is not None]

    def publish(self, result: AllocationResult) -> None:
        if self._thrust is not None:
            self._thrust_message.data = doubles(result.thrust[self._thrust_indices])
            self._thrust.publish(self._thrust_message)
        if self._angle is not None:
            self._angle_message.data = doubles(result.azimuth[self._angle_indices])
            self._angle.publish(self._angle_message)

    def close(self) -> None:
        for publisher in (self._thrust, self._angle):
            if publisher is not None:
                self._destroy(publisher)
        self._thrust = self._angle = None
