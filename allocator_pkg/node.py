"""ROS 2 node ``thrust_allocator``: topics, timer, parameters and services around the core.

ROS in (wrench, odometry, parameters, fault services), :class:`allocator_pkg.Allocator`,
ROS out (commands, status, diagnostics). Allocation runs on a timer at ``rate_hz`` on the
latest valid wrench, never in a subscription callback. See README.md for the interface.
"""

from __future__ import annotations

import math
import signal
import sys
import threading
from dataclasses import dataclass

import numpy as np
import rclpy
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from geometry_msgs.msg import Wrench
from nav_msgs.msg import Odometry
from rcl_interfaces.msg import SetParametersResult
from rclpy.duration import Duration
from rclpy.exceptions import ParameterNotDeclaredException
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.parameter_service import ParameterService
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.signals import SignalHandlerOptions
from rclpy.time import Time
from std_msgs.msg import Float64
from std_srvs.srv import Trigger

from allocator_msgs.msg import ActuatorFault, AllocationStatus, ThrusterCommands
from allocator_msgs.srv import SetActuatorFault

from . import ros_parameters
from .allocator import AllocationResult, Allocator
from .faults import FaultMode
from .vehicle import ConfigError, Vehicle

NODE_NAME = "thrust_allocator"
STOP_ACK_TIMEOUT = 1.0       # s the shutdown's zero-thrust command waits for acknowledgements
DIAGNOSTICS_PERIOD = 1.0
LOG_THROTTLE = 5.0


def wrench_to_array(wrench: Wrench) -> np.ndarray:
    return np.array([wrench.force.x, wrench.force.y, wrench.force.z,
                     wrench.torque.x, wrench.torque.y, wrench.torque.z])


class _WholeSetParameterService(ParameterService):
    """rclpy's parameter services, with ``set_parameters`` requests taken as a whole (see
    AllocatorNode.set_parameters) instead of value by value."""

    def _set_parameters_callback(self, request, response):
        node = self._get_node()
        parameters = [Parameter.from_parameter_msg(message) for message in request.parameters]
        try:
            response.results = node.set_parameters(parameters)
        except ParameterNotDeclaredException as error:
            response.results = [SetParametersResult(successful=False, reason=str(error)) for _ in parameters]
        return response


def array_to_wrench(values) -> Wrench:
    wrench = Wrench()
    (wrench.force.x, wrench.force.y, wrench.force.z,
     wrench.torque.x, wrench.torque.y, wrench.torque.z) = (float(v) for v in values)
    return wrench


@dataclass
class _Counters:
    """What the diagnostics report; the per-period ones are reset every report."""

    rejected_wrenches: int = 0
    rejected_odometry: int = 0
    rejected_in_period: int = 0
    samples: int = 0
    saturated: int = 0
    fallbacks: int = 0
    max_solve_time: float = 0.0

    def reset_period(self) -> None:
        self.samples = self.saturated = self.fallbacks = self.rejected_in_period = 0
        self.max_solve_time = 0.0


class AllocatorNode(Node):
    """The allocation node. Raises ConfigError if its parameters are invalid.

    State shared between callbacks sits behind one lock, and parameter changes are serialised
    by another (rclpy has none), so ``set_parameters`` may be called from any thread while an
    executor spins the node: each change is checked against the parameters it will replace.
    """

    def __init__(self, **kwargs):
        super().__init__(NODE_NAME, automatically_declare_parameters_from_overrides=True,
                         start_parameter_services=False, **kwargs)
        self._parameter_service = _WholeSetParameterService(self)
        self._lock = threading.Lock()
        self._parameters_lock = threading.RLock()
        vehicle = Vehicle.from_parameters(ros_parameters.allocator_parameters(self))
        ros_parameters.declare(self, vehicle)
        self._allocator = Allocator(vehicle)
        for warning in self._allocator.warnings:
            self.get_logger().warn(warning)
        for note in self._allocator.notes:
            self.get_logger().info(note)
        self._counters = _Counters()
        self._wrench = np.zeros(6)
        self._wrench_time: Time | None = None
        self._stale = False
        self._last: AllocationResult | None = None
        self.samples = 0
        self.wrenches_received = 0

        reliable = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE)
        self._commands = self.create_publisher(ThrusterCommands, "thruster_commands", reliable)
        self._status = self.create_publisher(AllocationStatus, "allocation_status", reliable)
        self._diagnostics = self.create_publisher(DiagnosticArray, "/diagnostics", 10)
        self._per_actuator: dict[str, tuple] = {}
        self._wrench_subscription = None
        self._apply_node_settings(vehicle)
        if vehicle.has_surfaces:
            self.create_subscription(Odometry, "odometry", self._on_odometry, 10)
        self.create_service(SetActuatorFault, "~/set_actuator_fault", self._on_set_fault)
        self.create_service(Trigger, "~/clear_faults", self._on_clear_faults)
        self._timer = self.create_timer(1.0 / vehicle.rate_hz, self._on_timer)
        self.create_timer(DIAGNOSTICS_PERIOD, self._on_diagnostics)
        self.add_on_set_parameters_callback(self._on_parameters)
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
        if not np.all(np.isfinite(values)):
            with self._lock:
                self.wrenches_received += 1
                self._counters.rejected_wrenches += 1
                self._counters.rejected_in_period += 1
            self.get_logger().warn(f"rejected a wrench with non-finite values {values.tolist()}",
                                   throttle_duration_sec=LOG_THROTTLE)
            return
        with self._lock:
            self.wrenches_received += 1
            self._wrench = values
            self._wrench_time = self.get_clock().now()

    def _on_odometry(self, message: Odometry) -> None:
        speed = message.twist.twist.linear.x
        if not math.isfinite(speed):
            with self._lock:
                self._counters.rejected_odometry += 1
                self._counters.rejected_in_period += 1
            self.get_logger().warn("rejected odometry with a non-finite surge speed",
                                   throttle_duration_sec=LOG_THROTTLE)
            return
        with self._lock:
            self._allocator.set_speed(speed)

    # -- the sample ---------------------------------------------------------------------

    def _on_timer(self) -> None:
        with self._lock:
            now = self.get_clock().now()
            timeout = self._allocator.vehicle.wrench_timeout
            stale = timeout > 0.0 and (self._wrench_time is None
                                       or now - self._wrench_time > Duration(seconds=timeout))
            if stale != self._stale:
                self._stale = stale
                if stale and self._wrench_time is None:
                    self.get_logger().info("waiting for wrench_command: commanding zero thrust")
                elif stale:
                    self.get_logger().warn(f"no valid wrench for {timeout:g} s: commanding zero thrust")
                else:
                    self.get_logger().info("wrench input resumed")
            result = self._allocator.stop() if stale else self._allocator.allocate(self._wrench)
            self.samples += 1
            self._count(result)
            self._publish(result, now, f"stale: no valid wrench for {timeout:g} s" if stale else result.status)

    def _count(self, result: AllocationResult) -> None:
        counters = self._counters
        counters.samples += 1
        counters.saturated += result.saturated
        counters.fallbacks += result.status.startswith("fallback")
        counters.max_solve_time = max(counters.max_solve_time, result.solve_time)
        self._last = result

    def _publish(self, result: AllocationResult, now: Time, status: str) -> None:
        stamp = now.to_msg()
        commands = ThrusterCommands()
        commands.header.stamp = stamp
        commands.name = list(self._allocator.names)
        commands.thrust = result.thrust.tolist()
        commands.command = result.command.tolist()
        commands.azimuth = result.azimuth.tolist()
        commands.mode = result.mode.tolist()
        self._commands.publish(commands)
        message = AllocationStatus()
        message.header.stamp = stamp
        message.requested = array_to_wrench(result.requested)
        message.achieved = array_to_wrench(result.achieved)
        message.saturated = result.saturated
        message.method = result.method
        message.solver_status = status
        message.iterations = result.iterations
        message.solve_time = result.solve_time
        message.power = result.power
        self._status.publish(message)
        for name, (thrust, azimuth) in self._per_actuator.items():
            i = self._allocator.names.index(name)
            thrust.publish(Float64(data=float(result.thrust[i])))
            if azimuth is not None:
                azimuth.publish(Float64(data=float(result.azimuth[i])))

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
                self._allocator.set_fault(fault.actuator, mode, efficiency=fault.efficiency, azimuth=fault.azimuth)
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

    def set_parameters(self, parameter_list: list[Parameter]) -> list[SetParametersResult]:
        """Several values at once are checked and applied as a whole (rclpy would apply each on
        its own, and values valid only together could never be set this way): one result per
        value, all alike. One change at a time across threads."""
        result = self.set_parameters_atomically(parameter_list)
        return [SetParametersResult(successful=result.successful, reason=result.reason) for _ in parameter_list]

    def set_parameters_atomically(self, parameter_list: list[Parameter]) -> SetParametersResult:
        """rclpy's ``set_parameters_atomically`` (also behind the parameter services), serialised."""
        with self._parameters_lock:
            return super().set_parameters_atomically(parameter_list)

    def _on_parameters(self, parameters: list[Parameter]) -> SetParametersResult:
        """Check a change against the whole schema; apply it between two samples, or not at all."""
        changes = {p.name: ros_parameters.plain(p.value) for p in parameters
                   if ros_parameters.is_allocator_parameter(p.name)}
        if not changes:
            return SetParametersResult(successful=True)
        candidate = ros_parameters.allocator_parameters(self)
        candidate.update(changes)
        try:
            vehicle = Vehicle.from_parameters(candidate)
        except ConfigError as error:
            self.get_logger().warn(f"rejected parameter change: {error}")
            return SetParametersResult(successful=False, reason=str(error))
        with self._lock:
            old = self._allocator.vehicle
            try:
                self._allocator.reconfigure(vehicle)
            except ValueError as error:
                return SetParametersResult(successful=False, reason=str(error))
            if vehicle.rate_hz != old.rate_hz:
                self._timer.timer_period_ns = round(1e9 / vehicle.rate_hz)
            self._apply_node_settings(vehicle, old)
        self.get_logger().info(f"applied {', '.join(sorted(changes))}")
        return SetParametersResult(successful=True)

    def _apply_node_settings(self, vehicle: Vehicle, old: Vehicle | None = None) -> None:
        """The wrench subscription's QoS and the per-actuator topics."""
        if old is None or vehicle.wrench_qos != old.wrench_qos:
            if self._wrench_subscription is not None:
                self.destroy_subscription(self._wrench_subscription)
            reliability = ReliabilityPolicy.BEST_EFFORT if vehicle.wrench_qos == "best_effort" \
                else ReliabilityPolicy.RELIABLE
            self._wrench_subscription = self.create_subscription(
                Wrench, "wrench_command", self._on_wrench, QoSProfile(depth=1, reliability=reliability))
        if vehicle.per_actuator_topics and not self._per_actuator:
            for actuator in vehicle.actuators:
                thrust = self.create_publisher(Float64, f"thrusters/{actuator.name}/thrust", 1)
                azimuth = (self.create_publisher(Float64, f"thrusters/{actuator.name}/azimuth", 1)
                           if actuator.rotatable else None)
                self._per_actuator[actuator.name] = (thrust, azimuth)
        elif not vehicle.per_actuator_topics and self._per_actuator:
            for thrust, azimuth in self._per_actuator.values():
                self.destroy_publisher(thrust)
                if azimuth is not None:
                    self.destroy_publisher(azimuth)
            self._per_actuator = {}

    # -- diagnostics --------------------------------------------------------------------

    def _on_diagnostics(self) -> None:
        with self._lock:
            status = self._diagnostic_status()
            self._counters.reset_period()
        array = DiagnosticArray()
        array.header.stamp = self.get_clock().now().to_msg()
        array.status = [status]
        self._diagnostics.publish(array)

    def _diagnostic_status(self) -> DiagnosticStatus:
        counters = self._counters
        allocator = self._allocator
        modes = allocator.modes()
        problems = []
        level = DiagnosticStatus.OK
        if self._stale:
            level = DiagnosticStatus.ERROR
            problems.append("stale wrench input: commanding zero thrust")
        warnings = [f"{name} {FaultMode(mode).name}" for name, mode in zip(allocator.names, modes) if mode]
        if counters.saturated:
            warnings.append(f"{counters.saturated} saturated samples")
        if counters.fallbacks:
            warnings.append(f"{counters.fallbacks} solver fallbacks")
        if counters.rejected_in_period:
            warnings.append(f"{counters.rejected_in_period} rejected inputs")
        warnings += allocator.warnings
        if warnings and level == DiagnosticStatus.OK:
            level = DiagnosticStatus.WARN
        problems += warnings
        status = DiagnosticStatus(level=level, name=f"{self.get_name()}: thrust allocation",
                                  hardware_id=self.get_fully_qualified_name(),
                                  message="; ".join(problems) if problems else "allocating")
        values = {
            "method": allocator.method,
            "rate_hz": f"{allocator.vehicle.rate_hz:g}",
            "samples in period": str(counters.samples),
            "saturated in period": str(counters.saturated),
            "fallbacks in period": str(counters.fallbacks),
            "fallbacks total": str(allocator.stats.fallbacks),
            "solver setups": str(allocator.stats.solver_setups),
            "max solve time in period [s]": f"{counters.max_solve_time:.6f}",
            "rejected wrenches": str(counters.rejected_wrenches),
            "rejected odometry": str(counters.rejected_odometry),
            "stale input": str(self._stale).lower(),
        }
        if self._last is not None:
            values["solver status"] = self._last.status
            values["iterations"] = str(self._last.iterations)
        if allocator.vehicle.has_surfaces:
            values["speed [m/s]"] = f"{allocator.speed:g}"
            unavailable = [a.name for a, ok in zip(allocator.vehicle.actuators, self._last.available) if not ok] \
                if self._last is not None else []
            values["unavailable"] = ", ".join(unavailable) or "none"
        if allocator.notes:
            values["actuation"] = "; ".join(allocator.notes)
        for name, mode in zip(allocator.names, modes):
            values[f"mode {name}"] = FaultMode(mode).name
        status.values = [KeyValue(key=key, value=value) for key, value in values.items()]
        return status


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
