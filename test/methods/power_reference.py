"""An exact power-limited reference for the allocator's tests, independent of its solvers: the
largest scale lambda of a direction d that the actuators reach with every source within its
power, max lambda s.t. T f = lambda d, |f_i| within its range, sum_i w_ij P_i |f_i|^(3/2) <= A_j,
by scipy's SLSQP from several starts (the power exact, no chords, no polygon)."""

from __future__ import annotations

import numpy as np
from scipy.optimize import minimize

SMOOTH = 1e-4
"""|f|^(3/2) is taken as (f^2 + (SMOOTH F)^2)^(3/4) in the constraints: smooth at zero and never
below |f|^(3/2) (the reference stays within the power; it overstates an actuator's draw by at
most P (SMOOTH F)^(3/2) = 1e-6 of its rated power)."""


class Reference:
    """The reference problem of one vehicle at one set of available powers ``available`` [W]
    with feed weights ``weights`` (actuators x sources). ``columns`` (6 x r) and ``across``
    (6 x r): each actuator's wrench per newton along its direction at azimuth 0 and, for a
    rotatable thruster, at azimuth pi/2; ``low``/``high`` its thrust range; ``dofs`` the rows
    of the controlled DOFs; ``scale`` each DOF's unit (d is a unit vector in these units)."""

    def __init__(self, columns, across, rotatable, low, high, coefficient, weights, available, dofs, scale):
        self.t0, self.t1 = columns[dofs], across[dofs]
        self.rot = np.asarray(rotatable, dtype=bool)
        self.low, self.high = np.asarray(low, float), np.asarray(high, float)
        self.range = np.maximum(np.abs(self.low), np.abs(self.high))
        self.coefficient, self.weights, self.available = coefficient, weights, np.asarray(available, float)
        self.scale = np.asarray(scale, float)

    def _split(self, x):
        r = self.range.size
        return x[:r] * self.range, np.where(self.rot, x[r:2 * r], 0.0) * self.range, x[-1]

    def power(self, along, across):
        """The exact draw [W] of each source at forces (along, across) per actuator."""
        return (self.coefficient * np.hypot(along, across) ** 1.5) @ self.weights

    def _smooth_power(self, along, across):
        delta = SMOOTH * self.range
        return (self.coefficient * (along ** 2 + across ** 2 + delta ** 2) ** 0.75) @ self.weights

    def largest(self, direction, starts: int = 6, seed: int = 0) -> float:
        """lambda*: the largest scale of the unit ``direction`` (in DOF units) with the power
        exact; the best of SLSQP from ``starts`` starts, each answer checked feasible."""
        direction = np.asarray(direction, float) * self.scale
        r = self.range.size
        rng = np.random.default_rng(seed)
        wrench_scale = np.abs(self.t0 * self.range).sum(axis=1) + np.abs(self.t1 * self.range).sum(axis=1) + 1.0
        lam_scale = float(np.max(np.abs(direction) / wrench_scale)) or 1.0

        def equality(x):
            along, across, lam = self._split(x)
            return (self.t0 @ along + self.t1 @ across - lam / lam_scale * direction) / wrench_scale

        def inequality(x):
            along, across, _ = self._split(x)
            circle = 1.0 - (along ** 2 + across ** 2) / np.maximum(self.range, 1e-9) ** 2
            box = np.concatenate(((along - self.low) / self.range, (self.high - along) / self.range))
            room = np.where(np.isfinite(self.available), self.available, 1e30)
            norm = np.maximum(self.coefficient * self.range ** 1.5 @ self.weights, 1.0)
            power = (np.minimum(room, 1e30) - self._smooth_power(along, across)) / norm
            return np.concatenate((np.where(self.rot, circle, 1.0), np.where(self.rot, 1.0, box[:r]),
                                   np.where(self.rot, 1.0, box[r:]), power))

        best = 0.0
        for k in range(starts):
            x0 = np.zeros(2 * r + 1) if k == 0 else np.append(rng.uniform(-0.5, 0.5, 2 * r), 0.0)
            answer = minimize(lambda x: -x[-1], x0, method="SLSQP",
                              constraints=[{"type": "eq", "fun": equality}, {"type": "ineq", "fun": inequality}],
                              options={"maxiter": 500, "ftol": 1e-12})
            along, across, lam = self._split(answer.x)
            lam = lam / lam_scale
            feasible = (np.all(inequality(answer.x) >= -1e-7) and np.all(np.abs(equality(answer.x)) <= 1e-7)
                        and np.all(self.power(along, across) <= self.available * (1 + 1e-6) + 1e-6))
            if feasible:
                best = max(best, lam)
        return best
