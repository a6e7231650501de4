"""Allocation method ``pseudoinverse``: the weighted generalised inverse (1.29) of the extended
configuration (1.32)-(1.34), with no solver.

:class:`PseudoInverseGains` caches the gains, computed as W^-1/2 pinv(T_e W^-1/2) once per set
of usable actuators; :class:`PseudoInverseAllocation` applies them, holds the actuators the
sample's limits pin down, and saturates by clipping, by one common scale
(``preserve_direction``) or by Durham's direct method (``direct``). DOF priorities are met by
sequential desaturation in the null space of the levels above. docs/theory.md (sections
`pseudoinverse` and DOF priorities) has the theory.
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
from .direct import DirectSolution, direct_sides

STEP_MARGIN = 1e-9
"""A level's step may pass a limit by this fraction of the actuator's range without being
scaled (rounding in the null space of the levels above; the final clip takes it)."""


class PseudoInverseAllocation(AllocationMethod):
    """Allocation method ``pseudoinverse``: no solver; ``gains`` may be a cache shared with
    the allocator (which also uses it for the fallback and azimuth planning)."""

    name = "pseudoinverse"
    saturation_modes = ("weighted", "preserve_direction", "direct")
    implements_priorities = True

    def __init__(self, model: Model, backend: BackendFactory, gains: PseudoInverseGains | None = None):
        super().__init__(model, backend)
        self.inverse = gains or PseudoInverseGains(model)
        self._version = -1
        self._preserve_direction = model.vehicle.saturation == "preserve_direction"
        self._direct = DirectSolution(model) if model.vehicle.saturation == "direct" else None
        self.setups += self._direct is not None
        self._levels = model.vehicle.priority_levels

    def update_model(self, model: Model) -> None:
        """A new configuration: new gains on the next sample (no solver to set up)."""
        self.model = model
        self.inverse = PseudoInverseGains(model)
        self._version = -1
        self._preserve_direction = model.vehicle.saturation == "preserve_direction"
        if self._direct is not None:
            self._direct.update_model(model)
        self._levels = model.vehicle.priority_levels

    @classmethod
    def thrust_region_sides(cls, vehicle: Vehicle) -> int | None:
        """None: the pseudo-inverse's own reach; with ``saturation: direct``, the polygon of the
        direct method's LP, which reaches the whole attainable set."""
        return direct_sides(vehicle.azimuth_polygon_sides) if vehicle.saturation == "direct" else None

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        model = self.model
        if limits.version < 0 or limits.version != self._version:
            self._fixed = fixed = limits.fixed()
            lines = {int(i): lim.low for i, lim in zip(model.rot, limits.azimuth) if lim.line and not fixed[i]}
            pinned = fixed_forces(model, limits, fixed)
            self._pinned = pinned if pinned.any() else None
            self._pinned_wrench = None if self._pinned is None else model.t_ec @ pinned
            if self._levels:
                self._cascade = self.inverse.cascade(fixed, lines, self._levels)
            else:
                self._gain = self.inverse.gain(fixed, lines)
            self._version = limits.version
        wanted = tau if self._pinned is None else tau - self._pinned_wrench
        if self._levels:
            force = np.zeros(model.m)
            for rows, gain in self._cascade:
                step = gain @ (wanted[rows] - model.t_ec[rows] @ force)
                force += step_to_limits(model, limits, force, step, self._fixed) * step
            if self._pinned is not None:
                force += self._pinned
            return MethodOutput(force=force, status="solved")
        force = self._gain @ wanted
        if self._preserve_direction:
            force *= scale_to_limits(model, limits, force, self._fixed)
        if self._pinned is not None:
            force += self._pinned
        if self._direct is not None and not within_limits(model, limits, force, self._fixed):
            boundary = self._direct.solve(tau, limits)
            if boundary.usable:
                return boundary
        return MethodOutput(force=force, status="solved")


def fixed_forces(model: Model, limits: SampleLimits, fixed: np.ndarray) -> np.ndarray:
    """Extended forces of the actuators the limits pin down (zero elsewhere). A rotatable
    thruster pinned at zero thrust gives zero whatever its angle, which may still be free (an
    unbounded window)."""
    force = np.zeros(model.m)
    for i in np.flatnonzero(fixed):
        start = model.starts[i]
        if model.rotatable[i]:
            if limits.low[i] == 0.0:
                continue
            angle = limits.azimuth[int(np.searchsorted(model.rot, i))].low
            force[start] = limits.low[i] * math.cos(angle)
            force[start + 1] = limits.low[i] * math.sin(angle)
        else:
            force[start] = limits.low[i]
    return force


def scale_to_limits(model: Model, limits: SampleLimits, force: np.ndarray, fixed: np.ndarray) -> float:
    """The largest factor in [0, 1] that brings every free force within its limits. A bound
    on the far side of zero (a thrust that a rate limit keeps from falling to zero) cannot be
    met by scaling down: the final clip keeps it."""
    scale = 1.0
    for i, start in enumerate(model.starts):
        if fixed[i]:
            continue
        if model.rotatable[i]:
            lim = limits.azimuth[int(np.searchsorted(model.rot, i))]
            magnitude = math.hypot(force[start], force[start + 1])
            if magnitude > lim.magnitude_max:
                scale = min(scale, lim.magnitude_max / magnitude)
        else:
            f, low, high = float(force[start]), float(limits.low[i]), float(limits.high[i])
            if f > high >= 0.0:
                scale = min(scale, high / f)
            elif f < low <= 0.0:
                scale = min(scale, low / f)
    return scale


WITHIN = 1e-9
"""Relative tolerance of :func:`within_limits` (forces) and its angle tolerance [rad]."""


def within_limits(model: Model, limits: SampleLimits, force: np.ndarray, fixed: np.ndarray) -> bool:
    """Whether every free actuator's force is inside this sample's limits: its thrust box, and
    for a rotatable thruster its thrust window and allowed angles (a force below the hold
    threshold has no direction to check)."""
    for i, start in enumerate(model.starts):
        if fixed[i]:
            continue
        slack = WITHIN * max(model.force_scale[i], 1.0)
        if not model.rotatable[i]:
            if not limits.low[i] - slack <= force[start] <= limits.high[i] + slack:
                return False
            continue
        lim = limits.azimuth[int(np.searchsorted(model.rot, i))]
        f1, f2 = float(force[start]), float(force[start + 1])
        magnitude = math.hypot(f1, f2)
        if magnitude <= model.hold[i]:
            if lim.thrust_low > magnitude + slack or lim.thrust_high < -magnitude - slack:
                return False
            continue
        alpha0 = float(limits.angle[i])
        if lim.line:
            along = f1 * math.cos(alpha0) + f2 * math.sin(alpha0)
            if abs(f1 * math.sin(alpha0) - f2 * math.cos(alpha0)) > slack or not \
                    lim.thrust_low - slack <= along <= lim.thrust_high + slack:
                return False
            continue
        direction = math.atan2(f2, f1) if lim.sigma > 0 else math.atan2(-f2, -f1)
        angle = alpha0 + wrap(direction - alpha0)
        thrust = lim.sigma * magnitude
        if not (lim.low - WITHIN <= angle <= lim.high + WITHIN
                and lim.thrust_low - slack <= thrust <= lim.thrust_high + slack):
            return False
    return True


def step_to_limits(model: Model, limits: SampleLimits, force: np.ndarray, step: np.ndarray,
                   fixed: np.ndarray) -> float:
    """The largest factor lambda in [0, 1] that keeps every free force within its limits (to
    ``STEP_MARGIN``) on force + lambda step, for a force already within them. A bound that ``force`` already
    breaks (a thrust that a rate limit keeps from falling to zero) cannot be met by this
    step: the final clip keeps it."""
    scale = 1.0
    for i, start in enumerate(model.starts):
        if fixed[i]:
            continue
        if model.rotatable[i]:
            lim = limits.azimuth[int(np.searchsorted(model.rot, i))]
            f, d = force[start:start + 2], step[start:start + 2]
            bound = lim.magnitude_max
            outside = min(float(f @ f) - bound * bound, 0.0)
            if math.sqrt(float(f @ f)) <= bound * (1.0 + STEP_MARGIN) \
                    and math.sqrt(float((f + d) @ (f + d))) > bound * (1.0 + STEP_MARGIN):
                a, b = float(d @ d), 2.0 * float(f @ d)
                scale = min(scale, max(-b + math.sqrt(max(b * b - 4.0 * a * outside, 0.0)), 0.0) / (2.0 * a))
        else:
            f, d = float(force[start]), float(step[start])
            low, high = float(limits.low[i]), float(limits.high[i])
            margin = STEP_MARGIN * max(high, -low)
            if d > 0.0 and f <= high + margin and high < f + d - margin:
                scale = min(scale, max(high - f, 0.0) / d)
            elif d < 0.0 and f >= low - margin and low > f + d + margin:
                scale = min(scale, min(low - f, 0.0) / d)
    return max(scale, 0.0)
