"""The available power of each source from ``power_available`` (allocator_msgs/PowerAvailable,
kW), for a vehicle with ``power.sources``: each valid message sets the sources it names from the
next sample (``Allocator.set_available_power``); a message with an unknown source, a NaN or a
negative value, or lists of different lengths is rejected whole, counted and logged, the last
valid values kept. Until the first valid message every source is at its capacity. With none
valid for ``power_timeout`` seconds the input is stale: each source is held at the lower of its
last valid value and ``power_stale_fallback`` of its capacity (never back up to the capacity),
an error is logged and the diagnostics stay at ERROR until a valid message comes. A message
that arrives before a simulated clock has started counts from the clock's first reading, not
from time zero."""

from __future__ import annotations

import threading

import numpy as np
from rclpy.constants import S_TO_NS
from rclpy.node import Node

from allocator_msgs.msg import PowerAvailable

from ..allocation.allocator import Allocator
from ..allocation.sample_rules import set_available_power
from . import qos
from .diagnostics import LOG_THROTTLE, Counters
from .power_report import available_text


class PowerInput:
    """The ``power_available`` subscription of one runtime, until :meth:`close`; ``lock`` is the
    runtime's, held around every change of ``allocator``. ``fallback`` says whether the
    capacities stand in for reported values (as they do until the first valid message),
    ``stale`` whether the messages stopped (the last valid values held, or lower); ``received``
    counts the messages, valid or not."""

    def __init__(self, node: Node, lock: threading.Lock, allocator: Allocator, counters: Counters):
        self._node = node
        self._lock = lock
        self.allocator = allocator
        self._counters = counters
        self._clock = node.get_clock()
        self._time: int | None = None
        self.fallback = True
        self.stale = False
        self.received = 0
        self._subscription = node.create_subscription(PowerAvailable, "power_available", self._on_power,
                                                      qos.power(), qos_overriding_options=qos.overridable())

    @property
    def topic_name(self) -> str:
        return self._subscription.topic_name

    def _on_power(self, message: PowerAvailable) -> None:
        with self._lock:
            self.received += 1
            try:
                set_available_power(self.allocator, message.source, message.available)
            except ValueError as error:
                self._counters.rejected_power += 1
                self._counters.rejected_in_period += 1
                reason = str(error)
            else:
                self._time = self._clock.now().nanoseconds or None    # 0: simulated time not started
                if self.fallback or self.stale:
                    self.fallback = self.stale = False
                    self._node.get_logger().info(f"available power from {self.topic_name}")
                return
        self._node.get_logger().warn(f"rejected available power: {reason}; keeping the last valid values",
                                     throttle_duration_sec=LOG_THROTTLE)

    def check(self, now: int, timeout: float, fallback: float) -> None:
        """Stale when no valid message came for ``timeout`` seconds up to ``now`` [ns of the
        node clock]: every source held at the lower of its last valid value and ``fallback``
        (a share) of its capacity. Lock held."""
        if self.fallback or self.stale:
            return
        if self._time is None:                # came before the clock started: counts from its start
            self._time = now
        if now - self._time > timeout * S_TO_NS:
            self.stale = True
            budget = self.allocator.power
            held = np.minimum(budget.reported, fallback * budget.capacity)
            self.allocator.set_available_power(dict(zip(budget.sources, held.tolist())))
            self._node.get_logger().error(f"no valid available power on {self.topic_name} for {timeout:g} s: "
                                          f"holding {available_text(self.allocator.power)}")

    @property
    def report(self) -> tuple[str, bool, bool]:
        """(topic, fallback, stale) for the diagnostics."""
        return self.topic_name, self.fallback, self.stale

    def close(self) -> None:
        self._node.destroy_subscription(self._subscription)
