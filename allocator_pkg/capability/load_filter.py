"""The consequence analysis' load (docs/power.md, "Consequence analysis"): a first-order low-pass
filter of the requested wrench, one allocated sample at a time,

    y_k = y_(k-1) + (1 - exp(-dt_k / T)) (tau_k - y_(k-1)),    T = consequence.filter_time

where the first sample, one after the clock went back, or any without a filter (T <= 0) sets y
to its request. ``allocator_node`` (:mod:`allocator_pkg.ros.consequence_topic`) and the
in-process link (:mod:`allocator_pkg.simulation.consequence_watch`) both filter with it."""

from __future__ import annotations

import math

import numpy as np

from ..allocation.sample_rules import NS


class LoadFilter:
    """The filtered load ``load`` [X, Y, Z, K, M, N] (FRD) and the time of the last sample."""

    def __init__(self) -> None:
        self.load = np.zeros(6)
        self._observed: int | None = None

    def restart(self) -> None:
        """The next sample sets the load to its request (as the first one does)."""
        self._observed = None

    def observe(self, wrench: np.ndarray, now: int, time_constant: float) -> None:
        """One allocated sample's requested ``wrench`` (FRD) at ``now`` [ns] into the filter, with
        the weight 1 - exp(-dt / ``time_constant``) [s]."""
        last, self._observed = self._observed, now
        if last is None or now < last or time_constant <= 0.0:
            self.load[:] = wrench
            return
        load = self.load
        load += (1.0 - math.exp((last - now) / (NS * time_constant))) * (wrench - load)
