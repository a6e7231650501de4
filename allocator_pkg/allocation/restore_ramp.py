"""The restore ramp (``power.restore_ramp``; docs/power.md, "Restore ramp"): the available
power the allocation uses falls at once and rises at most at capacity / T per second.

A power plant that has shed load (a generator tripped, a bus lost, a power management system
phasing back) takes load again in steps its governors can follow; a thruster drive that jumps
back to full power the sample the power is reported can trip the generator that has just come
back. With T = ``power.restore_ramp`` > 0, the power in use of source j, u_j, follows its
target a_j (the reported or configured available power, 0 while a group fault took it) as

    u_j(t + dt) = min(a_j, u_j(t) + C_j dt / T)      (rising; C_j its capacity)
    u_j = a_j                                         (as soon as a_j < u_j)

so that it rises from zero to the capacity in T seconds; the thrust limits follow u. T = 0:
u = a, at once.
"""

from __future__ import annotations

import numpy as np


class RestoreRamp:
    """The power in use [kW] of every source, ``level`` (None until the first target), rising at
    ``capacity`` / ``seconds`` per second (``rate``; None: no ramp, the target at once)."""

    def __init__(self, capacity: np.ndarray, seconds: float):
        self.seconds = float(seconds)
        self.rate = np.asarray(capacity, dtype=float) / self.seconds if self.seconds > 0.0 else None
        self.level: np.ndarray | None = None

    def rising(self, target: np.ndarray) -> bool:
        """Whether some source's power in use is below its ``target``."""
        return self.level is not None and bool(np.any(self.level < target))

    def in_use(self, target: np.ndarray) -> np.ndarray:
        """The power in use [kW] with the targets ``target``: each at most its level."""
        return target if self.level is None else np.minimum(target, self.level)

    def follow(self, target: np.ndarray) -> None:
        """A new ``target``: a source whose target is below its power in use falls to it at once
        (with a ramp; without, nothing is held back)."""
        if self.rate is not None:
            self.level = target.copy() if self.level is None else np.minimum(self.level, target)

    def advance(self, target: np.ndarray, seconds: float) -> bool:
        """``seconds`` later: every power in use below its target rises by rate x seconds, at
        most to the target; whether any changed."""
        if self.rate is None or not self.rising(target):
            return False
        before = self.level
        self.level = np.minimum(self.level + self.rate * seconds, np.maximum(target, self.level))
        return not np.array_equal(before, self.level)

    def carried(self, sources: tuple[str, ...], other: RestoreRamp, other_sources: tuple[str, ...]) -> None:
        """Take ``other``'s power in use for every source both know (a new configuration keeps a
        ramp under way)."""
        if self.rate is None or other.level is None:
            return
        self.level = np.array([other.level[other_sources.index(s)] if s in other_sources else np.inf
                               for s in sources])
