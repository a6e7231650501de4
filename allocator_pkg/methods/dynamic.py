"""Allocation method ``dynamic``: a control-Lyapunov update law (survey section 5.1, after
Johansen 2004), with no optimiser in the sample.

The allocation is a state, the extended forces (1.16), moved once per sample by a Newton step
of length h (``dynamic.gain``) plus the feed-forward of the request's change, along the
directions no limit holds, and projected on the static limits. Its equilibrium is the optimum
of (1.35) with beta = 0, the slack eliminated and each rotatable thruster's exact circle; which
bounds hold is decided by their KKT multipliers. The commanded forces are the state brought
into this sample's rate windows, with one more Newton step for the actuators left free.
docs/theory.md (section `dynamic`) has the law and why it descends; docs/performance.md the cost.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..effectiveness.model import AzimuthLimits, Model, SampleLimits
from ..effectiveness.resolve import pointing
from ..effectiveness.sectors import surroundings
from ..solvers import BackendFactory
from ..solvers.outcome import Outcome
from ..vehicle.angles import wrap
from ..vehicle.config import RotationConfig, Vehicle
from .base import CIRCLE_SIDES, AllocationMethod, MethodOutput

HALVINGS = 4
"""Times a step that would raise the Lyapunov function is halved before the law stays put."""
PINNED = 1e-12
"""[rad] A window of angles narrower than this is a single direction."""
QUARTER_TURN = 0.5 * math.pi
RATE_EDGE = 1e-9
"""[rad] A window edge this close to the present angle plus or minus the rate step is the rate
limit's, not a sector's."""
ON_BOUND = 1e-9
"""Rounding, not a modelling choice: a normalised force this close to a bound (or a magnitude
this fraction from it) is on the bound."""
RELEASE = 1e-12
"""Rounding: a held bound's multiplier of the wrong sign smaller than this share of the
largest is taken as zero."""


class DynamicAllocation(AllocationMethod):
    """Allocation method ``dynamic``."""

    name = "dynamic"
    saturation_modes = ("weighted",)

    def __init__(self, model: Model, backend: BackendFactory):
        super().__init__(model, backend)
        self._use(model)
        self._x = np.zeros(model.m)
        self._request = np.zeros(model.n)
        self._sample: np.ndarray | None = None
        self._start = (self._x, self._request)

    @classmethod
    def thrust_region_sides(cls, vehicle: Vehicle) -> int | None:
        return CIRCLE_SIDES

    def update_model(self, model: Model) -> None:
        """Take a configuration with the same structure: new arrays; the state carries over."""
        self._use(model)

    def _use(self, model: Model) -> None:
        """Per-configuration arrays in normalised units: forces by their actuator's range F,
        DOFs by their authority D, the cost by its largest effort curvature."""
        self.model = model
        force = np.maximum(model.force_scale, 1e-9)[model.extended_owner]
        self._column_force = force
        self._dof = model.dof_scale
        self._t = model.t_ec * force / self._dof[:, None]
        weight = model.weight_ext * force * force
        slack = model.slack_weights(model.weight) * self._dof * self._dof
        reference = float(np.max(weight))
        self._weight = weight / reference
        self._slack = slack / reference
        self._weighted_t = self._t.T * self._slack                    # T' Q
        self._hessian = np.diag(self._weight) + self._weighted_t @ self._t
        self._gain = model.vehicle.dynamic_gain
        self._scalar_columns = model.scalar_columns
        self._rot_pairs = [(int(i), int(c1), int(c2)) for i, (c1, c2) in zip(model.rot, model.rot_columns)]
        self._hold = (model.hold / np.maximum(model.force_scale, 1e-9)).tolist()
        self._angle_step = model.angle_step[model.rot].tolist()
        self._rotations = [model.vehicle.actuators[i].rotation for i in model.rot]

    # -- one sample -------------------------------------------------------------------------

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        if limits.thrust is self._sample:
            self._x, self._request = self._start                # another pass of the same sample
        else:
            self._sample = limits.thrust
            self._start = (self._x, self._request)
        request = tau / self._dof
        static = self._static_limits(limits)
        x = self._project(self._x, static, limits)
        gradient = self._weight * x + self._weighted_t @ (self._t @ x - request)
        drive = self._gain * gradient - (1.0 - self._gain) * (self._weighted_t @ (request - self._request))
        low, high = self._scalar_bounds(limits)
        scalar = x[self._scalar_columns]
        held = (scalar <= low + ON_BOUND) | (scalar >= high - ON_BOUND)
        full, step = self._newton(x, gradient, drive, static, limits, held)
        if held.any():
            released = self._release(scalar, (gradient + self._hessian @ full)[self._scalar_columns], low, high, held)
            if released >= 0:
                held[released] = False
                full, step = self._newton(x, gradient, drive, static, limits, held)
        new, tries = self._move(x, step, request, static, limits, low, high)
        if not np.isfinite(new).all():
            return MethodOutput(force=np.zeros(self.model.m), status="not finite", iterations=tries,
                                outcome=Outcome.FAILED)
        self._x, self._request = new, request
        return MethodOutput(force=self._commanded(new, request, limits) * self._column_force, status="solved",
                            iterations=tries)

    def _scalar_bounds(self, limits: SampleLimits) -> tuple[np.ndarray, np.ndarray]:
        """The static thrust range of each scalar column, normalised."""
        columns = self._scalar_columns
        force = self._column_force[columns]
        low = limits.low if limits.range_low is None else limits.range_low
        high = limits.high if limits.range_high is None else limits.range_high
        return low[self.model.scalar] / force, high[self.model.scalar] / force

    def _newton(self, x: np.ndarray, gradient: np.ndarray, drive: np.ndarray, static: list[AzimuthLimits],
                limits: SampleLimits, held: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The whole Newton step to the minimum of J on the face the held limits leave (the
        scalar forces ``held`` on their bounds), and the law's step (``drive``) on the same
        face: one linear solve with two right-hand sides."""
        basis, curvature = self._free_directions(x, gradient, static, limits, held=held)
        if not basis.shape[1]:
            return np.zeros(self.model.m), np.zeros(self.model.m)
        reduced = basis.T @ self._hessian @ basis + np.diag(curvature)
        steps = -basis @ np.linalg.solve(reduced, basis.T @ np.column_stack((gradient, drive)))
        return steps[:, 0], steps[:, 1]

    @staticmethod
    def _release(scalar: np.ndarray, multiplier: np.ndarray, low: np.ndarray, high: np.ndarray,
                 held: np.ndarray) -> int:
        """The held scalar force (its index among the scalar columns) whose bound does not
        hold: at the minimum on the face, the gradient there (g + H d, the bound's KKT
        multiplier) pulls it off the bound; the one pulled hardest, or -1 when every held
        bound's multiplier has the sign that keeps it."""
        wrong = np.where(held & (scalar <= low + ON_BOUND), -multiplier, 0.0) + \
            np.where(held & (scalar >= high - ON_BOUND), multiplier, 0.0)
        worst = int(np.argmax(wrong))
        return worst if wrong[worst] > RELEASE * max(float(np.max(np.abs(multiplier))), 1.0) else -1

    def _move(self, x: np.ndarray, step: np.ndarray, request: np.ndarray, static: list[AzimuthLimits],
              limits: SampleLimits, low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, int]:
        """The state after ``step``: x + step where no limit stops it. Where one does, the
        better (lower V) of the step projected on S, halved while it would raise V, and the
        step cut where the first scalar force reaches its bound, a descent along the face's
        Newton direction; x when neither lowers V."""
        if not step.any():
            return x, 0
        value = self._cost(x, request)
        best, best_value = x, value + 1e-12 * max(abs(value), 1.0)
        target = x + step
        trial = self._project(target, static, limits)
        trial_value = self._cost(trial, request)
        if trial_value <= best_value and np.array_equal(trial, target):
            return trial, 1
        columns = self._scalar_columns
        move = step[columns]
        moving = move != 0.0
        room = np.where(move > 0.0, high - x[columns], low - x[columns])
        share = float(np.min(room[moving] / move[moving], initial=1.0))
        if 0.0 < share < 1.0:
            cut = self._project(x + share * step, static, limits)
            cut_value = self._cost(cut, request)
            if cut_value <= best_value:
                best, best_value = cut, cut_value
        tries = 1
        while trial_value > best_value and best is x and tries <= HALVINGS:
            step = 0.5 * step
            trial = self._project(x + step, static, limits)
            trial_value = self._cost(trial, request)
            tries += 1
        return (trial, tries) if trial_value <= best_value else (best, tries)

    def _commanded(self, x: np.ndarray, request: np.ndarray, limits: SampleLimits) -> np.ndarray:
        """The state brought into this sample's limits, then one Newton step of J within them
        (actuators a rate limit holds stay, the others make up what those miss; a rotatable
        thruster only along the angle the state gives it, so that it keeps turning toward the
        state), kept if it lowers J."""
        sample = self._project(x, None, limits)
        if not np.array_equal(sample, x):
            gradient = self._weight * sample + self._weighted_t @ (self._t @ sample - request)
            basis, curvature = self._free_directions(sample, gradient, limits.azimuth, limits, sample=True)
            if basis.shape[1]:
                reduced = basis.T @ self._hessian @ basis + np.diag(curvature)
                trial = self._along(sample, sample - basis @ np.linalg.solve(reduced, basis.T @ gradient), limits)
                if self._cost(trial, request) < self._cost(sample, request):
                    return trial
        return sample

    def _along(self, sample: np.ndarray, trial: np.ndarray, limits: SampleLimits) -> np.ndarray:
        """``trial`` within this sample's limits, each rotatable thruster kept on the angle it has
        in ``sample`` (its thrust clipped to its window)."""
        model = self.model
        out = trial.copy()
        if model.scalar.size:
            columns = self._scalar_columns
            force = self._column_force[columns]
            out[columns] = np.minimum(np.maximum(trial[columns], limits.low[model.scalar] / force),
                                      limits.high[model.scalar] / force)
        for lim, (_, c1, c2) in zip(limits.azimuth, self._rot_pairs):
            magnitude = math.hypot(sample[c1], sample[c2])
            if magnitude == 0.0:
                out[c1], out[c2] = sample[c1], sample[c2]
                continue
            sign = 1.0 if lim.sigma > 0 else -1.0
            cos, sin = sign * sample[c1] / magnitude, sign * sample[c2] / magnitude
            scale = float(self._column_force[c1])
            thrust = min(max(trial[c1] * cos + trial[c2] * sin, lim.thrust_low / scale), lim.thrust_high / scale)
            out[c1], out[c2] = thrust * cos, thrust * sin
        return out

    def _cost(self, x: np.ndarray, request: np.ndarray) -> float:
        miss = self._t @ x - request
        return 0.5 * float(x @ (self._weight * x) + miss @ (self._slack * miss))

    # -- limits -----------------------------------------------------------------------------

    def _static_limits(self, limits: SampleLimits) -> list[AzimuthLimits]:
        """Each rotatable thruster's limits without its rate limits (see :func:`_static`)."""
        range_low = limits.low if limits.range_low is None else limits.range_low
        range_high = limits.high if limits.range_high is None else limits.range_high
        rotations = self._rotations if limits.rotations is None else limits.rotations
        return [_static(lim, rotation, float(limits.angle[i]), step, float(range_low[i]), float(range_high[i]))
                for lim, rotation, step, (i, _, _) in zip(limits.azimuth, rotations, self._angle_step,
                                                          self._rot_pairs)]

    def _project(self, x: np.ndarray, static: list[AzimuthLimits] | None, limits: SampleLimits) -> np.ndarray:
        """The nearest point of the static limits (``static`` given) or of this sample's."""
        model = self.model
        out = x.copy()
        if model.scalar.size:
            columns = self._scalar_columns
            force = self._column_force[columns]
            if static is None:
                low, high = limits.low, limits.high
            else:
                low = limits.low if limits.range_low is None else limits.range_low
                high = limits.high if limits.range_high is None else limits.range_high
            out[columns] = np.minimum(np.maximum(x[columns], low[model.scalar] / force), high[model.scalar] / force)
        for k, (i, c1, c2) in enumerate(self._rot_pairs):
            lim = limits.azimuth[k] if static is None else static[k]
            out[c1], out[c2] = _sector_projection(lim, float(limits.angle[i]), float(x[c1]), float(x[c2]),
                                                  float(self._column_force[c1]), self._hold[i])
        return out

    def _free_directions(self, x: np.ndarray, gradient: np.ndarray, static: list[AzimuthLimits],
                         limits: SampleLimits, sample: bool = False,
                         held: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Z (m x k) and the curvature C (k) the circle adds along each column of Z, within the
        static limits (or this sample's, ``sample``). The scalar forces ``held`` (given) stay;
        without it, one on a bound of this sample's range stays where the gradient pushes it
        against the bound."""
        model = self.model
        columns: list[np.ndarray] = []
        curvature: list[float] = []
        if model.scalar.size:
            if held is None:
                force = self._column_force[self._scalar_columns]
                low, high = limits.low[model.scalar] / force, limits.high[model.scalar] / force
                push = gradient[self._scalar_columns]
                held = ((x[self._scalar_columns] <= low + ON_BOUND) & (push > 0.0)) | \
                    ((x[self._scalar_columns] >= high - ON_BOUND) & (push < 0.0))
            for c in self._scalar_columns[~held].tolist():
                column = np.zeros(model.m)
                column[c] = 1.0
                columns.append(column)
                curvature.append(0.0)
        for k, (i, c1, c2) in enumerate(self._rot_pairs):
            free = _free_along(static[k], float(limits.angle[i]), float(x[c1]), float(x[c2]), float(gradient[c1]),
                               float(gradient[c2]), float(self._column_force[c1]), self._hold[i]) if sample else \
                _free_in_plane(static[k], float(limits.angle[i]), float(x[c1]), float(x[c2]), float(gradient[c1]),
                               float(gradient[c2]), float(self._column_force[c1]), self._hold[i])
            for direction, bend in free:
                column = np.zeros(model.m)
                column[c1], column[c2] = direction
                columns.append(column)
                curvature.append(bend)
        if not columns:
            return np.zeros((model.m, 0)), np.zeros(0)
        return np.column_stack(columns), np.array(curvature)


def _static(lim: AzimuthLimits, rotation: RotationConfig, alpha0: float, angle_step: float, range_low: float,
            range_high: float) -> AzimuthLimits:
    """A rotatable thruster's limits without its rate limits: the thrust window opened to the
    static range on its side, and, when the rate step bounds its angles, the allowed piece the
    thruster is in within a quarter turn of the direction the planner sends it to (its goal;
    its present angle when it has none): a convex cone, as the planner keeps every window,
    that holds where the thruster is going rather than where it is. Sectors, the feasible
    sector and a crossing's zero thrust stay."""
    if lim.magnitude_max == 0.0:
        return lim
    if lim.line:
        return replace(lim, thrust_low=range_low, thrust_high=range_high)
    low, high = lim.low, lim.high
    if abs(alpha0 - angle_step - low) <= RATE_EDGE or abs(alpha0 + angle_step - high) <= RATE_EDGE:
        piece = surroundings(rotation, alpha0)[2] or (0.0, 0.0)
        centre = alpha0 if lim.goal is None else alpha0 + wrap(lim.goal - alpha0)
        low = max(alpha0 + piece[0], centre - QUARTER_TURN)
        high = min(alpha0 + piece[1], centre + QUARTER_TURN)
        if low > high:
            low, high = alpha0 + max(piece[0], -QUARTER_TURN), alpha0 + min(piece[1], QUARTER_TURN)
    side = (0.0, lim.physical_max) if lim.sigma > 0 else (-lim.physical_max, 0.0)
    return replace(lim, low=low, high=high, thrust_low=side[0], thrust_high=side[1])


def _pinned(lim: AzimuthLimits) -> bool:
    return lim.line or lim.high - lim.low < PINNED or lim.magnitude_max == 0.0


def _angle(lim: AzimuthLimits, alpha0: float, z1: float, z2: float, hold: float) -> float:
    """The thruster angle nearest to pushing along (z1, z2) within the window: a pinned
    thruster's one direction, else the angle the allocator resolves the force to."""
    if _pinned(lim):
        return lim.low if math.isfinite(lim.low) else alpha0
    return pointing(lim, alpha0, z1, z2, hold)


def _sector_projection(lim: AzimuthLimits, alpha0: float, z1: float, z2: float, scale: float,
                       hold: float) -> tuple[float, float]:
    """The point of a rotatable thruster's allowed set nearest to (z1, z2) (forces in units of
    ``scale``): thrust F in [thrust_low, thrust_high] along an angle in [low, high], the point
    the allocator's resolve also picks."""
    angle = _angle(lim, alpha0, z1, z2, hold)
    cos, sin = math.cos(angle), math.sin(angle)
    thrust = min(max(z1 * cos + z2 * sin, lim.thrust_low / scale), lim.thrust_high / scale)
    return thrust * cos, thrust * sin


def _free_in_plane(lim: AzimuthLimits, alpha0: float, x1: float, x2: float, g1: float, g2: float, scale: float,
                   hold: float) -> list[tuple[tuple[float, float], float]]:
    """The directions in which a rotatable thruster's force may move (unit vectors in its
    plane) with the curvature each adds: both when nothing holds it; along the circle, with
    curvature lambda / B, at its thrust limit; along its direction at an edge of its angles;
    along its line when STUCK; none when pinned at a limit."""
    low, high = lim.thrust_low / scale, lim.thrust_high / scale
    if _pinned(lim):
        if lim.magnitude_max == 0.0:
            return []
        angle = lim.low if math.isfinite(lim.low) else alpha0
        cos, sin = math.cos(angle), math.sin(angle)
        along, push = x1 * cos + x2 * sin, -(g1 * cos + g2 * sin)
        held = (along >= high - ON_BOUND and push > 0.0) or (along <= low + ON_BOUND and push < 0.0)
        return [] if held else [((cos, sin), 0.0)]
    magnitude = math.hypot(x1, x2)
    if magnitude <= hold:
        if not (math.isfinite(lim.low) or math.isfinite(lim.high)):
            return [((1.0, 0.0), 0.0), ((0.0, 1.0), 0.0)]
        # At the cone's vertex: the one direction of the cone that descends fastest, if any.
        d1, d2 = _sector_projection(replace(lim, thrust_low=0.0, thrust_high=scale), alpha0, -g1, -g2, scale, 0.0)
        size = math.hypot(d1, d2)
        return [((d1 / size, d2 / size), 0.0)] if size > 0.0 else []
    radial = (x1 / magnitude, x2 / magnitude)
    tangent = (-radial[1], radial[0])
    outward = -(g1 * radial[0] + g2 * radial[1])
    bound = max(abs(low), abs(high))
    at_circle = magnitude >= bound * (1.0 - ON_BOUND) and outward > 0.0
    angle = math.atan2(x2, x1) if lim.sigma > 0 else math.atan2(-x2, -x1)
    angle = alpha0 + wrap(angle - alpha0)
    turning = -(g1 * tangent[0] + g2 * tangent[1])             # > 0: toward larger angles
    at_edge = (angle <= lim.low + ON_BOUND and turning < 0.0) or (angle >= lim.high - ON_BOUND and turning > 0.0)
    if at_circle and at_edge:
        return []
    if at_circle:
        return [(tangent, outward / magnitude)]
    if at_edge:
        return [(radial, 0.0)]
    return [((1.0, 0.0), 0.0), ((0.0, 1.0), 0.0)]


def _free_along(lim: AzimuthLimits, alpha0: float, x1: float, x2: float, g1: float, g2: float, scale: float,
                hold: float) -> list[tuple[tuple[float, float], float]]:
    """Within this sample: a rotatable thruster's force may change along the angle the state
    gives it, unless its thrust window holds it there."""
    angle = _angle(lim, alpha0, x1, x2, hold)
    cos, sin = math.cos(angle), math.sin(angle)
    along, push = x1 * cos + x2 * sin, -(g1 * cos + g2 * sin)
    low, high = lim.thrust_low / scale, lim.thrust_high / scale
    held = (along >= high - ON_BOUND and push > 0.0) or (along <= low + ON_BOUND and push < 0.0) or high - low <= 0.0
    return [] if held else [((cos, sin), 0.0)]

