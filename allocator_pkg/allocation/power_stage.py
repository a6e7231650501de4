"""The power rule in a sample (docs/power.md): the thrust ranges the available power leaves,
a short source's unused power shared again within the sample, and the phase-back of a drop.

- **Ranges.** When faults, speed, voltage or the available power change,
  :meth:`PowerStage.refresh` narrows the static ranges to the power bounds of
  :meth:`~.power_budget.PowerBudget.limit`, never per sample.
- **Sharing again.** A sample whose thrust leaves a short source's power unused while some of
  its consumers sit at their bound is solved once more (warm-started, values only) inside the
  bounds of :meth:`~.power_budget.PowerBudget.shared`: :meth:`PowerStage.widened` gives the
  second solve this sample's limits with the windows of those consumers opened toward their
  new bound (from the state the sample starts from, at their rate limit) and the others'
  narrowed to the thrust they use.
- **Phase-back.** With ``power.phase_back`` (the default) a drop of available power holds from
  the next sample, faster than the rate limit allows. Without it, an actuator above its new
  bound comes down at its rate limit (:meth:`PowerStage.ramp`): this sample's ceiling is
  max(bound, |f_prev| - step), until it is inside; meanwhile its source may be over.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from .azimuth import thrust_window
from .conditions import Conditions
from .power_budget import PowerBudget, PowerLimit, narrowed

SHARE_PASSES = 2
"""Extra solves a power-limited sample may make to share a short source's unused power again."""


class PowerStage:
    """The power limit in force, the ranges without it (``base``), and the actuators coming down
    to a lower bound at their rate limit (``ramping``, None when none does)."""

    def __init__(self, model: Model):
        self.limit: PowerLimit | None = None
        self.ramping: np.ndarray | None = None
        self.sharing = False
        self._widened: SampleLimits | None = None
        self._bound = np.zeros(0)
        self.configure(model)

    def configure(self, model: Model) -> None:
        """Per-configuration constants: the rate steps and the rotatable thrusters."""
        self.model = model
        self._step = model.thrust_step
        self._rotatable = {int(i): k for k, i in enumerate(model.rot)}

    def refresh(self, budget: PowerBudget, base: Conditions, thrust: np.ndarray | None,
                phase_back: bool) -> Conditions:
        """The conditions of every stage: ``base`` (what faults, speed and voltage leave) inside
        the power bounds of ``budget``'s available power. Without ``phase_back``, the actuators
        whose ``thrust`` lies above a bound that has just come down (or that were coming down)
        ramp to it."""
        previous, ramping, self.budget, self.base = self.limit, self.ramping, budget, base
        limit = self.limit = budget.limit(base.low, base.high) if budget.active else None
        self.sharing = limit is not None and bool(limit.limited.any())
        self.ramping = None
        if not self.sharing:
            return base
        if not phase_back and thrust is not None:
            lowered = np.ones(limit.bound.size, dtype=bool) if previous is None else limit.bound < previous.bound
            if ramping is not None and ramping.size == lowered.size:
                lowered |= ramping
            over = limit.limited & lowered & (np.abs(thrust) > limit.bound) & np.isfinite(self._step)
            self.ramping = over if over.any() else None
        low, high = narrowed(base.low, base.high, limit)
        return replace(base, low=low, high=high)

    def ramp(self, thrust: np.ndarray) -> Conditions:
        """This sample's conditions while some actuator comes down to its bound: its ceiling
        max(bound, |f_prev| - step), the rate limit's; ``ramping`` ends once every one is
        inside its bound."""
        bound = self.limit.bound
        lowest = np.abs(thrust) - self._step
        ceiling = np.where(self.ramping, np.maximum(bound, lowest), np.where(self.limit.limited, bound, np.inf))
        over = self.ramping & (lowest > bound)
        self.ramping = over if over.any() else None
        return replace(self.base, low=np.clip(self.base.low, -ceiling, ceiling),
                       high=np.clip(self.base.high, -ceiling, ceiling))

    def widened(self, limits: SampleLimits, thrust: np.ndarray) -> SampleLimits | None:
        """The limits of a second solve that shares a short source's unused power again, from
        this sample's ``limits`` and the ``thrust`` its first solve gave; None when no source
        has power to share."""
        movable = np.ones(thrust.size, dtype=bool)
        for k, i in enumerate(limits.rot):
            lim = limits.azimuth[k]
            movable[i] = lim.line or lim.high > lim.low      # not turning through, nor ramping to turn
        old = self._bound if limits is self._widened else self.limit.bound
        bound = self.budget.shared(self.limit, old, thrust, movable)
        if bound is None:
            return None
        self._bound = bound
        range_low, range_high = np.maximum(self.base.low, -bound), np.minimum(self.base.high, bound)
        low, high, azimuth = limits.low.copy(), limits.high.copy(), list(limits.azimuth)
        for i in np.flatnonzero(bound != old).tolist():
            if bound[i] > old[i]:
                window = thrust_window(float(limits.thrust[i]), float(self._step[i]), range_low[i], range_high[i])
            else:
                window = (max(low[i], -bound[i]), min(high[i], bound[i]))
            k = self._rotatable.get(i)
            if k is None:
                low[i], high[i] = window
                continue
            lim = azimuth[k]
            if not lim.line:
                window = (max(window[0], 0.0), max(window[1], 0.0)) if lim.sigma > 0 else \
                    (min(window[0], 0.0), min(window[1], 0.0))
            physical = lim.physical_max if lim.line else (range_high[i] if lim.sigma > 0 else -range_low[i])
            azimuth[k] = replace(lim, thrust_low=window[0], thrust_high=window[1], physical_max=physical)
            low[i], high[i] = window
        self._widened = SampleLimits(low, high, limits.rot, azimuth, limits.angle, limits.thrust,
                                     range_low=range_low, range_high=range_high)
        return self._widened
