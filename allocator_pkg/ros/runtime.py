"""What runs while the allocator is configured, the same in ``allocator_node`` and
``allocator_lifecycle_node``: the allocator, its topics and timers, the watchdog and the
samples. A node builds one from checked parameters (:mod:`allocator_pkg.ros.node_base`),
activates it, deactivates it and closes it; nothing here parses parameters.

On a ``LifecycleNode`` every output is a lifecycle publisher (:mod:`~allocator_pkg.ros.outputs`),
which rclpy enables and disables with the node's state. The runtime's own
:meth:`~AllocationRuntime.activate` and :meth:`~AllocationRuntime.deactivate` start and stop the
timers and the sampling on a wrench, which rclpy leaves running.

A sample runs on the timer at ``rate_hz`` (``trigger: timer``), or at once on each valid
wrench (``trigger: input``) unless the last sample is less than a period old: the wrench then
waits, replaced by any newer one, for the timer, set to fire one period after that sample. In
both modes the timer runs the watchdog, and while the input is stale it commands zero thrust
every period. With the input trigger the timer fires only when something is due (a waiting
wrench, the moment the input would turn stale, every period while it is), so that a fast
rate_hz costs no idle wake-ups.

With thrust tables measured at several supply voltages, the runtime follows the voltage of
``battery_state`` (:mod:`~allocator_pkg.ros.battery`; its timeout checked with the diagnostics,
once a second), and with power sources the available power of ``power_available``
(:mod:`~allocator_pkg.ros.power_input`, the same way); ``~/set_group_fault`` fails a redundancy
group (:meth:`~AllocationRuntime.set_group_fault`), ``~/set_bus_tie`` opens or closes a bus tie.
On the bench, ``~/hold_actuator`` holds one actuator (:meth:`~AllocationRuntime.hold`,
:mod:`~allocator_pkg.ros.hold`); a stale input still stops it. With redundancy groups, each
sample feeds the consequence analysis' load filter; the analysis runs on a thread of its own
(:mod:`~allocator_pkg.ros.consequence_topic`).
"""

from __future__ import annotations

import threading

import numpy as np
from geometry_msgs.msg import Wrench, WrenchStamped
from nav_msgs.msg import Odometry
from rclpy.constants import S_TO_NS
from rclpy.node import Node

from allocator_msgs.msg import ActuatorFault

from ..allocation.allocator import AllocationResult, Allocator
from ..allocation.sample_rules import Watchdog, set_fault
from ..effectiveness.faults import FaultMode
from ..vehicle.config import Vehicle
from ..vehicle.node_settings import INPUT, TIMER, NodeSettings
from . import qos, wrench_input
from .battery import BatteryInput
from .capability_query import CapabilityQuery
from .consequence_topic import ConsequenceMonitor
from .diagnostics import LOG_THROTTLE, Counters, diagnostic_statuses
from .hold import Hold, refusal
from .outputs import Outputs
from .power_input import PowerInput

DIAGNOSTICS_PERIOD = 1.0     # s between two reports on /diagnostics


class AllocationRuntime:
    """``allocator`` on ``node`` for one checked configuration; ``geometry`` holds the flat
    parameters a robot description supplied (merged into every later parameter check).

    State shared between callbacks sits behind one lock, so that services, parameter changes
    and samples may come from any thread. ``active`` says whether the runtime samples: the
    timers run and a wrench (input trigger) starts a sample. ``power_input`` is the
    ``power_available`` input (None without power sources)."""

    def __init__(self, node: Node, allocator: Allocator, settings: NodeSettings, geometry: dict[str, list[float]]):
        self._node = node
        self._lock = threading.Lock()
        self.allocator = allocator
        vehicle = allocator.vehicle
        self.settings = settings
        self.geometry = geometry
        self.counters = Counters()
        self.watchdog = Watchdog(settings.wrench_timeout)
        self.samples = 0
        self.wrenches_received = 0
        self.active = False
        self._wrench = np.zeros(6)
        self._wrench_time: int | None = None
        self._waiting_wrench = False
        self._last_sample: int | None = None
        self._last: AllocationResult | None = None
        self._reported: set[str] = set()
        self._hold: Hold | None = None
        self._wrench_type = wrench_input.message_type(settings)
        self._clock = node.get_clock()
        self._outputs = Outputs(node, allocator, vehicle, settings)
        self._wrench_subscription = node.create_subscription(self._wrench_type, "wrench_command", self._on_wrench,
                                                             qos.wrench(), qos_overriding_options=qos.overridable())
        self._odometry = node.create_subscription(Odometry, "odometry", self._on_odometry, qos.odometry(),
                                                  qos_overriding_options=qos.overridable()) \
            if vehicle.has_surfaces else None
        self._battery = BatteryInput(node, self._lock, allocator, self.counters) \
            if vehicle.voltage_range is not None else None
        self.power_input = PowerInput(node, self._lock, allocator, self.counters) if vehicle.power_sources else None
        self._capability = CapabilityQuery()
        self._consequence = ConsequenceMonitor(node, self._lock, allocator, settings, self._outputs) \
            if vehicle.redundancy_groups else None
        self._period_ns = round(S_TO_NS / vehicle.rate_hz)
        self._timer = node.create_timer(1.0 / vehicle.rate_hz, self._on_timer, autostart=False)
        self._diagnostics_timer = node.create_timer(DIAGNOSTICS_PERIOD, self._on_diagnostics, autostart=False)

    @property
    def period(self) -> float:
        """The allocation period 1 / rate_hz [s]."""
        return self._period_ns * 1e-9

    @property
    def statuses_published(self) -> int:
        """How many AllocationStatus messages went out."""
        return self._outputs.statuses_published

    def topics(self) -> str:
        """The resolved names of the node's topics, for the start-up log."""
        wrench = self._wrench_subscription.topic_name
        outputs = self._outputs.topics
        text = (f"wrench from {wrench} ({wrench_input.TYPE_NAMES[self._wrench_type]}, frame "
                f"{self.settings.frame.upper()} '{self.settings.base_frame}', trigger {self.settings.trigger})")
        if self._odometry is not None:
            text += f", speed from {self._odometry.topic_name}"
        if self._battery is not None:
            text += f", supply voltage from {self._battery.topic_name}"
        if self.power_input is not None:
            text += f", available power from {self.power_input.topic_name}"
        return text + f"; publishing {', '.join(outputs)}"

    # -- life cycle ---------------------------------------------------------------------

    def activate(self) -> None:
        """Start sampling (the watchdog waits for the first wrench) and reporting. A managed
        node enables its lifecycle publishers first."""
        with self._lock:
            self.active = True
            self._last_sample = None
            self._timer.reset()
            self._diagnostics_timer.reset()
            if self._consequence is not None:
                self._consequence.activate()

    def deactivate(self) -> None:
        """Command zero thrust once, angles held, then stop sampling and reporting. A managed
        node disables its lifecycle publishers after this."""
        with self._lock:
            self._end_hold()
            if self.active:
                self._outputs.publish(self.allocator.stop(), self._clock.now().nanoseconds, "stopped: deactivated",
                                      always=True)
            self.active = False
            self._timer.cancel()
            self._diagnostics_timer.cancel()
            if self._consequence is not None:
                self._consequence.deactivate()

    def publish_stop(self, timeout: float) -> bool:
        """One zero-thrust command (shutdown), angles held; waits up to ``timeout`` seconds
        for every subscriber to acknowledge it (the node is about to go, and with it the
        reliable writer that would resend it). Whether all did."""
        with self._lock:
            self._outputs.publish(self.allocator.stop(), self._clock.now().nanoseconds, "stopped: shutting down",
                                  always=True)
        return self._outputs.wait_for_acknowledgement(timeout)

    def close(self) -> None:
        """Destroy every publisher, subscription and timer; the allocator (and its solver) goes with this object."""
        node = self._node
        with self._lock:
            self.active = False
            for timer in (self._timer, self._diagnostics_timer):
                node.destroy_timer(timer)
            for subscription in (self._wrench_subscription, self._odometry):
                if subscription is not None:
                    node.destroy_subscription(subscription)
            if self._battery is not None:
                self._battery.close()
            if self.power_input is not None:
                self.power_input.close()
            if self._consequence is not None:
                self._consequence.close()
            self._outputs.close()

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
            result = self.allocator.allocate(self._hold.wrench(self.allocator))
        else:
            result = self.allocator.allocate(self._wrench)
        self._waiting_wrench = False
        self._last_sample = now
        self.samples += 1
        self.counters.count(result)
        self._last = result
        if self._consequence is not None and not stale:
            self._consequence.observe(result.requested, now)
        self._outputs.publish(result, now, f"stale: no valid wrench for {self.watchdog.timeout:g} s" if stale
                              else result.status)

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
                return True, set_fault(self.allocator, fault.actuator, mode, fault.efficiency, fault.azimuth)
            except ValueError as error:
                return False, str(error)

    def set_group_fault(self, group: str) -> tuple[bool, str]:
        """Fail a redundancy group from the next sample; (success, message naming the groups)."""
        with self._lock:
            self._end_hold()
            try:
                self.allocator.set_group_fault(group)
            except ValueError as error:
                return False, str(error)
            members = self.allocator.power.group(group)
        return True, (f"{group}: {', '.join(members.actuators) or 'no actuators'} FAILED and "
                      f"{', '.join(members.sources) or 'no sources'} at 0 kW from the next sample")

    def set_bus_tie(self, name: str, closed: bool) -> tuple[bool, str]:
        """Open or close a bus tie from the next sample; (success, message naming the ties)."""
        with self._lock:
            try:
                return True, self.allocator.set_bus_tie(name, closed)
            except ValueError as error:
                return False, str(error)

    def clear_faults(self) -> str:
        """Every actuator back to NOMINAL, every source back to its available power; what was
        cleared."""
        with self._lock:
            self._end_hold()
            had = sorted(self.allocator.faults)
            groups = self.allocator.group_faults
            self.allocator.clear_faults()
        cleared = f"cleared faults of {', '.join(had)}" if had else "no faults were set"
        return cleared + (f" (redundancy groups {', '.join(groups)})" if groups else "")

    def capability(self, direction: np.ndarray) -> tuple[bool, str, float, np.ndarray]:
        """``~/get_capability`` for ``direction``, a wrench in the node's frame
        (:class:`~allocator_pkg.ros.capability_query.CapabilityQuery`)."""
        return self._capability.answer(self.allocator, self._lock, self.settings.frame, direction)

    def apply(self, vehicle: Vehicle, settings: NodeSettings) -> None:
        """A checked configuration of the same actuators, between two samples."""
        with self._lock:
            self._end_hold()
            self.allocator.reconfigure(vehicle)
            self._period_ns = round(S_TO_NS / vehicle.rate_hz)
            if settings.trigger == TIMER and self._timer.timer_period_ns != self._period_ns:
                self._timer.timer_period_ns = self._period_ns
            self._outputs.apply(vehicle, settings, self.active)
            if self._consequence is not None:
                self._consequence.apply(settings)
            self.settings = settings
            self.watchdog.timeout = settings.wrench_timeout

    # -- the bench: one actuator held ----------------------------------------------------

    def hold(self, actuator: str, thrust: float, duration: float) -> tuple[bool, str]:
        """Hold ``actuator`` at ``thrust`` [N] for ``duration`` [s], every other one FAILED, from
        the next sample; (success, message saying why not, :func:`~allocator_pkg.ros.hold.refusal`)."""
        with self._lock:
            now = self._clock.now().nanoseconds
            refused = refusal(self.allocator, self.settings, actuator, thrust, duration, self.active,
                              self.watchdog.is_stale(now, self._wrench_time))
            if refused is not None:
                return False, refused
            self._end_hold()
            end = now + round(duration * S_TO_NS)
            self._hold = Hold.start(self.allocator, actuator, thrust, end)
        self._node.get_logger().warn(f"step test: holding {actuator} at {thrust:g} N for {duration:g} s, every "
                                     "other actuator FAILED")
        return True, f"{actuator}: {thrust:g} N for {duration:g} s from the next sample, every other actuator FAILED"

    def _end_hold(self) -> None:
        """Put back the faults in force before the hold, if one runs. Lock held."""
        hold, self._hold = self._hold, None
        if hold is not None:
            hold.release(self.allocator)
            self._node.get_logger().info(f"step test: {self.allocator.names[hold.index]} released, faults as before")

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
            battery = self._battery
            if battery is not None:
                battery.check(self._clock.now().nanoseconds, self.settings.battery_timeout)
            report = None if battery is None else (battery.topic_name, battery.fallback)
            power = self.power_input
            if power is not None:
                power.check(self._clock.now().nanoseconds, self.settings.power_timeout,
                            self.settings.power_stale_fallback)
            statuses = diagnostic_statuses(node.get_fully_qualified_name(), self.allocator, self.counters,
                                           self.watchdog.stale, self._last, foreign, report,
                                           None if power is None else power.report)
            if self._consequence is not None:
                statuses.append(self._consequence.diagnostic(node.get_fully_qualified_name()))
            self.counters.reset_period()
        self._outputs.publish_diagnostics(statuses, self._clock.now().to_msg())
