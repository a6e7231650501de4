"""What runs while the allocator is configured, the same in ``allocator_node`` and
``allocator_lifecycle_node``: the allocator, its topics and timers, the watchdog and the
samples. A node builds one from checked parameters (:mod:`allocator_pkg.ros.node_base`),
activates it, deactivates it and closes it; nothing here parses parameters.

On a ``LifecycleNode`` every output (commands, status, markers, diagnostics, per-actuator
and ros2_control topics) is a lifecycle publisher: rclpy enables them in the node's active state and drops
what they are given in any other. The runtime's own :meth:`~AllocationRuntime.activate` and
:meth:`~AllocationRuntime.deactivate` start and stop the timers and the sampling on a wrench,
which rclpy leaves running. On a plain ``Node`` the outputs are plain publishers.

A sample runs on the timer at ``rate_hz`` (``trigger: timer``), or at once on each valid
wrench (``trigger: input``) unless the last sample is less than a period old: the wrench then
waits, replaced by any newer one, for the timer, set to fire one period after that sample. In
both modes the timer runs the watchdog, and while the input is stale it commands zero thrust
every period. With the input trigger the timer fires only when something is due (a waiting
wrench, the moment the input would turn stale, every period while it is), so that a fast
rate_hz costs no idle wake-ups.

With thrust tables measured at several supply voltages, the runtime follows the voltage of
``battery_state`` (sensor_msgs/BatteryState): a NaN or out-of-table voltage is rejected,
counted and logged, the last valid one kept; with none for ``battery_timeout`` seconds the
thrust limits go back to ``nominal_voltage`` (checked with the diagnostics, once a second),
and the diagnostics say so.

On the bench (``step_test.enabled``), ``~/hold_actuator`` holds one actuator at a small thrust
for a bounded time (:meth:`~AllocationRuntime.hold`): every other actuator is set FAILED, and
each sample allocates the wrench the held thrust gives along the actuator's current direction,
so that the actuator alone meets it through the same limits, faults, rate limits and dead band
as any sample's. A stale input still stops it; when the hold ends (its duration, a fault
service, a parameter change, deactivation) the faults in force before come back.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Wrench, WrenchStamped
from lifecycle_msgs.msg import State
from nav_msgs.msg import Odometry
from rclpy.constants import S_TO_NS
from rclpy.duration import Duration
from rclpy.lifecycle import LifecycleNode, LifecyclePublisher, LifecycleState
from rclpy.node import Node
from rclpy.publisher import Publisher
from rclpy.qos import QoSProfile
from sensor_msgs.msg import BatteryState
from std_msgs.msg import Header
from visualization_msgs.msg import MarkerArray

from allocator_msgs.msg import ActuatorFault, AllocationStatus, ThrusterCommands

from ..allocation.allocator import AllocationResult, Allocator
from ..analysis.capability import Capability
from ..effectiveness.faults import Fault, FaultMode
from ..vehicle.config import Vehicle
from ..vehicle.frames import wrench_between
from ..vehicle.node_settings import INPUT, TIMER, NodeSettings
from . import qos, wrench_input
from .actuator_topics import ActuatorTopics
from .conversions import commands_message, status_message
from .diagnostics import Counters, diagnostic_statuses
from .markers import thrust_markers
from .ros2_control import Ros2ControlOutput, ros2_control_changed
from .watchdog import Watchdog

DIAGNOSTICS_PERIOD = 1.0
LOG_THROTTLE = 5.0
ACTIVE = LifecycleState("active", State.PRIMARY_STATE_ACTIVE)


def status_period(settings: NodeSettings) -> int:
    """The shortest time [ns] between two statuses, 1 / status_rate_hz (0: every sample)."""
    rate = settings.status_rate_hz
    return round(S_TO_NS / rate) if rate > 0.0 else 0


@dataclass
class Hold:
    """One actuator held (``index``) at ``thrust`` [N] until ``end`` [ns of the node clock]; the
    faults in force before it."""

    index: int
    thrust: float
    end: int
    faults: dict[str, Fault]


class AllocationRuntime:
    """The allocation on ``node`` for one checked configuration; ``geometry`` holds the flat
    parameters a robot description supplied (merged into every later parameter check).

    State shared between callbacks sits behind one lock, so that services, parameter changes
    and samples may come from any thread. ``active`` says whether the runtime samples: the
    timers run and a wrench (input trigger) starts a sample."""

    def __init__(self, node: Node, vehicle: Vehicle, settings: NodeSettings, geometry: dict[str, list[float]]):
        self._node = node
        self._lock = threading.Lock()
        self.allocator = Allocator(vehicle)
        self.settings = settings
        self.geometry = geometry
        self.counters = Counters()
        self.watchdog = Watchdog(settings.wrench_timeout)
        self.samples = 0
        self.statuses_published = 0
        self.wrenches_received = 0
        self.active = False
        self._wrench = np.zeros(6)
        self._wrench_time: int | None = None
        self._waiting_wrench = False
        self._last_sample: int | None = None
        self._last: AllocationResult | None = None
        self._markers_due = 0
        self._reported: set[str] = set()
        self._hold: Hold | None = None
        self._wrench_type = wrench_input.message_type(settings)
        self._clock = node.get_clock()
        self._commands = self._output(ThrusterCommands, "thruster_commands", qos.output())
        self._status = self._output(AllocationStatus, "allocation_status", qos.output())
        self._status_last: int | None = None
        self._status_period = status_period(settings)
        # Filled and published again every sample, always under the lock (making them anew costs
        # more than filling them); both share one header, its stamp set in place.
        self._commands_message, self._status_message = ThrusterCommands(), AllocationStatus()
        self._header = Header(frame_id=settings.base_frame)
        self._diagnostics = self._output(DiagnosticArray, "/diagnostics", qos.diagnostics())
        self._markers = self._output(MarkerArray, "~/thrust_markers", qos.output())
        self._wrench_subscription = node.create_subscription(self._wrench_type, "wrench_command", self._on_wrench,
                                                             qos.wrench(), qos_overriding_options=qos.overridable())
        self._odometry = node.create_subscription(Odometry, "odometry", self._on_odometry, qos.odometry(),
                                                  qos_overriding_options=qos.overridable()) \
            if vehicle.has_surfaces else None
        self._battery = node.create_subscription(BatteryState, "battery_state", self._on_battery, qos.battery(),
                                                 qos_overriding_options=qos.overridable()) \
            if vehicle.voltage_range is not None else None
        self._battery_time: int | None = None
        self.battery_fallback = vehicle.voltage_range is not None
        self._capability: Capability | None = None
        self._per_actuator: ActuatorTopics | None = None
        self._apply_per_actuator(settings)
        self._ros2_control = Ros2ControlOutput(vehicle, settings, self._output, self._destroy_output)
        self._period_ns = round(S_TO_NS / vehicle.rate_hz)
        self._timer = node.create_timer(1.0 / vehicle.rate_hz, self._on_timer, autostart=False)
        self._diagnostics_timer = node.create_timer(DIAGNOSTICS_PERIOD, self._on_diagnostics, autostart=False)

    @property
    def period(self) -> float:
        """The allocation period 1 / rate_hz [s]."""
        return self._period_ns * 1e-9

    def topics(self) -> str:
        """The resolved names of the node's topics, for the start-up log."""
        wrench = self._wrench_subscription.topic_name
        outputs = [self._commands.topic_name, self._status.topic_name, self._markers.topic_name,
                   self._diagnostics.topic_name, *self._ros2_control.topics]
        text = (f"wrench from {wrench} ({wrench_input.TYPE_NAMES[self._wrench_type]}, frame "
                f"{self.settings.frame.upper()} '{self.settings.base_frame}', trigger {self.settings.trigger})")
        if self._odometry is not None:
            text += f", speed from {self._odometry.topic_name}"
        if self._battery is not None:
            text += f", supply voltage from {self._battery.topic_name}"
        return text + f"; publishing {', '.join(outputs)}"

    # -- outputs ------------------------------------------------------------------------

    def _output(self, message_type: type, topic: str, profile: QoSProfile) -> Publisher:
        """A publisher of one output: a lifecycle publisher on a LifecycleNode, a plain one on a
        Node. rclpy enables lifecycle publishers when the node activates; one made while the
        runtime is active (per_actuator_topics set then) is enabled here, like the others."""
        node = self._node
        if not isinstance(node, LifecycleNode):
            return node.create_publisher(message_type, topic, profile, qos_overriding_options=qos.overridable())
        publisher = node.create_lifecycle_publisher(message_type, topic, profile,
                                                    qos_overriding_options=qos.overridable())
        if self.active:
            publisher.on_activate(ACTIVE)
        return publisher

    def _destroy_output(self, publisher: Publisher) -> None:
        """Destroy an output publisher (a lifecycle one leaves the node's managed entities)."""
        if isinstance(publisher, LifecyclePublisher):
            self._node.destroy_lifecycle_publisher(publisher)
        else:
            self._node.destroy_publisher(publisher)

    # -- life cycle ---------------------------------------------------------------------

    def activate(self) -> None:
        """Start sampling (the watchdog waits for the first wrench) and reporting. A managed
        node enables its lifecycle publishers first."""
        with self._lock:
            self.active = True
            self._last_sample = None
            self._timer.reset()
            self._diagnostics_timer.reset()

    def deactivate(self) -> None:
        """Command zero thrust once, angles held, then stop sampling and reporting. A managed
        node disables its lifecycle publishers after this."""
        with self._lock:
            self._end_hold()
            if self.active:
                self._publish(self.allocator.stop(), self._clock.now().nanoseconds, "stopped: deactivated",
                              always=True)
            self.active = False
            self._timer.cancel()
            self._diagnostics_timer.cancel()

    def publish_stop(self, timeout: float) -> bool:
        """One zero-thrust command (shutdown), angles held; waits up to ``timeout`` seconds
        for every subscriber to acknowledge it (the node is about to go, and with it the
        reliable writer that would resend it). Whether all did."""
        with self._lock:
            self._publish(self.allocator.stop(), self._clock.now().nanoseconds, "stopped: shutting down",
                          always=True)
        return self._commands.wait_for_all_acked(Duration(seconds=timeout))

    def close(self) -> None:
        """Destroy every publisher, subscription and timer; the allocator (and its solver) goes with this object."""
        node = self._node
        with self._lock:
            self.active = False
            for timer in (self._timer, self._diagnostics_timer):
                node.destroy_timer(timer)
            for subscription in (self._wrench_subscription, self._odometry, self._battery):
                if subscription is not None:
                    node.destroy_subscription(subscription)
            if self._per_actuator is not None:
                self._per_actuator.close()
            self._ros2_control.close()
            for publisher in (self._commands, self._status, self._diagnostics, self._markers):
                self._destroy_output(publisher)

    # -- inputs -------------------------------------------------------------------------

    def _on_wrench(self, message: Wrench | WrenchStamped) -> None:
        verdict = wrench_input.accept(message, self.settings)
        with self._lock:
            self.wrenches_received += 1
            if verdict.wrench is None:
                self.counters.rejected_wrenches += 1
                self.counters.rejected_frames += verdict.kind == "frame"
                self.counters.rejected_in_period += 1
            else:
                now = self._clock.now().nanoseconds
                self._wrench = verdict.wrench
                self._wrench_time = now
                if self.active and self.settings.trigger == INPUT:
                    waiting = self._waiting_wrench
                    self._waiting_wrench = True
                    if self._last_sample is None or now - self._last_sample >= self._period_ns:
                        self._sample(now)
                        self._schedule(now)
                    elif not waiting:
                        self._arm(self._last_sample + self._period_ns - now)
        if verdict.wrench is None:
            self._node.get_logger().warn(verdict.reason, throttle_duration_sec=LOG_THROTTLE)

    def _on_odometry(self, message: Odometry) -> None:
        speed = message.twist.twist.linear.x
        with self._lock:
            if np.isfinite(speed):
                self.allocator.set_speed(speed)
                return
            self.counters.rejected_odometry += 1
            self.counters.rejected_in_period += 1
        self._node.get_logger().warn("rejected odometry with a non-finite surge speed",
                                     throttle_duration_sec=LOG_THROTTLE)

    def _on_battery(self, message: BatteryState) -> None:
        voltage = message.voltage
        with self._lock:
            try:
                self.allocator.set_voltage(voltage)
            except ValueError as error:
                self.counters.rejected_battery += 1
                self.counters.rejected_in_period += 1
                reason = str(error)
            else:
                self._battery_time = self._clock.now().nanoseconds
                if self.battery_fallback:
                    self.battery_fallback = False
                    self._node.get_logger().info(f"supply voltage from {self._battery.topic_name}: {voltage:.2f} V")
                return
        self._node.get_logger().warn(f"rejected battery state: {reason}; keeping "
                                     f"{self.allocator.voltage:g} V", throttle_duration_sec=LOG_THROTTLE)

    def _check_battery(self, now: int) -> None:
        """Back to the nominal voltage when no valid battery voltage came for battery_timeout. Lock held."""
        if self._battery is None or self.battery_fallback:
            return
        if self._battery_time is None or now - self._battery_time > self.settings.battery_timeout * S_TO_NS:
            self.battery_fallback = True
            nominal = self.allocator.vehicle.nominal_voltage
            self.allocator.set_voltage(nominal)
            self._node.get_logger().warn(f"no valid battery voltage on {self._battery.topic_name} for "
                                         f"{self.settings.battery_timeout:g} s: thrust limits at nominal_voltage "
                                         f"{nominal:g} V")

    # -- the sample ---------------------------------------------------------------------

    def _on_timer(self) -> None:
        with self._lock:
            if self.active:
                now = self._clock.now().nanoseconds
                self._sample(now)
                if self.settings.trigger == INPUT:
                    self._schedule(now, exact=True)

    def _schedule(self, now: int, exact: bool = False) -> None:
        """Input trigger, after the timer or a sample: the next time the timer has work. Lock
        held. ``exact`` after the timer fired (its next call is a whole period of its own away,
        which may be sooner than needed), else a timer due sooner is kept."""
        if self.watchdog.stale or self._waiting_wrench:
            self._arm(self._period_ns, exact)
        elif self.watchdog.timeout > 0.0 and self._wrench_time is not None:
            self._arm(self._wrench_time + round(self.watchdog.timeout * S_TO_NS) - now + self._period_ns, exact)
        else:
            self._arm(round(S_TO_NS * DIAGNOSTICS_PERIOD), exact)          # nothing can fall due: a slow heartbeat

    def _arm(self, delay: int, exact: bool = True) -> None:
        """Have the timer fire ``delay`` ns from now; unless ``exact``, a timer already due sooner
        is left alone (when it fires early it finds nothing due and is armed again then), so
        that a steady input re-arms it about once per watchdog timeout or heartbeat, not every
        sample."""
        timer = self._timer
        if not exact and not timer.is_canceled():
            until = timer.time_until_next_call()
            if until is not None and 0 <= until <= delay:
                return
        timer.timer_period_ns = max(delay, 1)
        timer.reset()

    def _sample(self, now: int) -> None:
        """Check the watchdog at ``now`` [ns of the node clock]; allocate the latest wrench (zero
        thrust while it is stale) unless the trigger is the input and no wrench waits. Called
        with the lock held."""
        stale, transition = self.watchdog.check(now, self._wrench_time)
        if transition is not None and transition[0] == "warn":
            self._node.get_logger().warn(transition[1])
        elif transition is not None:
            self._node.get_logger().info(transition[1])
        if not (stale or self._waiting_wrench or self.settings.trigger == TIMER):
            return
        if self._hold is not None and (stale or now >= self._hold.end):
            self._end_hold()
        if stale:
            result = self.allocator.stop()
        elif self._hold is not None:
            result = self.allocator.allocate(self._held_wrench())
        else:
            result = self.allocator.allocate(self._wrench)
        self._waiting_wrench = False
        self._last_sample = now
        self.samples += 1
        self.counters.count(result)
        self._last = result
        self._publish(result, now, f"stale: no valid wrench for {self.watchdog.timeout:g} s" if stale
                      else result.status)

    def _publish(self, result: AllocationResult, now: int, status: str, always: bool = False) -> None:
        """The sample's outputs, stamped ``now`` [ns]. The status goes out only while someone
        subscribes, and at most status_rate_hz times a second (0: every sample) unless
        ``always`` (a stop)."""
        header = self._header
        stamp = header.stamp
        stamp.sec, stamp.nanosec = divmod(now, S_TO_NS)
        self._commands.publish(commands_message(result, self.allocator.names, header, self._commands_message))
        # Due every sample, at a stop, or once a period of status_rate_hz has passed since the last
        # status (or the clock was set back, as a simulator restarting does).
        period, last = self._status_period, self._status_last
        due = always or not period or last is None or not 0 <= now - last < period
        if due and self._status.get_subscription_count():
            self._status_last = now
            self._status.publish(status_message(result, status, header, self.settings.frame, self.allocator.voltage,
                                                self._status_message))
            self.statuses_published += 1
        if self._per_actuator is not None:
            self._per_actuator.publish(result)
        self._ros2_control.publish(result)
        rate = self.settings.markers_rate_hz
        if rate > 0.0 and now >= self._markers_due:
            self._markers_due = now + round(S_TO_NS / rate)
            if self._markers.get_subscription_count():
                limits = self.allocator.ranges
                self._markers.publish(thrust_markers(self.allocator.vehicle, result, limits, header,
                                                     self.settings.frame))

    # -- faults and parameters ------------------------------------------------------------

    def set_fault(self, fault: ActuatorFault) -> tuple[bool, str]:
        """Set one actuator's fault from the next sample; (success, message naming the valid choices)."""
        try:
            mode = FaultMode(fault.mode)
        except ValueError:
            return False, (f"unknown mode {fault.mode}; modes: NOMINAL={ActuatorFault.NOMINAL}, "
                           f"DEGRADED={ActuatorFault.DEGRADED}, FAILED={ActuatorFault.FAILED}, "
                           f"STUCK={ActuatorFault.STUCK}")
        with self._lock:
            self._end_hold()
            try:
                self.allocator.set_fault(fault.actuator, mode, efficiency=fault.efficiency, angle=fault.azimuth)
            except ValueError as error:
                return False, str(error)
        return True, f"{fault.actuator}: {mode.name} from the next sample"

    def clear_faults(self) -> str:
        """Every actuator back to NOMINAL; what was cleared."""
        with self._lock:
            self._end_hold()
            had = sorted(self.allocator.faults)
            self.allocator.clear_faults()
        return f"cleared faults of {', '.join(had)}" if had else "no faults were set"

    def capability(self, direction: np.ndarray) -> tuple[bool, str, float, np.ndarray]:
        """The largest scale along ``direction`` (a wrench in the node's frame) under the faults,
        voltage and speed in force, and the wrench there in the node's frame: (success,
        message, scale, wrench). The analysis is built once per configuration."""
        if not np.all(np.isfinite(direction)):
            return False, f"the direction must be finite, got {direction.tolist()}", 0.0, np.zeros(6)
        body = wrench_between(direction, self.settings.frame)
        with self._lock:
            allocator = self.allocator
            if self._capability is None or self._capability.vehicle is not allocator.vehicle:
                try:
                    self._capability = Capability(allocator.vehicle, allocator.method, allocator.speed)
                except ValueError as error:
                    return False, str(error), 0.0, np.zeros(6)
            faults, speed, voltage = allocator.faults, allocator.speed, allocator.voltage
            capability = self._capability
        if not np.any(body[list(capability.vehicle.dof_indices)]):
            return False, (f"the direction has no component in the controlled DOFs "
                           f"({', '.join(capability.vehicle.dofs)})"), 0.0, np.zeros(6)
        scale, wrench = capability.reach(body, faults, speed, voltage)
        where = f", {voltage:g} V" if voltage is not None else ""
        return True, (f"steady state with {len(faults)} faults, speed {speed:g} m/s{where}, method "
                      f"{capability.method}"), scale, wrench_between(wrench, self.settings.frame)

    def apply(self, vehicle: Vehicle, settings: NodeSettings) -> None:
        """A checked configuration of the same actuators, between two samples."""
        with self._lock:
            self._end_hold()
            self.allocator.reconfigure(vehicle)
            self._period_ns = round(S_TO_NS / vehicle.rate_hz)
            if settings.trigger == TIMER and self._timer.timer_period_ns != self._period_ns:
                self._timer.timer_period_ns = self._period_ns
            self._apply_per_actuator(settings)
            if ros2_control_changed(self.settings, settings):
                self._ros2_control.close()
                self._ros2_control = Ros2ControlOutput(vehicle, settings, self._output, self._destroy_output)
            self.settings = settings
            self.watchdog.timeout = settings.wrench_timeout
            self._status_period = status_period(settings)
            self._status_last = None                # a new status_rate_hz from the next sample

    # -- the bench: one actuator held ----------------------------------------------------

    def hold(self, actuator: str, thrust: float, duration: float) -> tuple[bool, str]:
        """Hold ``actuator`` at ``thrust`` [N] for ``duration`` [s], every other one FAILED, from
        the next sample; (success, message saying why not). Refused unless step_test.enabled,
        beyond step_test.thrust_share of the actuator's largest thrust or step_test.duration_max,
        for a control surface, for an actuator acting on no controlled DOF, and while inactive."""
        settings = self.settings
        if not settings.step_test_enabled:
            return False, "refused: step_test.enabled is false (enable it on the bench only)"
        with self._lock:
            allocator = self.allocator
            names = allocator.names
            if actuator not in names:
                return False, f"unknown actuator '{actuator}'; actuators: {', '.join(names)}"
            index = names.index(actuator)
            config = allocator.vehicle.actuators[index]
            if config.is_surface:
                return False, f"{actuator} is a control surface: it has no thrust of its own to hold"
            largest = max(config.thrust_max, -config.thrust_min)
            limit = settings.step_test_thrust_share * largest
            if not (math.isfinite(thrust) and abs(thrust) <= limit):
                return False, (f"thrust {thrust:g} N of {actuator}: at most {limit:g} N in magnitude "
                               f"(step_test.thrust_share {settings.step_test_thrust_share:g} of {largest:g} N)")
            if not (math.isfinite(duration) and 0.0 < duration <= settings.step_test_duration_max):
                return False, f"duration {duration:g} s: more than 0 and at most step_test.duration_max " \
                              f"{settings.step_test_duration_max:g} s"
            if not self.active:
                return False, "not active: no samples to hold an actuator in"
            column = allocator.configuration_matrix()[list(allocator.vehicle.dof_indices), index]
            if not np.any(column):
                return False, f"{actuator} acts on none of the controlled DOFs ({', '.join(allocator.dofs)})"
            self._end_hold()
            saved = allocator.faults
            for name in names:
                if name != actuator:
                    allocator.set_fault(name, FaultMode.FAILED)
            end = self._clock.now().nanoseconds + round(duration * S_TO_NS)
            self._hold = Hold(index, float(thrust), end, saved)
        self._node.get_logger().warn(f"step test: holding {actuator} at {thrust:g} N for {duration:g} s, every "
                                     "other actuator FAILED")
        return True, f"{actuator}: {thrust:g} N for {duration:g} s from the next sample, every other actuator FAILED"

    def _held_wrench(self) -> np.ndarray:
        """The wrench (FRD) the held thrust gives along the held actuator's current direction. Lock held."""
        hold = self._hold
        return self.allocator.configuration_matrix()[:, hold.index] * hold.thrust

    def _end_hold(self) -> None:
        """Put back the faults in force before the hold, if one runs. Lock held."""
        hold, self._hold = self._hold, None
        if hold is None:
            return
        allocator = self.allocator
        allocator.clear_faults()
        for name, fault in hold.faults.items():
            allocator.set_fault(name, fault.mode, efficiency=fault.efficiency, angle=fault.angle)
        self._node.get_logger().info(f"step test: {allocator.names[hold.index]} released, faults as before")

    def _apply_per_actuator(self, settings: NodeSettings) -> None:
        if settings.per_actuator_topics and self._per_actuator is None:
            self._per_actuator = ActuatorTopics(self.allocator.vehicle, self._output, self._destroy_output)
        elif not settings.per_actuator_topics and self._per_actuator is not None:
            self._per_actuator.close()
            self._per_actuator = None

    # -- diagnostics --------------------------------------------------------------------

    def _on_diagnostics(self) -> None:
        node = self._node
        topic = self._wrench_subscription.topic_name
        foreign = wrench_input.foreign_publishers(node, topic, wrench_input.TYPE_NAMES[self._wrench_type])
        for publisher in sorted(set(foreign) - self._reported):
            node.get_logger().warn(f"a publisher of another type on {topic} never connects: {publisher}; this "
                                   f"node takes {wrench_input.TYPE_NAMES[self._wrench_type]} "
                                   f"(wrench_type: {self.settings.wrench_type})")
        self._reported.update(foreign)
        with self._lock:
            self._check_battery(self._clock.now().nanoseconds)
            battery = None if self._battery is None else (self._battery.topic_name, self.battery_fallback)
            statuses = diagnostic_statuses(node.get_fully_qualified_name(), self.allocator, self.counters,
                                           self.watchdog.stale, self._last, foreign, battery)
            self.counters.reset_period()
        self._diagnostics.publish(DiagnosticArray(header=Header(stamp=self._clock.now().to_msg()),
                                                  status=statuses))
