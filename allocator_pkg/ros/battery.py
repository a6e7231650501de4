"""The supply voltage from ``battery_state`` (sensor_msgs/BatteryState), for thrust tables
measured at several voltages: each valid voltage sets the thrust limits
(``Allocator.set_voltage``); a NaN or out-of-table one is rejected, counted and logged, the last
valid one kept; with none for ``battery_timeout`` seconds the limits go back to
``nominal_voltage``, and the diagnostics say so. A voltage that arrives before a simulated clock
has started counts from the clock's first reading, not from time zero."""

from __future__ import annotations

import threading

from rclpy.constants import S_TO_NS
from rclpy.node import Node
from sensor_msgs.msg import BatteryState

from ..allocation.allocator import Allocator
from ..allocation.sample_rules import set_supply_voltage
from . import qos
from .diagnostics import LOG_THROTTLE, Counters


class BatteryInput:
    """The ``battery_state`` subscription of one runtime, until :meth:`close`; ``lock`` is the
    runtime's, held around every change of ``allocator``. ``fallback`` says whether
    nominal_voltage stands in for a battery voltage (as it does until the first valid one)."""

    def __init__(self, node: Node, lock: threading.Lock, allocator: Allocator, counters: Counters):
        self._node = node
        self._lock = lock
        self._allocator = allocator
        self._counters = counters
        self._clock = node.get_clock()
        self._time: int | None = None
        self.fallback = True
        self._subscription = node.create_subscription(BatteryState, "battery_state", self._on_battery,
                                                      qos.battery(), qos_overriding_options=qos.overridable())

    @property
    def topic_name(self) -> str:
        return self._subscription.topic_name

    def _on_battery(self, message: BatteryState) -> None:
        voltage = message.voltage
        with self._lock:
            try:
                set_supply_voltage(self._allocator, voltage)
            except ValueError as error:
                self._counters.rejected_battery += 1
                self._counters.rejected_in_period += 1
                reason = str(error)
            else:
                self._time = self._clock.now().nanoseconds or None    # 0: simulated time not started
                if self.fallback:
                    self.fallback = False
                    self._node.get_logger().info(f"supply voltage from {self.topic_name}: {voltage:.2f} V")
                return
        self._node.get_logger().warn(f"rejected battery state: {reason}; keeping "
                                     f"{self._allocator.voltage:g} V", throttle_duration_sec=LOG_THROTTLE)

    def check(self, now: int, timeout: float) -> None:
        """Back to the nominal voltage when no valid battery voltage came for ``timeout``
        seconds up to ``now`` [ns of the node clock]. Lock held."""
        if self.fallback:
            return
        if self._time is None:                # came before the clock started: counts from its start
            self._time = now
        if now - self._time > timeout * S_TO_NS:
            self.fallback = True
            nominal = self._allocator.vehicle.nominal_voltage
            self._allocator.set_voltage(nominal)
            self._node.get_logger().warn(f"no valid battery voltage on {self.topic_name} for {timeout:g} s: "
                                         f"thrust limits at nominal_voltage {nominal:g} V")

    def close(self) -> None:
        self._node.destroy_subscription(self._subscription)
