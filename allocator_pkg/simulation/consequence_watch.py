"""The online consequence analysis of the in-process link (docs/power.md, "Consequence
analysis"): what ``allocator_node`` does for a vehicle with redundancy groups
(``ros/consequence_topic.py``), sample by sample in this process. Each allocated sample feeds
the node's low-pass filter of the requested wrench
(:class:`~allocator_pkg.capability.load_filter.LoadFilter`); at every multiple of the
analysis period 1 / ``consequence.rate`` of the sim clock, the
:class:`~allocator_pkg.capability.consequence.Consequence` analysis of the load filtered up to
the sample before, under what the allocator has in force (``InForce``), sets the alarm that
the statuses carry from that sample on.

The node analyses on a thread of its own, started by a timer on the same clock: its alarm
reaches the statuses a sample or more after its timer fired, while here it reaches the
sample of that clock step. An alarm time of the two links can so differ by up to one analysis
period; everything else of a run is the same."""

from __future__ import annotations

import numpy as np

from ..allocation.allocator import Allocator
from ..allocation.sample_rules import consequence_period
from ..capability.consequence import Consequence
from ..capability.group_loss import InForce
from ..capability.load_filter import LoadFilter
from ..vehicle.node_settings import NodeSettings


class ConsequenceWatch:
    """The load filter and the periodic analysis of one allocator; ``alarm`` is the last one's."""

    def __init__(self, allocator: Allocator):
        self.filter = LoadFilter()
        self.alarm = False
        self._analysis: Consequence | None = None
        self._due: int | None = None
        self._allocator = allocator

    def observe(self, wrench: np.ndarray, now: int, settings: NodeSettings) -> None:
        """One allocated sample's requested wrench (FRD) at ``now`` [ns] into the filter."""
        self.filter.observe(wrench, now, settings.consequence_filter_time)

    @property
    def load(self) -> np.ndarray:
        """The load filtered so far [X, Y, Z, K, M, N] (FRD)."""
        return self.filter.load

    def tick(self, now: int, settings: NodeSettings) -> None:
        """The clock at ``now`` [ns]: at the first tick at or after each multiple of the analysis
        period (as a timer on the clock fires), analyse the load filtered so far and set the
        alarm; with the analysis off (rate 0), no alarm."""
        period = consequence_period(settings.consequence_rate)
        if period is None:
            self.alarm, self._due = False, None
            return
        if self._due is None:
            self._due = -(-now // period) * period
        if now < self._due:
            return
        self._due = (now // period + 1) * period
        allocator = self._allocator
        analysis = self._analysis
        if analysis is None or analysis.vehicle is not allocator.vehicle or analysis.method != allocator.method:
            analysis = self._analysis = Consequence(allocator.vehicle, allocator.method)
        self.alarm = any(group.alarm for group in analysis.utilisation(self.filter.load, InForce.of(allocator)))
