"""Allocation method ``svd_filter``: SVD and filtering (survey section 5.4), after Sordalen
(1997), with damped least squares after Berge and Fossen (1997).

Each sample steers every rotatable thruster toward a low-pass filtered copy of the force the
extended solution (1.33) wants of it, then gives the thrusts at those angles by the damped
least-squares inverse of T(alpha): the weighted pseudo-inverse (1.43) for singular values
above the damping threshold eps, no gain above 1/eps below it, so that a singular configuration
asks for no unbounded force. Vehicles without rotatable thrusters are refused. docs/theory.md (section
`svd_filter`) has the filter, the damping and its behaviour through a singularity.
"""

from __future__ import annotations

import math

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from ..effectiveness.weighted_inverse import PseudoInverseGains
from ..solvers import BackendFactory
from ..vehicle.angles import wrap
from ..vehicle.config import Vehicle
from .base import AllocationMethod, MethodOutput
from .pseudoinverse import fixed_forces, scale_to_limits


class SVDFilterAllocation(AllocationMethod):
    """Allocation method ``svd_filter``. For the record, of the last sample: ``singular_values``
    of the normalised T(alpha) of the free actuators (largest first), ``gains`` g(s_i) of the
    damped inverse, and ``thrust``, each actuator's thrust before any limit clips it."""

    name = "svd_filter"

    def __init__(self, model: Model, backend: BackendFactory):
        super().__init__(model, backend)
        self._use(model)
        self._filtered = np.zeros((model.rot.size, 2))
        self._sample: np.ndarray | None = None
        self._start = self._filtered
        self.singular_values = np.zeros(0)
        self.gains = np.zeros(0)
        self.thrust = np.zeros(model.r)

    @classmethod
    def problems(cls, vehicle: Vehicle) -> list[str]:
        reasons = super().problems(vehicle)
        if not vehicle.has_rotatable:
            reasons.append("it steers rotatable thrusters and this vehicle has none (use pseudoinverse)")
        return reasons

    @classmethod
    def thrust_region_sides(cls, vehicle: Vehicle) -> int | None:
        """None: at rest the thrusters point where the extended solution wants them, and the
        thrusts are the weighted pseudo-inverse's (it does not redistribute force)."""
        return None

    def update_model(self, model: Model) -> None:
        """A new configuration: new gains and arrays; the filter's state carries over."""
        self._use(model)

    def _use(self, model: Model) -> None:
        self.model = model
        self.inverse = PseudoInverseGains(model)
        vehicle = model.vehicle
        constant = vehicle.svd_filter_time_constant
        self._kappa = 1.0 - math.exp(-model.dt / constant) if constant > 0.0 else 1.0
        self._epsilon = vehicle.svd_filter_damping_threshold
        self._force_unit = float(np.max(model.force_scale, initial=1e-9))
        self._root_weight = np.sqrt(model.weight / float(np.max(model.weight)))
        self._dof = model.dof_scale
        self._preserve_direction = vehicle.saturation == "preserve_direction"
        self._version = -1

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        model = self.model
        if limits.thrust is self._sample:
            self._filtered = self._start                        # another pass of the same sample
        else:
            self._sample, self._start = limits.thrust, self._filtered
        if limits.version < 0 or limits.version != self._version:
            self._fixed = limits.fixed()
            pinned = fixed_forces(model, limits, self._fixed)
            self._pinned = pinned
            self._pinned_wrench = model.t_ec @ pinned
            lines = {int(i): lim.low for i, lim in zip(model.rot, limits.azimuth) if lim.line and not self._fixed[i]}
            self._gain = self.inverse.gain(self._fixed, lines)
            self._version = limits.version
        request = tau - self._pinned_wrench
        desired = self._gain @ request
        self._filtered = self._filtered + self._kappa * (desired[model.rot_columns] - self._filtered)
        angle = limits.angle.copy()
        for k, (i, lim) in enumerate(zip(model.rot.tolist(), limits.azimuth)):
            angle[i] = self._steer(lim, float(limits.angle[i]), self._filtered[k], float(model.hold[i]))
        free = np.flatnonzero(~self._fixed)
        thrust = np.zeros(model.r)
        if free.size:
            columns = self._columns(angle)[:, free]
            scale = self._force_unit / self._root_weight[free]
            thrust[free] = scale * self._damped(columns * scale / self._dof[:, None], request / self._dof)
        self.thrust = thrust
        force = np.zeros(model.m)
        force[model.scalar_columns] = thrust[model.scalar]
        force[model.rot_columns[:, 0]] = thrust[model.rot] * np.cos(angle[model.rot])
        force[model.rot_columns[:, 1]] = thrust[model.rot] * np.sin(angle[model.rot])
        if self._preserve_direction:
            force *= scale_to_limits(model, limits, force, self._fixed)
        return MethodOutput(force=force + self._pinned, status="solved", angle=angle)

    @staticmethod
    def _steer(lim, alpha0: float, filtered: np.ndarray, hold: float) -> float:
        """The angle toward the filtered direction, within this sample's window; a direction
        too small to define holds the angle (or turns toward the window's goal)."""
        if lim.line or lim.magnitude_max == 0.0:
            return lim.low if math.isfinite(lim.low) else alpha0
        x, y = float(filtered[0]), float(filtered[1])
        if math.hypot(x, y) <= hold:
            target = alpha0 if lim.goal is None else lim.goal
        else:
            direction = math.atan2(y, x) if lim.sigma > 0 else math.atan2(-y, -x)
            target = alpha0 + wrap(direction - alpha0)
        return min(max(target, lim.low), lim.high)

    def _columns(self, angle: np.ndarray) -> np.ndarray:
        """T(alpha) on the controlled DOFs (n x r), from the constant T_e."""
        model = self.model
        t = np.empty((model.n, model.r))
        t[:, model.scalar] = model.t_ec[:, model.scalar_columns]
        rot = model.rot
        cos, sin = np.cos(angle[rot]), np.sin(angle[rot])
        t[:, rot] = cos * model.t_ec[:, model.rot_columns[:, 0]] + sin * model.t_ec[:, model.rot_columns[:, 1]]
        return t

    def _damped(self, a: np.ndarray, request: np.ndarray) -> np.ndarray:
        """x = V diag(g(s)) U' request, the damped least-squares inverse (see the module)."""
        u, s, vt = np.linalg.svd(a, full_matrices=False)
        epsilon = self._epsilon
        gains = np.where(s >= epsilon, 1.0 / np.maximum(s, epsilon), s / (epsilon * epsilon))
        self.singular_values, self.gains = s, gains
        return vt.T @ (gains * (u.T @ request))
