"""The online consequence analysis in the node (docs/power.md): ``~/consequence``, the status's
``consequence_alarm`` and a diagnostic status, for a vehicle with redundancy groups.

The sample path only feeds the load filter (:meth:`ConsequenceMonitor.observe`: the first-order
low-pass of the requested wrench of :class:`~allocator_pkg.capability.load_filter.LoadFilter`, a
few operations on six numbers, under the runtime's lock). A timer at ``consequence.rate`` on the
node's clock takes a snapshot under that lock (the filtered load, the configuration, and what the
allocator has in force: its faults, the available power with the failed groups' sources at 0 kW,
speed and voltage, :class:`~allocator_pkg.capability.group_loss.InForce`) and hands it to a thread
of the monitor's own, which solves each group's programme
(:class:`~allocator_pkg.capability.consequence.Consequence`; HiGHS lets go of the GIL while it
solves), publishes the answer and sets the alarm. That thread never takes the runtime's lock, so
no sample waits for an analysis.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np
from diagnostic_msgs.msg import DiagnosticStatus, KeyValue
from rclpy.constants import S_TO_NS
from rclpy.node import Node

from allocator_msgs.msg import ConsequenceAnalysis, GroupConsequence

from ..allocation.allocator import Allocator
from ..allocation.sample_rules import consequence_period
from ..capability.consequence import Consequence, GroupUtilisation
from ..capability.group_loss import InForce
from ..capability.load_filter import LoadFilter
from ..vehicle.config import Vehicle
from ..vehicle.node_settings import NodeSettings
from .conversions import fill_wrench_in
from .outputs import Outputs


@dataclass(frozen=True)
class Snapshot:
    """What one analysis needs, taken at once under the runtime's lock: the configuration and
    method, the filtered load [X, Y, Z, K, M, N] (FRD), what the allocator has in force (a
    group's loss comes on top of it), the time [ns of the node clock], the frame convention and
    name of the message."""

    vehicle: Vehicle
    method: str
    load: np.ndarray
    in_force: InForce
    stamp: int
    frame: str
    base_frame: str


def consequence_message(snapshot: Snapshot, groups: tuple[GroupUtilisation, ...]) -> ConsequenceAnalysis:
    """The analysis of ``snapshot``: its load in the controlled DOFs (in the node's frame
    convention), each group's utilisation and margin, and whether any group alarms."""
    message = ConsequenceAnalysis(alarm=any(group.alarm for group in groups))
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(snapshot.stamp, S_TO_NS)
    message.header.frame_id = snapshot.base_frame
    load = np.zeros(6)
    controlled = list(snapshot.vehicle.dof_indices)
    load[controlled] = snapshot.load[controlled]
    fill_wrench_in(message.load, load, snapshot.frame)
    message.groups = [GroupConsequence(group=group.group, utilisation=group.utilisation, margin=group.margin)
                      for group in groups]
    return message


def consequence_status(node_name: str, rate: float, groups: tuple[GroupUtilisation, ...] | None,
                       lost: tuple[str, ...] = ()) -> DiagnosticStatus:
    """``<node>: consequence analysis``: ERROR naming every group whose loss would leave too
    little for the present load, else OK with the worst group; each group's utilisation and
    the power sources the analysis took as ``lost`` already."""
    status = DiagnosticStatus(level=DiagnosticStatus.OK, name=f"{node_name}: consequence analysis",
                              hardware_id=node_name)
    if rate <= 0.0:
        status.message = "off (consequence.rate 0)"
        return status
    if groups is None:
        status.message = "no analysis yet"
        return status
    if any(group.alarm for group in groups):
        status.level = DiagnosticStatus.ERROR
        status.message = alarm_text(groups)
    else:
        worst = max(groups, key=lambda group: group.utilisation)
        status.message = f"every group's loss leaves enough; worst {worst.group} at {_percent(worst.utilisation)}"
    status.values = [KeyValue(key=f"utilisation {group.group}", value=f"{group.utilisation:.4f}") for group in groups]
    status.values.append(KeyValue(key="sources already lost", value=", ".join(lost) or "none"))
    status.values.append(KeyValue(key="rate [Hz]", value=f"{rate:g}"))
    return status


def alarm_text(groups: tuple[GroupUtilisation, ...]) -> str:
    """The consequence alarm in words, naming each group whose loss leaves too little."""
    return "consequence alarm: the present load could not be held after the loss of " + ", ".join(
        f"{group.group} ({_percent(group.utilisation)} of what it leaves)" for group in groups if group.alarm)


def _percent(utilisation: float) -> str:
    return "more than it gives in that direction" if math.isinf(utilisation) else f"{100.0 * utilisation:.0f} %"


class ConsequenceMonitor:
    """The analysis of ``allocator``'s vehicle on ``node``: the load filter, the timer, the thread,
    and the last answer (``groups``, ``alarm``). Published through ``outputs``."""

    def __init__(self, node: Node, lock: threading.Lock, allocator: Allocator, settings: NodeSettings,
                 outputs: Outputs):
        self._node = node
        self._lock = lock
        self._allocator = allocator
        self._outputs = outputs
        self._settings = settings
        self._filter = LoadFilter()
        self._active = False
        self.groups: tuple[GroupUtilisation, ...] | None = None
        self.lost: tuple[str, ...] = ()
        self.alarm = False
        self._ready = threading.Condition()
        self._pending: Snapshot | None = None
        self._closed = False
        self._timer = node.create_timer(self._period(settings) / S_TO_NS, self._on_timer, autostart=False)
        self._thread = threading.Thread(target=self._work, name="consequence analysis", daemon=True)
        self._thread.start()

    @staticmethod
    def _period(settings: NodeSettings) -> int:
        """[ns] of the timer (:func:`~allocator_pkg.allocation.sample_rules.consequence_period`;
        one second while the analysis is off)."""
        return consequence_period(settings.consequence_rate) or S_TO_NS

    def observe(self, wrench: np.ndarray, now: int) -> None:
        """One sample's requested wrench (FRD) at ``now`` [ns] into the low-pass filter, with
        the weight 1 - exp(-dt / consequence.filter_time) (the first, after the clock went back
        or without a filter: the wrench itself). Lock held."""
        self._filter.observe(wrench, now, self._settings.consequence_filter_time)

    def diagnostic(self, node_name: str) -> DiagnosticStatus:
        return consequence_status(node_name, self._settings.consequence_rate, self.groups, self.lost)

    def activate(self) -> None:
        """Start analysing (lock held)."""
        self._active = True
        self._filter.restart()
        if self._settings.consequence_rate > 0.0:
            self._timer.reset()

    def deactivate(self) -> None:
        """Stop analysing; an analysis under way is not published (lock held)."""
        self._active = False
        self._timer.cancel()

    def apply(self, settings: NodeSettings) -> None:
        """New node settings (lock held): the rate from now, the filter's time constant from the
        next sample; rate 0 clears the alarm."""
        self._settings = settings
        if settings.consequence_rate <= 0.0:
            self._timer.cancel()
            self._set_alarm(False)
            self.groups = None
            return
        self._timer.timer_period_ns = self._period(settings)
        if self._active:
            self._timer.reset()

    def close(self) -> None:
        """Stop the timer and the thread (lock held; the thread never takes it)."""
        self._active = False
        with self._ready:
            self._closed = True
            self._ready.notify()
        self._thread.join()
        self._node.destroy_timer(self._timer)

    def _on_timer(self) -> None:
        """The executor's part: a snapshot for the thread (the last one not yet taken is replaced)."""
        allocator, settings = self._allocator, self._settings
        with self._lock:
            if not self._active:
                return
            snapshot = Snapshot(allocator.vehicle, allocator.method, self._filter.load.copy(), InForce.of(allocator),
                                self._node.get_clock().now().nanoseconds, settings.frame, settings.base_frame)
        with self._ready:
            self._pending = snapshot
            self._ready.notify()

    def _work(self) -> None:
        """The thread: one analysis per snapshot, its programmes set up again when the
        configuration or method changes."""
        analysis: Consequence | None = None
        while True:
            with self._ready:
                while self._pending is None and not self._closed:
                    self._ready.wait()
                if self._closed:
                    return
                snapshot, self._pending = self._pending, None
            try:
                if analysis is None or analysis.vehicle is not snapshot.vehicle or analysis.method != snapshot.method:
                    analysis = Consequence(snapshot.vehicle, snapshot.method)
                groups = analysis.utilisation(snapshot.load, snapshot.in_force)
                if self._active and self._settings.consequence_rate > 0.0:
                    self._report(snapshot, groups)
            except Exception as error:          # the thread must outlive any one analysis
                self._node.get_logger().error(f"consequence analysis failed: {type(error).__name__}: {error}")

    def _report(self, snapshot: Snapshot, groups: tuple[GroupUtilisation, ...]) -> None:
        """The alarm and diagnostics first, so that whoever has the message finds them in force."""
        message = consequence_message(snapshot, groups)
        was, self.groups = self.alarm, groups
        self.lost = snapshot.in_force.lost_sources(snapshot.vehicle)
        self._set_alarm(message.alarm)
        if message.alarm != was:
            logger = self._node.get_logger()
            if message.alarm:
                logger.error(alarm_text(groups))
            else:
                logger.info("consequence alarm cleared: every group's loss leaves enough for the present load")
        self._outputs.publish_consequence(message)

    def _set_alarm(self, alarm: bool) -> None:
        self.alarm = alarm
        self._outputs.consequence_alarm = alarm
