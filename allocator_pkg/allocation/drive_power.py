"""The power each thruster's drive draws (docs/power.md, "The power the drives draw"): its
forward and reverse power coefficients, a DEGRADED thruster's power counted on its set-point,
and the drive limits as thrust ranges.

- **Forward and reverse.** The drive draws p_i = P_i |f_i|^(3/2) (survey (1.44)) with
  P_i = ``power_coefficient`` while f_i >= 0 and P_i = ``reverse_power_coefficient`` (default:
  the forward one) while f_i < 0.
- **Degraded.** A DEGRADED thruster of efficiency eta delivers f = eta f_c, f_c the force its
  set-point gives a sound thruster (the command maps divide by eta to reach f). The drive turns
  the propeller at that set-point, so it draws what the set-point draws: p = P |f_c|^(3/2) =
  P |f / eta|^(3/2) = (P / eta^(3/2)) |f|^(3/2). On the delivered force the coefficient is
  P / eta^(3/2).
- **Drive limit.** A drive rated D_i [kW] keeps P_i |f_i|^(3/2) <= D_i: the thrust range
  f_i <= (D_i / P_fwd)^(2/3) ahead and f_i >= -(D_i / P_rev)^(2/3) astern, with the coefficients
  on the delivered force (a DEGRADED thruster's drive reaches its limit at eta times the thrust).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..vehicle.config import Vehicle
from .conditions import Conditions

KW = 1000.0
"""Watts in a kilowatt: the configuration and the topic speak kW, the model W (1.44)."""


@dataclass(frozen=True)
class DrivePower:
    """Per thruster, the coefficients [W/N^1.5] on the delivered force, ``forward`` and
    ``reverse``, and the drive limit ``limit`` [kW] (inf: none)."""

    forward: np.ndarray
    reverse: np.ndarray
    limit: np.ndarray

    @classmethod
    def of(cls, vehicle: Vehicle) -> DrivePower:
        """The configured coefficients and limits of a sound vehicle."""
        actuators = vehicle.actuators
        forward = np.array([a.power_coefficient for a in actuators], dtype=float)
        reverse = np.array([a.power_coefficient if a.reverse_power_coefficient is None
                            else a.reverse_power_coefficient for a in actuators], dtype=float)
        limit = np.array([np.inf if a.drive_limit is None else a.drive_limit for a in actuators], dtype=float)
        return cls(forward, reverse, limit)

    def degraded(self, efficiency: np.ndarray) -> DrivePower:
        """The coefficients on the delivered force at the command ``efficiency`` of every
        thruster (a fault set's ``command_efficiency``: 1 for a sound or failed one): P / eta^(3/2)."""
        factor = np.asarray(efficiency, dtype=float) ** -1.5
        return replace(self, forward=self.forward * factor, reverse=self.reverse * factor)

    def power(self, thrust: np.ndarray) -> np.ndarray:
        """What each drive draws [W] at ``thrust`` [N]: the forward coefficient ahead, the reverse
        one astern."""
        thrust = np.asarray(thrust, dtype=float)
        return np.where(thrust < 0.0, self.reverse, self.forward) * np.abs(thrust) ** 1.5

    def bound_coefficient(self, low: np.ndarray, high: np.ndarray) -> np.ndarray:
        """The larger coefficient of the directions the range [low, high] allows (the forward one
        for a range that allows neither): a magnitude bound b keeps the drive's power within
        this coefficient times b^(3/2) whichever way it pushes."""
        forward = np.where(high > 0.0, self.forward, 0.0)
        reverse = np.where(low < 0.0, self.reverse, 0.0)
        both = np.maximum(forward, reverse)
        return np.where((high > 0.0) | (low < 0.0), both, self.forward)

    def ranges(self, low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The range [low, high] inside the drive limits: f <= (D / P_fwd)^(2/3) and
        f >= -(D / P_rev)^(2/3), for each thruster with a limit and a coefficient above 0."""
        with np.errstate(divide="ignore"):
            ahead = np.where(self.forward > 0.0, (self.limit * KW / self.forward) ** (2.0 / 3.0), np.inf)
            astern = np.where(self.reverse > 0.0, (self.limit * KW / self.reverse) ** (2.0 / 3.0), np.inf)
        return np.maximum(low, -astern), np.minimum(high, ahead)

    @property
    def limited(self) -> bool:
        """Whether any thruster has a drive limit."""
        return bool(np.isfinite(self.limit).any())



def within_drive_limits(conditions: Conditions, drive: DrivePower) -> Conditions:
    """``conditions`` with every thruster's range inside its drive limit (:meth:`DrivePower.ranges`;
    ``drive`` at the faults in force)."""
    if not drive.limited:
        return conditions
    low, high = drive.ranges(conditions.low, conditions.high)
    return replace(conditions, low=low, high=high)
