"""Allocation method ``qp`` (the default): the constrained QP (1.35)-(1.40) on one warm-started
solver problem per configuration (:mod:`~.qp_problem`).

Each sample writes values only: the request, the thrust boxes, and for each rotatable thruster
the polygon of (1.46) turned to the direction it pushes in, the bounds of this sample's angles
and, at its thrust limit, the circle's curvature; with thrust bias, the linear term of the
offset (:mod:`~.bias`). An unattainable request is then answered by
the scale problem of ``saturation: preserve_direction``, by Durham's direct method for
``saturation: direct`` (section 4.3), or by the cascade of DOF priorities, one DAQP stage per
level. docs/theory.md has the theory (sections `qp`, DOF priorities, thrust bias, and
rotatable thrusters near their capability); docs/performance.md the cost.
"""

from __future__ import annotations

import math

import numpy as np

from ..effectiveness.model import AT_LIMIT, Model, SampleLimits
from ..effectiveness.power_rows import PowerPattern, PowerRows
from ..solvers import BACKENDS, BackendFactory
from ..solvers.backend import NO_BOUND
from ..vehicle.config import Vehicle
from .base import CIRCLE_SIDES, AllocationMethod, MethodOutput
from .bias import biased_objective
from .direct import DirectSolution
from .qp_problem import QPProblem, build, constant_bounds, objective, write_power

PINNED = 1e-12
"""[rad] A window of angles narrower than this is a single direction."""
SLAB_STEP = 0.5 * math.pi
"""Rate steps below this bound v by a slab |v| <= B sin(step); wider windows by their edges."""
CURVATURE_CHANGE = 1e-3
"""The thrust-limit curvature is sent to the solver again only when it changes by more than
this fraction (a new P means a new factorisation)."""
SATURATION_SLACK = 1e-6
"""Slack, as a fraction of its DOF's authority, above which a request counts as unattainable."""
PRIORITY_HOLD = 1e-6
"""How far, as a fraction of its DOF's authority, a higher priority level's achieved wrench may
move away from the request while a lower level is solved: a margin for rounding, so that every
stage is feasible."""
POWER_MARGIN = 1e-7
"""A source row's bound lies this share below the available power: the power rows are solved
by DAQP, exact to rounding, and a solution it accepts keeps the source within A_j."""
CASCADE_BACKEND = "daqp"
"""The backend of the priority cascade's stages: exact on the sliver a saturated level leaves
the next (docs/theory.md, DOF priorities); and of the problems with power rows in force, where
a first-order solver crawls along the power boundary (docs/theory.md, power rows)."""


class QPAllocation(AllocationMethod):
    """Allocation method ``qp``."""

    name = "qp"
    saturation_modes = ("weighted", "preserve_direction", "direct")
    implements_priorities = True
    implements_bias = True
    power_rows = True

    def __init__(self, model: Model, backend: BackendFactory):
        super().__init__(model, backend)
        self._use(model)
        self._direct = DirectSolution(model) if model.vehicle.saturation == "direct" else None
        self.setups += self._direct is not None
        self._problems(model, PowerPattern.of(model.vehicle))

    def _problems(self, model: Model, pattern: PowerPattern | None) -> None:
        """Set up the main problem and the scale problem on the method's backend, and with the
        power rows of ``pattern`` (docs/theory.md, power rows) the same two on
        CASCADE_BACKEND, used while some source is short, and the cascade's."""
        self._pattern, self._short = pattern, False
        preserve = model.vehicle.saturation == "preserve_direction"
        self._free = (self._setup(model, scale=False), self._setup(model, scale=True) if preserve else None)
        self._rows = (self._setup(model, False, rows=True), self._setup(model, True, rows=True) if preserve else None) \
            if pattern is not None else (None, None)
        self._stages = self._setup(model, scale=False, stages=True) if model.vehicle.priority_levels else None

    @property
    def _main(self) -> QPProblem:
        return self._rows[0] if self._short else self._free[0]

    @property
    def _scale(self) -> QPProblem | None:
        return self._rows[1] if self._short else self._free[1]

    def set_power(self, rows: PowerRows | None) -> None:
        """The power rows' values in every problem that has them: entries and bounds only,
        unless the rows come on another pattern (then the problems are set up again). The
        samples solve with them while some source is short (``short``), else without."""
        self.power = rows
        if rows is None:
            self._short = False
            return
        if not rows.pattern.same(self._pattern):
            self._problems(self.model, rows.pattern)
        for problem in (*self._rows, self._stages):
            if problem is not None:
                write_power(problem, rows, POWER_MARGIN)
        self._short = bool(rows.short().any())

    @classmethod
    def thrust_region_sides(cls, vehicle: Vehicle) -> int | None:
        """The circle: at rest a thruster pushes along its polygon's face normal, where the
        bound is its exact thrust limit."""
        return CIRCLE_SIDES

    def _use(self, model: Model) -> None:
        """Per-configuration constants of the per-sample path, as the types it reads fastest."""
        self._rot = model.rot.tolist()
        self._angle_step = model.angle_step[model.rot].tolist()
        self._rot_columns = [(int(c1), int(c2)) for c1, c2 in model.rot_columns]
        self._u_columns = model.rot_columns[:, 0].copy()
        first, second = model.t_ec[:, model.rot_columns[:, 0]].T, model.t_ec[:, model.rot_columns[:, 1]].T
        # Per thruster, the matrix taking (cos d, sin d) to its equality entries T_e R(d), row
        # by row the u then the v column: u = t1 cos + t2 sin, v = t2 cos - t1 sin.
        self._rotation = np.stack((np.stack((first, second), axis=-1), np.stack((second, -first), axis=-1)),
                                  axis=2).reshape(len(self._rot), 2 * model.n, 2)
        self._levels = [np.array(level, dtype=int) for level in model.vehicle.priority_levels]
        self._lower = [np.concatenate(self._levels[k + 1:]) if k + 1 < len(self._levels) else np.zeros(0, int)
                       for k in range(len(self._levels))]
        self._hold = PRIORITY_HOLD * model.dof_scale

    def update_model(self, model: Model) -> None:
        """Take a configuration with the same structure: values only, no new set-up (unless the
        feeds changed the power rows' pattern)."""
        self.model = model
        pattern = PowerPattern.of(model.vehicle)
        if (pattern is None) != (self._pattern is None) or (pattern is not None and not pattern.same(self._pattern)):
            self._use(model)
            self._problems(model, pattern)
            self.power = None
            return
        for problem, scale in ((self._free[0], False), (self._free[1], True), (self._rows[0], False),
                               (self._rows[1], True), (self._stages, False)):
            if problem is None:
                continue
            # Of A's values only T_e's follow the configuration (the rest is fixed by the
            # structure); the moving entries are written again by the next sample.
            values = problem.qp.a.data.copy()
            values[problem.t_ec_index] = model.t_ec.ravel()
            p, q = objective(model, scale)
            if problem.power is not None:
                p = np.concatenate((p, np.zeros(problem.power.columns)))
                q = np.concatenate((q, np.zeros(problem.power.columns)))
            constant_bounds(problem.qp, model, problem.index, scale)
            problem.qp.update_matrix(values)
            problem.qp.update_objective(p, q)
            problem.qp.update_settings(model.vehicle.solver)
            problem.p_diagonal, problem.q, problem.biased = p, q, False
            problem.directions, problem.edges = [], []
            problem.multiplier, problem.curvature = [0.0] * len(model.rot), [0.0] * len(model.rot)
            problem.version = -1
            if self.power is not None and problem.power is not None:
                write_power(problem, self.power, POWER_MARGIN)
        if self._direct is not None:
            self._direct.update_model(model)
        self._use(model)

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        output, x = self._solve(self._main, tau, limits)
        if (self._scale is None and self._direct is None and not self._levels) or not output.usable:
            return output
        slack = x[self.model.m:self.model.m + self.model.n]
        if np.all(np.abs(slack) <= SATURATION_SLACK * self.model.authority):
            return output
        if self._levels:
            return self._cascade(tau, limits, output)
        if self._direct is not None:
            boundary = self._direct.solve(tau, limits)
            boundary.iterations += output.iterations
            return boundary if boundary.usable else output
        scaled, _ = self._solve(self._scale, tau, limits)
        scaled.iterations += output.iterations
        return scaled if scaled.usable else output

    def _cascade(self, tau: np.ndarray, limits: SampleLimits, output: MethodOutput) -> MethodOutput:
        """The lexicographic solve of DOF priorities, by values only (docs/theory.md, DOF
        priorities): each level's achieved wrench is held while the next is solved; a stage
        that fails leaves the last usable answer."""
        problem, model = self._stages, self.model
        self._prepare(problem, tau, limits)
        qp, equality, slack = problem.qp, problem.equality, problem.slack
        low, up = qp.low, qp.up
        iterations = output.iterations
        for level, lower in zip(self._levels, self._lower):
            low[equality[level]] = up[equality[level]] = tau[level]
            low[slack[level]], up[slack[level]] = -NO_BOUND, NO_BOUND
            low[equality[lower]], up[equality[lower]] = -NO_BOUND, NO_BOUND
            low[slack[lower]] = up[slack[lower]] = 0.0
            solution = qp.solve(low, up)
            iterations += solution.iterations
            if not solution.usable:
                break
            x = solution.x
            output = MethodOutput(force=self._forces(problem, x), status=solution.status, outcome=solution.outcome,
                                  residual=solution.residual)
            missed = x[model.m + level]
            low[equality[level]] = tau[level] + np.minimum(missed, 0.0) - self._hold[level]
            up[equality[level]] = tau[level] + np.maximum(missed, 0.0) + self._hold[level]
            low[slack[level]] = up[slack[level]] = 0.0
        output.iterations = iterations
        return output

    def _forces(self, problem: QPProblem, x: np.ndarray) -> np.ndarray:
        """The extended forces of a solution, rotatable thrusters back in the body frame."""
        force = x[:self.model.m].copy()
        for (c1, c2), cos, sin in zip(self._rot_columns, problem.cos, problem.sin):
            u, v = float(x[c1]), float(x[c2])
            force[c1], force[c2] = cos * u - sin * v, sin * u + cos * v
        return force

    def _setup(self, model: Model, scale: bool, stages: bool = False, rows: bool = False) -> QPProblem:
        """One of the method's problems (:func:`~.qp_problem.build`) on its backend, the
        cascade's and those with power ``rows`` on ``CASCADE_BACKEND``."""
        exact = stages or rows
        problem = build(model, scale, BACKENDS[CASCADE_BACKEND]() if exact else self.backend(), stages,
                        self._pattern if exact else None)
        self.setups += 1
        return problem

    # -- per sample ---------------------------------------------------------------------

    def _solve(self, problem: QPProblem, tau: np.ndarray, limits: SampleLimits) -> tuple[MethodOutput, np.ndarray]:
        model = self.model
        qp = problem.qp
        self._prepare(problem, tau, limits)
        solution = qp.solve(qp.low, qp.up)
        x = solution.x
        if model.rot.size:
            force = self._forces(problem, x)
            at_limit = False
            if solution.usable:
                at_limit = any(u >= bound * (1.0 - AT_LIMIT) > 0.0 for u, bound in
                               zip(x[self._u_columns].tolist(), qp.up[problem.polygon[:, 0]].tolist()))
                problem.multiplier = (np.maximum(solution.y[problem.polygon], 0.0).sum(axis=1)
                                      + np.maximum(solution.y[problem.polygon_minimax], 0.0).sum(axis=1)).tolist() \
                    if at_limit else [0.0] * len(self._rot)
        else:
            force = x[:model.m].copy()
        output = MethodOutput(force=force if solution.usable else np.zeros(model.m), status=solution.status,
                              iterations=solution.iterations, outcome=solution.outcome, residual=solution.residual)
        return output, x

    def _prepare(self, problem: QPProblem, tau: np.ndarray, limits: SampleLimits) -> None:
        """This sample's values in a problem: the request, the thrust boxes (when the limits
        changed), the rotatable thrusters' rows."""
        model = self.model
        qp = problem.qp
        if problem.scale_index.size:
            qp.update_matrix(-tau, problem.scale_index)
        else:
            qp.low[problem.equality] = qp.up[problem.equality] = tau
        if limits.version < 0 or limits.version != problem.version:
            qp.low[problem.box] = limits.low[model.scalar]
            qp.up[problem.box] = limits.high[model.scalar]
            problem.version = limits.version
        if model.rot.size:
            self._azimuth_rows(problem, limits)
            biased_objective(problem, limits.bias, self._rot_columns)

    def _azimuth_rows(self, problem: QPProblem, limits: SampleLimits) -> None:
        """Each rotatable thruster in its own frame (u along the direction d it pushes in, v
        across it): the equality entries T_e R(d), the polygon's bound, and the bounds and
        edges of this sample's angles. Only values change, and values are sent to the solver
        only when they differ from the last sample's (at rest, none do)."""
        qp = problem.qp
        low, up = qp.low, qp.up
        angles = limits.angle
        directions, edges, bounds = [], [], []
        for k, lim in enumerate(limits.azimuth):
            i, step = self._rot[k], self._angle_step[k]
            polygon, along, across, edge_low, edge_high = problem.rows[k]
            alpha0 = float(angles[i])
            low[edge_low] = low[edge_high] = -NO_BOUND
            up[edge_low] = up[edge_high] = NO_BOUND
            if lim.line or lim.high - lim.low < PINNED or lim.magnitude_max == 0.0:
                # One direction: the force is F along it, F in [thrust_low, thrust_high].
                directions.append(lim.low if math.isfinite(lim.low) else alpha0)
                up[polygon] = NO_BOUND
                low[along], up[along] = lim.thrust_low, lim.thrust_high
                low[across] = up[across] = 0.0
                edges += (0.0, 1.0, 0.0, 1.0)
                bounds.append(0.0)
                continue
            directions.append(alpha0 + math.pi if lim.sigma < 0 else alpha0)
            smallest, largest = (lim.thrust_low, lim.thrust_high) if lim.sigma > 0 else \
                (-lim.thrust_high, -lim.thrust_low)
            bound = max(min(lim.physical_max, largest), smallest)
            bounds.append(bound)
            up[polygon] = bound
            narrow = step < SLAB_STEP
            low[along], up[along] = (max(smallest, 0.0) if narrow or smallest > 0.0 else -NO_BOUND), NO_BOUND
            slab = bound * math.sin(step) if narrow else NO_BOUND
            offset_low, offset_high = lim.low - alpha0, lim.high - alpha0
            edge = [0.0, 1.0, 0.0, 1.0]
            up[across] = NO_BOUND
            if offset_high >= step - PINNED and narrow:
                up[across] = slab
            elif math.isfinite(offset_high):
                edge[2:] = (-math.sin(offset_high), math.cos(offset_high))
                up[edge_high] = 0.0
            low[across] = -NO_BOUND
            if offset_low <= -step + PINNED and narrow:
                low[across] = -slab
            elif math.isfinite(offset_low):
                edge[:2] = (-math.sin(offset_low), math.cos(offset_low))
                low[edge_low] = 0.0
            edges += edge
        p_diagonal = self._circle_curvature(problem, bounds)
        if directions != problem.directions or edges != problem.edges:
            if directions != problem.directions:
                problem.directions = directions
                problem.cos = [math.cos(d) for d in directions]
                problem.sin = [math.sin(d) for d in directions]
                problem.rotated = (self._rotation @ np.array([problem.cos, problem.sin]).T[:, :, None]).reshape(-1)
            problem.edges = edges
            qp.update_entries(problem.moving, np.concatenate((problem.rotated, edges)), p_diagonal)
        elif p_diagonal is not None:
            qp.update_objective(p_diagonal)

    def _circle_curvature(self, problem: QPProblem, bounds: list[float]) -> np.ndarray | None:
        """The curvature of |f| <= B across the pushing direction, weighted by the thrust
        limit's multiplier of the last sample: 1/2 (lambda / B) v^2 added to the cost.

        The polygon's faces are flat; the circle they stand for curves by 1/B. At a thruster's
        limit (lambda > 0) a flat face overestimates the force off its normal by B (1/cos - 1),
        a second-order gain the QP takes by turning a full rate step, then turning back: a
        two-sample cycle. With the circle's curvature in the Lagrangian, the QP is the
        second-order model of the thrust circle (a sequential QP step), and the angle settles
        where the circle's optimum is. A thruster below its limit has lambda = 0: nothing changes.
        Returns the new diagonal of P, or None when it stays.
        """
        curvature = [m / b if b > 0.0 else 0.0 for m, b in zip(problem.multiplier, bounds)]
        if all(abs(c - old) <= CURVATURE_CHANGE * max(c, old) for c, old in zip(curvature, problem.curvature)):
            return None
        problem.curvature = curvature
        p = problem.p_diagonal.copy()
        p[self.model.rot_columns[:, 1]] += curvature
        return p
