"""The power rule in a sample (docs/power.md): the power rows a method solves with, or the
proportional bounds of a method without rows, and the phase-back of a drop.

- **Rows.** When faults, speed, voltage or the available power change,
  :meth:`PowerStage.refresh` hands the method the power rows' values
  (:meth:`~.power_budget.PowerBudget.rows`; values only on the solver's pattern) and narrows the
  static ranges by the derating of a lost feed only; a method without rows (the pseudo-inverse
  family) gets the proportional bounds of :meth:`~.power_budget.PowerBudget.limit` in its ranges
  instead. Not per sample, with two exceptions: each sample while the restore ramp raises the
  power in use, and each sample of a ramp-down without phase-back (below); one solve per sample.
- **Phase-back.** With ``power.phase_back`` (the default) a drop of available power holds from
  the next sample, faster than the rate limit allows: that sample the thrust windows of the
  consumers of a source now over its power open down to zero (:meth:`PowerStage.opened`), a
  drop of power winning over the rate limit as a fault's does. Without it the consumers come
  down at their rate limit: with rows, each sample's available power of a source over its new
  power is max(A_j, the draw, as the chord rows see it, of the last thrust each consumer less
  RAMP_ROOM of its rate step) (:meth:`PowerStage.ramp_rows`), so the rate window around the last
  thrust stays feasible, until the source is within A_j; without rows, an actuator above its new bound has
  the ceiling max(bound, |f_prev| - step) (:meth:`PowerStage.ramp`). Meanwhile the source may be
  over.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from ..effectiveness.power_rows import PowerRows
from .conditions import Conditions
from .power_budget import PowerBudget, PowerLimit, narrowed

RAMP_ROOM = 0.99
"""While a source ramps down, its power this sample is that of each consumer's last thrust less
this share of its rate step: the rate window keeps room below its bound for the solver."""


class PowerStage:
    """The power limit in force, the ranges without it (``base``), the consumers whose windows
    the next sample opens to zero (``opening``), the sources coming down to a lower power at
    their consumers' rate limit with rows (``ramping_sources``) and the actuators coming down to
    a lower bound at their rate limit without rows (``ramping_actuators``); None when none does."""

    def __init__(self, model: Model):
        self.limit: PowerLimit | None = None
        self.ramping_sources: np.ndarray | None = None
        self.ramping_actuators: np.ndarray | None = None
        self.opening: np.ndarray | None = None
        self.configure(model)

    def configure(self, model: Model) -> None:
        """Per-configuration constants: the rate steps and the rotatable thrusters."""
        self.model = model
        self._step = model.thrust_step
        self._rotatable = {int(i): k for k, i in enumerate(model.rot)}

    @property
    def rows(self) -> PowerRows | None:
        """The power rows in force (None: no sources, or a method without rows)."""
        return None if self.limit is None else self.limit.rows

    def refresh(self, budget: PowerBudget, base: Conditions, thrust: np.ndarray | None,
                phase_back: bool, rows: bool) -> Conditions:
        """The conditions of every stage: ``base`` (what faults, speed and voltage leave), with
        ``rows`` (the method solves with the power rows) the rows in force and the derating of a
        lost feed, else inside the proportional power bounds of ``budget``'s available power.
        A drop of power that leaves ``thrust`` over it opens the next sample's windows
        (``phase_back``) or ramps (module docstring)."""
        previous, ramping, self.base = self.limit, self.ramping_actuators, base
        limit = self.limit = budget.limit(base.low, base.high, rows) if budget.active else None
        self.ramping_sources = self.ramping_actuators = self.opening = None
        if limit is None:
            return base
        if thrust is not None:
            self._dropped(previous, limit, ramping, thrust, phase_back)
        low, high = narrowed(base.low, base.high, limit)
        return replace(base, low=low, high=high, power=limit.rows,
                       power_bound=None if limit.rows is None else limit.proportional)

    def _dropped(self, previous: PowerLimit | None, limit: PowerLimit, ramping: np.ndarray | None,
                 thrust: np.ndarray, phase_back: bool) -> None:
        """``opening``, ``ramping_sources`` or ``ramping_actuators`` after a change of power that
        ``thrust`` is over; ``ramping`` the actuators still ramping without rows."""
        if limit.rows is not None:
            over = limit.rows.seen(thrust) > limit.rows.available
            if not over.any():
                return
            consumers = (limit.rows.weights[:, over] > 0.0).any(axis=1)
            if phase_back:
                self.opening = consumers
            else:
                self.ramping_sources = over
            return
        if phase_back:
            return
        lowered = np.ones(limit.bound.size, dtype=bool) if previous is None else limit.bound < previous.bound
        if ramping is not None:
            lowered |= ramping
        over = limit.limited & lowered & (np.abs(thrust) > limit.bound) & np.isfinite(self._step)
        self.ramping_actuators = over if over.any() else None

    def ramp_rows(self, thrust: np.ndarray) -> PowerRows:
        """This sample's power rows while a source comes down to a lower power at the rate
        limit (module docstring); ``ramping_sources`` ends once every source is within its power."""
        rows = self.limit.rows
        step = RAMP_ROOM * np.where(np.isfinite(self._step), self._step, 0.0)
        lowest = np.sign(thrust) * np.maximum(np.abs(thrust) - step, 0.0)
        reachable = rows.seen(lowest)
        over = self.ramping_sources & (reachable > rows.available)
        self.ramping_sources = over if over.any() else None
        return replace(rows, available=np.where(over, reachable, rows.available))

    def ramp(self, thrust: np.ndarray) -> Conditions:
        """This sample's conditions (a method without rows) while some actuator comes down to
        its bound: its ceiling max(bound, |f_prev| - step), the rate limit's; ``ramping_actuators`` ends
        once every one is inside its bound."""
        bound = self.limit.bound
        lowest = np.abs(thrust) - self._step
        ceiling = np.where(self.ramping_actuators, np.maximum(bound, lowest),
                           np.where(self.limit.limited, bound, np.inf))
        over = self.ramping_actuators & (lowest > bound)
        self.ramping_actuators = over if over.any() else None
        return replace(self.base, low=np.clip(self.base.low, -ceiling, ceiling),
                       high=np.clip(self.base.high, -ceiling, ceiling))

    @property
    def bound(self) -> np.ndarray | None:
        """The thrust bounds [N] the power sets in the ranges (None without sources): the
        proportional ones for a method without rows, the derating of a lost feed with rows."""
        return None if self.limit is None else self.limit.bound

    def opened(self, limits: SampleLimits) -> SampleLimits:
        """``limits`` with the windows of the ``opening`` consumers reaching zero thrust (a
        drop of power wins over the rate limit); once, the sample after the drop."""
        opening, self.opening = self.opening, None
        low, high, azimuth = limits.low.copy(), limits.high.copy(), list(limits.azimuth)
        for i in np.flatnonzero(opening).tolist():
            low[i], high[i] = min(low[i], 0.0), max(high[i], 0.0)
            k = self._rotatable.get(i)
            if k is not None and not azimuth[k].line:
                lim = azimuth[k]
                azimuth[k] = replace(lim, thrust_low=min(lim.thrust_low, 0.0), thrust_high=max(lim.thrust_high, 0.0))
        return replace(limits, low=low, high=high, azimuth=azimuth, version=-1)
