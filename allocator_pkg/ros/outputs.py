"""The runtime's outputs and how often each goes out: ``thruster_commands`` every sample,
``allocation_status`` while someone subscribes (at most ``status_rate_hz`` times a second),
``~/thrust_markers`` while someone subscribes (at most ``markers_rate_hz``), ``/diagnostics``
when the runtime reports, ``~/consequence`` when the consequence analysis answers, and the
per-actuator (:mod:`~allocator_pkg.ros.actuator_topics`) and ros2_control
(:mod:`~allocator_pkg.ros.ros2_control`) topics every sample when configured.

On a ``LifecycleNode`` every one is a lifecycle publisher: rclpy enables them in the node's
active state and drops what they are given in any other. On a plain ``Node`` they are plain
publishers.
"""

from __future__ import annotations

from functools import partial

from builtin_interfaces.msg import Time
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from lifecycle_msgs.msg import State
from rclpy.constants import S_TO_NS
from rclpy.duration import Duration
from rclpy.lifecycle import LifecycleNode, LifecyclePublisher, LifecycleState
from rclpy.node import Node
from rclpy.publisher import Publisher
from rclpy.qos import QoSProfile
from std_msgs.msg import Header
from visualization_msgs.msg import MarkerArray

from allocator_msgs.msg import AllocationStatus, ConsequenceAnalysis, ThrusterCommands

from ..allocation.allocator import AllocationResult, Allocator
from ..vehicle.config import Vehicle
from ..vehicle.node_settings import NodeSettings
from . import qos
from .actuator_topics import ActuatorTopics, CreateOutput
from .conversions import commands_message, status_message
from .markers import thrust_markers
from .ros2_control import Ros2ControlOutput, ros2_control_changed

ACTIVE = LifecycleState("active", State.PRIMARY_STATE_ACTIVE)


def status_period(settings: NodeSettings) -> int:
    """The shortest time [ns] between two statuses, 1 / status_rate_hz (0: every sample)."""
    rate = settings.status_rate_hz
    return round(S_TO_NS / rate) if rate > 0.0 else 0


class Outputs:
    """The publishers of ``allocator``'s samples on ``node``, until :meth:`close`. Called with
    the runtime's lock held, except :meth:`publish_diagnostics` and :meth:`publish_consequence`."""

    def __init__(self, node: Node, allocator: Allocator, vehicle: Vehicle, settings: NodeSettings):
        self._node = node
        self._allocator = allocator
        self._settings = settings
        self.statuses_published = 0
        self._commands = self._create(ThrusterCommands, "thruster_commands", qos.output())
        self._status = self._create(AllocationStatus, "allocation_status", qos.output())
        self._status_last: int | None = None
        self._status_period = status_period(settings)
        # Filled and published again every sample, always under the lock (making them anew costs
        # more than filling them); both share one header, its stamp set in place.
        self._commands_message, self._status_message = ThrusterCommands(), AllocationStatus()
        self._header = Header(frame_id=settings.base_frame)
        self._diagnostics = self._create(DiagnosticArray, "/diagnostics", qos.diagnostics())
        self._markers = self._create(MarkerArray, "~/thrust_markers", qos.output())
        self._markers_due = 0
        self._consequence = self._create(ConsequenceAnalysis, "~/consequence", qos.output()) \
            if vehicle.redundancy_groups else None
        self.consequence_alarm = False
        """Copied into every status: set by the consequence analysis (:mod:`~allocator_pkg.ros.consequence_topic`)."""
        self._per_actuator: ActuatorTopics | None = None
        self._apply_per_actuator(vehicle, settings, self._create)
        self._ros2_control = Ros2ControlOutput(vehicle, settings, self._create, self._destroy)

    @property
    def topics(self) -> list[str]:
        """The resolved names of the topics published (the per-actuator ones left out)."""
        consequence = [self._consequence.topic_name] if self._consequence is not None else []
        return [self._commands.topic_name, self._status.topic_name, self._markers.topic_name,
                self._diagnostics.topic_name, *consequence, *self._ros2_control.topics]

    def _create(self, message_type: type, topic: str, profile: QoSProfile, enable: bool = False) -> Publisher:
        """A publisher of one output: a lifecycle publisher on a LifecycleNode, a plain one on a
        Node. rclpy enables lifecycle publishers when the node activates; one made while the
        runtime is active (``enable``: per_actuator_topics or the ros2_control topics set then)
        is enabled here, like the others."""
        node = self._node
        if not isinstance(node, LifecycleNode):
            return node.create_publisher(message_type, topic, profile, qos_overriding_options=qos.overridable())
        publisher = node.create_lifecycle_publisher(message_type, topic, profile,
                                                    qos_overriding_options=qos.overridable())
        if enable:
            publisher.on_activate(ACTIVE)
        return publisher

    def _destroy(self, publisher: Publisher) -> None:
        """Destroy an output publisher (a lifecycle one leaves the node's managed entities)."""
        if isinstance(publisher, LifecyclePublisher):
            self._node.destroy_lifecycle_publisher(publisher)
        else:
            self._node.destroy_publisher(publisher)

    def publish(self, result: AllocationResult, now: int, status: str, always: bool = False) -> None:
        """The sample's outputs, stamped ``now`` [ns]. The status goes out only while someone
        subscribes, and at most status_rate_hz times a second (0: every sample) unless
        ``always`` (a stop)."""
        header = self._header
        stamp = header.stamp
        stamp.sec, stamp.nanosec = divmod(now, S_TO_NS)
        allocator = self._allocator
        self._commands.publish(commands_message(result, allocator.names, header, self._commands_message))
        # Due every sample, at a stop, or once a period of status_rate_hz has passed since the last
        # status (or the clock was set back, as a simulator restarting does).
        period, last = self._status_period, self._status_last
        due = always or not period or last is None or not 0 <= now - last < period
        if due and self._status.get_subscription_count():
            self._status_last = now
            limit = allocator.power_limit
            power = None if limit is None else allocator.power.reading(result.thrust, limit)
            message = status_message(result, status, header, self._settings.frame, allocator.voltage,
                                     self._status_message, power)
            message.consequence_alarm = self.consequence_alarm
            message.lost_reach = allocator.lost_reach       # computed when the faults changed
            self._status.publish(message)
            self.statuses_published += 1
        if self._per_actuator is not None:
            self._per_actuator.publish(result)
        self._ros2_control.publish(result)
        rate = self._settings.markers_rate_hz
        if rate > 0.0 and now >= self._markers_due:
            self._markers_due = now + round(S_TO_NS / rate)
            if self._markers.get_subscription_count():
                limits = allocator.ranges
                self._markers.publish(thrust_markers(allocator.vehicle, result, limits, header,
                                                     self._settings.frame))

    def publish_diagnostics(self, statuses: list[DiagnosticStatus], stamp: Time) -> None:
        self._diagnostics.publish(DiagnosticArray(header=Header(stamp=stamp), status=statuses))

    def publish_consequence(self, message: ConsequenceAnalysis) -> None:
        """``~/consequence``, from the analysis' own thread (a vehicle with redundancy groups)."""
        self._consequence.publish(message)

    def wait_for_acknowledgement(self, timeout: float) -> bool:
        """Whether every subscriber of the commands acknowledged what was published, within
        ``timeout`` seconds."""
        return self._commands.wait_for_all_acked(Duration(seconds=timeout))

    def apply(self, vehicle: Vehicle, settings: NodeSettings, active: bool) -> None:
        """A checked configuration of the same actuators: the per-actuator and ros2_control
        topics made or destroyed as it says (enabled at once when ``active``), and the status
        rate from the next sample."""
        create = partial(self._create, enable=active)
        self._apply_per_actuator(vehicle, settings, create)
        if ros2_control_changed(self._settings, settings):
            self._ros2_control.close()
            self._ros2_control = Ros2ControlOutput(vehicle, settings, create, self._destroy)
        self._settings = settings
        self._status_period = status_period(settings)
        self._status_last = None

    def _apply_per_actuator(self, vehicle: Vehicle, settings: NodeSettings, create: CreateOutput) -> None:
        if settings.per_actuator_topics and self._per_actuator is None:
            self._per_actuator = ActuatorTopics(vehicle, create, self._destroy)
        elif not settings.per_actuator_topics and self._per_actuator is not None:
            self._per_actuator.close()
            self._per_actuator = None

    def close(self) -> None:
        """Destroy every publisher."""
        if self._per_actuator is not None:
            self._per_actuator.close()
        self._ros2_control.close()
        for publisher in (self._commands, self._status, self._diagnostics, self._markers, self._consequence):
            if publisher is not None:
                self._destroy(publisher)
