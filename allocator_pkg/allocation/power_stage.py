"""The power rule in a sample (docs/power.md): the thrust ranges the available power leaves,
a short source's power shared again within the sample and carried to the next, and the
phase-back of a drop.

- **Ranges.** When faults, speed, voltage or the available power change,
  :meth:`PowerStage.refresh` narrows the static ranges to the proportional power bounds of
  :meth:`~.power_budget.PowerBudget.limit`, never per sample.
- **Carried over.** A power-limited sample starts from the bounds the last one ended with,
  relaxed toward the proportional ones (:meth:`PowerStage.carried`); a refresh that changes
  neither the available power nor the feeds keeps them.
- **Sharing again.** When that solve's thrust leaves a short source's power unused while one of
  its consumers sits at its bound, the sample is solved once more (warm-started, values only)
  inside the bounds of :meth:`~.power_budget.PowerBudget.shared`, the sample's own thrust
  pattern scaled until the source is full (:meth:`PowerStage.widened`).
- **Phase-back.** With ``power.phase_back`` (the default) a drop of available power holds from
  the next sample, faster than the rate limit allows. Without it, an actuator above its new
  bound comes down at its rate limit (:meth:`PowerStage.ramp`): this sample's ceiling is
  max(bound, |f_prev| - step), until it is inside; meanwhile its source may be over.

Every set of bounds here keeps every source within its available power on its own; the windows
of a sample inside new bounds are the rate limit's around the state it starts from, inside the
new ranges (a range that has come down wins over the rate limit, as a fault's does).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from .azimuth import thrust_window
from .conditions import Conditions
from .power_budget import PowerBudget, PowerLimit, narrowed

SHARE_PASSES = 1
"""Extra solves a power-limited sample may make to share a short source's unused power again."""

RELAX = 0.1
"""How far each sample's bounds start from the last sample's toward the proportional ones (in
power): what a consumer gave up comes back to it over some samples, so that no sharing holds
once the request has moved on."""


class PowerStage:
    """The power limit in force, the ranges without it (``base``), and the actuators coming down
    to a lower bound at their rate limit (``ramping``, None when none does)."""

    def __init__(self, model: Model):
        self.limit: PowerLimit | None = None
        self.ramping: np.ndarray | None = None
        self.sharing = False
        self._bound = np.zeros(0)
        self._last: np.ndarray | None = None
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
        same_power = (previous is not None and limit is not None and np.array_equal(previous.available, limit.available)
                      and np.array_equal(previous.weights, limit.weights))
        self.ramping, self._last = None, self._last if same_power else None
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

    def carried(self, limits: SampleLimits) -> SampleLimits:
        """This sample's ``limits`` (built inside the proportional bounds) inside the bounds the
        last sample ended with, relaxed toward the proportional ones: per actuator
        p = RELAX P b_prop^(3/2) + (1 - RELAX) P b_last^(3/2), a mean of two sets of bounds that
        each keep every source within its available power, so this one does too."""
        proportional = self.limit.bound
        last = self._last if self._last is not None else proportional
        with np.errstate(invalid="ignore"):
            bound = np.where(np.isfinite(proportional), (RELAX * proportional ** 1.5 + (1.0 - RELAX) * last ** 1.5)
                             ** (2.0 / 3.0), proportional)
        self._bound = bound
        return self._within(limits, proportional, bound)

    def widened(self, limits: SampleLimits, thrust: np.ndarray) -> SampleLimits | None:
        """The limits of one more solve that shares a short source's unused power again, from
        this sample's ``limits`` and the ``thrust`` the last solve gave; None when no source has
        power to share."""
        bound = self.budget.shared(self.limit, self._bound, thrust, self._movable(limits))
        if bound is None:
            return None
        old, self._bound = self._bound, bound
        return self._within(limits, old, bound)

    @property
    def bound(self) -> np.ndarray | None:
        """The thrust bounds the last sample ended with [N] (the proportional ones before any
        sample has shared; None without sources)."""
        if self.limit is None:
            return None
        return self._last if self._last is not None else self.limit.bound

    def commit(self) -> None:
        """The bounds this sample ended with are the next one's start."""
        self._last = self._bound

    @staticmethod
    def _movable(limits: SampleLimits) -> np.ndarray:
        """The actuators whose thrust window may move with their bound: every one but a
        rotatable thruster turning through a forbidden sector or ramping to zero to turn."""
        movable = np.ones(limits.low.size, dtype=bool)
        for k, i in enumerate(limits.rot):
            lim = limits.azimuth[k]
            movable[i] = lim.line or lim.high > lim.low
        return movable

    def _within(self, limits: SampleLimits, old: np.ndarray, bound: np.ndarray) -> SampleLimits:
        """``limits``, built inside the bounds ``old``, inside ``bound``: the window of each
        actuator whose bound changed is the rate limit's around the state the sample starts
        from, inside its new range (a range that has come down wins over the rate limit); a
        thruster turning through keeps its window, inside the bound."""
        changed = np.flatnonzero(bound != old).tolist()
        if not changed:
            return limits
        movable = self._movable(limits)
        range_low, range_high = np.maximum(self.base.low, -bound), np.minimum(self.base.high, bound)
        low, high, azimuth = limits.low.copy(), limits.high.copy(), list(limits.azimuth)
        for i in changed:
            if movable[i]:
                window = thrust_window(float(limits.thrust[i]), float(self._step[i]), range_low[i], range_high[i])
            else:
                window = (min(max(low[i], -bound[i]), bound[i]), min(max(high[i], -bound[i]), bound[i]))
            k = self._rotatable.get(i)
            if k is None:
                low[i], high[i] = window
                continue
            lim = azimuth[k]
            if movable[i] and not lim.line:
                window = (max(window[0], 0.0), max(window[1], 0.0)) if lim.sigma > 0 else \
                    (min(window[0], 0.0), min(window[1], 0.0))
            physical = lim.physical_max if lim.line else (range_high[i] if lim.sigma > 0 else -range_low[i])
            azimuth[k] = replace(lim, thrust_low=window[0], thrust_high=window[1], physical_max=physical)
            low[i], high[i] = window
        return SampleLimits(low, high, limits.rot, azimuth, limits.angle, limits.thrust, range_low=range_low,
                            range_high=range_high)
