"""ROS 2 node ``thrust_allocator``: topics, timer, parameters and services around the core.

ROS in (wrench, odometry, parameters, fault services), :class:`allocator_pkg.Allocator`,
ROS out (commands, status, diagnostics). Allocation runs on a timer at ``rate_hz`` on the
latest valid wrench, never in a subscription callback. Messages are built in
:mod:`allocator_pkg.conversions`, diagnostics in :mod:`allocator_pkg.diagnostics`. See
README.md for the interface.
"""

from __future__ import annotations

import math
import signal
import sys
import threading

import numpy as np
import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Wrench
from nav_msgs.msg import Odometry
from rcl_interfaces.msg import SetParametersResult
from rclpy.duration import Duration
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.signals import SignalHandlerOptions
from rclpy.time import Time
from std_msgs.msg import Header
from std_srvs.srv import Trigger

from allocator_msgs.msg import ActuatorFault, AllocationStatus, ThrusterCommands
from allocator_msgs.srv import SetActuatorFault

from . import ros_parameters
from .actuator_topics import ActuatorTopics
from .allocator import AllocationResult, Allocator
from .conversions import commands_message, status_message, wrench_to_array
from .diagnostics import Counters, diagnostic_status
from .faults import FaultMode
from .node_settings import NODE_NAME, NodeSettings
from .parameters import parse_parameters
from .ros_parameters import WholeSetParameters
from .vehicle import ConfigError, Vehicle
from .watchdog import Watchdog

STOP_ACK_TIMEOUT = 1.0       # s the shutdown's zero-thrust command waits for acknowledgements
DIAGNOSTICS_PERIOD = 1.0
LOG_THROTTLE = 5.0


class AllocatorNode(WholeSetParameters, Node):
    """The allocation node. Raises ConfigError if its parameters are invalid.

    State shared between callbacks sits behind one lock, and parameter changes are serialised
    by another (rclpy has none), so ``set_parameters`` may be called from any thread while an
    executor spins the node: each change is checked against the parameters it will replace.
    """

    def __init__(self, **kwargs):
        super().__init__(NODE_NAME, automatically_declare_parameters_from_overrides=True, **kwargs)
        self.setup_whole_set_parameters()
        self._lock = threading.Lock()
        self._pending: tuple[Vehicle, NodeSettings, list[str]] | None = None
        vehicle, settings = parse_parameters(ros_parameters.allocator_parameters(self))
        ros_parameters.declare(self, vehicle)
        self._allocator = Allocator(vehicle)
        for warning in self._allocator.warnings:
            self.get_logger().warn(warning)
        for note in self._allocator.notes:
            self.get_logger().info(note)
        self._counters = Counters()
        self._wrench = np.zeros(6)
        self._wrench_time: int | None = None
        self._watchdog = Watchdog(settings.wrench_timeout)
        self._last: AllocationResult | None = None
        self.samples = 0
        self.wrenches_received = 0

        reliable = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE)
        self._commands = self.create_publisher(ThrusterCommands, "thruster_commands", reliable)
        self._status = self.create_publisher(AllocationStatus, "allocation_status", reliable)
        self._diagnostics = self.create_publisher(DiagnosticArray, "/diagnostics", 10)
        self._per_actuator: ActuatorTopics | None = None
        self._wrench_subscription = None
        self._settings = settings
        self._apply_settings(settings, None)
        if vehicle.has_surfaces:
            self.create_subscription(Odometry, "odometry", self._on_odometry, 10)
        self.create_service(SetActuatorFault, "~/set_actuator_fault", self._on_set_fault)
        self.create_service(Trigger, "~/clear_faults", self._on_clear_faults)
        self._timer = self.create_timer(1.0 / vehicle.rate_hz, self._on_timer)
        self.create_timer(DIAGNOSTICS_PERIOD, self._on_diagnostics)
        self.add_on_set_parameters_callback(self._check_parameters)
        self.add_post_set_parameters_callback(self._apply_parameters)
        left = self._allocator.uncontrolled
        self.get_logger().info(
            f"allocating {', '.join(vehicle.dofs)} over {len(vehicle.actuators)} actuators with "
            f"'{self._allocator.method}' at {vehicle.rate_hz:g} Hz"
            + (f"; {', '.join(left)} left to the vehicle" if left else ""))

    @property
    def allocator(self) -> Allocator:
        return self._allocator

    @property
    def period(self) -> float:
        """The allocation timer's period [s]."""
        return self._timer.timer_period_ns * 1e-9

    # -- inputs -------------------------------------------------------------------------

    def _on_wrench(self, message: Wrench) -> None:
        values = wrench_to_array(message)
        with self._lock:
            self.wrenches_received += 1
            if np.all(np.isfinite(values)):
                self._wrench = values
                self._wrench_time = self.get_clock().now().nanoseconds
                return
            self._counters.rejected_wrenches += 1
            self._counters.rejected_in_period += 1
        self.get_logger().warn(f"rejected a wrench with non-finite values {values.tolist()}",
                               throttle_duration_sec=LOG_THROTTLE)

    def _on_odometry(self, message: Odometry) -> None:
        speed = message.twist.twist.linear.x
        with self._lock:
            if math.isfinite(speed):
                self._allocator.set_speed(speed)
                return
            self._counters.rejected_odometry += 1
            self._counters.rejected_in_period += 1
        self.get_logger().warn("rejected odometry with a non-finite surge speed", throttle_duration_sec=LOG_THROTTLE)

    # -- the sample ---------------------------------------------------------------------

    def _on_timer(self) -> None:
        with self._lock:
            now = self.get_clock().now()
            stale, transition = self._watchdog.check(now.nanoseconds, self._wrench_time)
            if transition is not None and transition[0] == "warn":
                self.get_logger().warn(transition[1])
            elif transition is not None:
                self.get_logger().info(transition[1])
            result = self._allocator.stop() if stale else self._allocator.allocate(self._wrench)
            self.samples += 1
            self._counters.count(result)
            self._last = result
            self._publish(result, now, f"stale: no valid wrench for {self._watchdog.timeout:g} s" if stale
                          else result.status)

    def _publish(self, result: AllocationResult, now: Time, status: str) -> None:
        stamp = now.to_msg()
        self._commands.publish(commands_message(result, self._allocator.names, stamp))
        self._status.publish(status_message(result, status, stamp))
        if self._per_actuator is not None:
            self._per_actuator.publish(result)

    def publish_stop(self, timeout: float = STOP_ACK_TIMEOUT) -> bool:
        """One zero-thrust command (shutdown), angles held; waits up to ``timeout`` seconds
        for every subscriber to acknowledge it (the node is about to go, and with it the
        reliable writer that would resend it). Whether all did."""
        with self._lock:
            self._publish(self._allocator.stop(), self.get_clock().now(), "stopped: shutting down")
        return self._commands.wait_for_all_acked(Duration(seconds=timeout))

    # -- faults -------------------------------------------------------------------------

    def _on_set_fault(self, request: SetActuatorFault.Request, response: SetActuatorFault.Response):
        fault = request.fault
        try:
            mode = FaultMode(fault.mode)
        except ValueError:
            response.success = False
            response.message = (f"unknown mode {fault.mode}; modes: NOMINAL={ActuatorFault.NOMINAL}, "
                                f"DEGRADED={ActuatorFault.DEGRADED}, FAILED={ActuatorFault.FAILED}, "
                                f"STUCK={ActuatorFault.STUCK}")
            return response
        with self._lock:
            try:
                self._allocator.set_fault(fault.actuator, mode, efficiency=fault.efficiency, angle=fault.azimuth)
            except ValueError as error:
                response.success = False
                response.message = str(error)
                return response
        response.success = True
        response.message = f"{fault.actuator}: {mode.name} from the next sample"
        self.get_logger().info(response.message)
        return response

    def _on_clear_faults(self, request: Trigger.Request, response: Trigger.Response):
        with self._lock:
            had = sorted(self._allocator.faults)
            self._allocator.clear_faults()
        response.success = True
        response.message = f"cleared faults of {', '.join(had)}" if had else "no faults were set"
        self.get_logger().info(response.message)
        return response

    # -- parameters ---------------------------------------------------------------------

    def _check_parameters(self, parameters: list[Parameter]) -> SetParametersResult:
        """Check a change against the whole schema and the running allocator; keep what it
        builds for :meth:`_apply_parameters`. Nothing changes here."""
        self._pending = None
        changes = {p.name: ros_parameters.plain(p.value) for p in parameters
                   if ros_parameters.is_allocator_parameter(p.name)}
        if not changes:
            return SetParametersResult(successful=True)
        candidate = ros_parameters.allocator_parameters(self)
        candidate.update(changes)
        try:
            vehicle, settings = parse_parameters(candidate)
            self._allocator.check_reconfigure(vehicle)
        except ValueError as error:
            self.get_logger().warn(f"rejected parameter change: {error}")
            return SetParametersResult(successful=False, reason=str(error))
        self._pending = (vehicle, settings, sorted(changes))
        return SetParametersResult(successful=True)

    def _apply_parameters(self, parameters: list[Parameter]) -> None:
        """Apply what :meth:`_check_parameters` accepted, between two samples."""
        if self._pending is None:
            return
        vehicle, settings, names = self._pending
        self._pending = None
        with self._lock:
            old = self._allocator.vehicle
            self._allocator.reconfigure(vehicle)
            if vehicle.rate_hz != old.rate_hz:
                self._timer.timer_period_ns = round(1e9 / vehicle.rate_hz)
            self._apply_settings(settings, self._settings)
            self._settings = settings
            self._watchdog.timeout = settings.wrench_timeout
        self.get_logger().info(f"applied {', '.join(names)}")

    def _apply_settings(self, settings: NodeSettings, old: NodeSettings | None) -> None:
        """The wrench subscription's QoS and the per-actuator topics."""
        if old is None or settings.wrench_qos != old.wrench_qos:
            if self._wrench_subscription is not None:
                self.destroy_subscription(self._wrench_subscription)
            reliability = ReliabilityPolicy.BEST_EFFORT if settings.wrench_qos == "best_effort" \
                else ReliabilityPolicy.RELIABLE
            self._wrench_subscription = self.create_subscription(
                Wrench, "wrench_command", self._on_wrench, QoSProfile(depth=1, reliability=reliability))
        if settings.per_actuator_topics and self._per_actuator is None:
            self._per_actuator = ActuatorTopics(self, self._allocator.vehicle)
        elif not settings.per_actuator_topics and self._per_actuator is not None:
            self._per_actuator.close()
            self._per_actuator = None

    # -- diagnostics --------------------------------------------------------------------

    def _on_diagnostics(self) -> None:
        with self._lock:
            status = diagnostic_status(f"{self.get_name()}: thrust allocation", self.get_fully_qualified_name(),
                                       self._allocator, self._counters, self._watchdog.stale, self._last)
            self._counters.reset_period()
        self._diagnostics.publish(DiagnosticArray(header=Header(stamp=self.get_clock().now().to_msg()),
                                                  status=[status]))


def main(args: list[str] | None = None) -> int:
    """Entry point of ``allocator_node``: spin until SIGINT/SIGTERM, then command zero thrust."""
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    stop = threading.Event()
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signal_number, lambda *_: stop.set())
    try:
        node = AllocatorNode()
    except ConfigError as error:
        print(f"{NODE_NAME}: invalid configuration:\n  " + "\n  ".join(
            f"{name}: {reason}" for name, reason in error.problems), file=sys.stderr)
        rclpy.try_shutdown()
        return 1
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    try:
        while not stop.is_set() and rclpy.ok():
            executor.spin_once(timeout_sec=0.1)
        if node.publish_stop():
            node.get_logger().info("stopped: published zero thrust")
        else:
            node.get_logger().warn(f"stopped: published zero thrust, not acknowledged by every "
                                   f"subscriber within {STOP_ACK_TIMEOUT:g} s")
    finally:
        executor.shutdown()
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
