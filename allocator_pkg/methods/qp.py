"""Constrained allocation (1.35) as one warm-started OSQP problem per configuration.

Decision vector z = [f_e, s, fbar] (1.38): extended forces (two per rotatable thruster),
one slack per controlled DOF, and the largest force fbar:

    minimise   f_e' W f_e + s' Q s + beta fbar
    subject to T_e f_e - s = tau                          (equality of (1.35))
               low_i <= f_i <= high_i                     (thrust box, tightened by rate limits)
               -fbar <= f_i <= fbar                       (minimax, scalar actuators)
               n_k . (u_j, v_j) <= B_j,  k = 1..N         (|f_j| <= B_j, the N-gon of 5.3, rotatable j)
               n_k . (u_j, v_j) <= fbar                   (minimax, rotatable j)
               u_j >= u_min,  v_j within this sample's angles (rate limit and sector edges)

A rotatable thruster's two extended components are written in its own frame this sample:
(u, v) = R(-d) f_j, with d the direction it pushes in now (its angle, or the opposite one
when it pushes backwards), u along d and v across it. Its polygon has a face normal along d
at distance B, the most it may push this sample (thrust limit with faults, thrust rate), so
that along d the bound is exact: at rest, the thruster gives its full thrust, not the
1 - cos(pi/N) less of a polygon fixed in the body frame, and off d the polygon overestimates
by at most 1/cos(pi/N) (the final thrust is clipped to the exact limits). The angles
reachable this sample are simple bounds on v (|v| <= B sin(step) for a rate step below
90 degrees) and, where a forbidden sector, the feasible sector or the half-plane a wide window
is cut to lies nearer than the rate step, a half-plane through the origin at that edge. Each
sample changes only values: the entries of T_e R(d) in the equality rows and the edge rows
(``Ax``), and the bounds (``l``, ``u``). P never changes. Why this form, and not a cone of
two half-planes in the body frame, is in docs/theory.md (azimuths near capability).

The matrices are built once per configuration with every entry that can ever be non-zero
stored explicitly (T_e dense, both components of every half-plane), so that each sample
only updates values on the same pattern; OSQP keeps its previous primal and dual iterates
and starts the next sample from them (warm start). A configuration change of values only
(positions, directions, weights, limits) updates ``Ax``/``Px``/``q`` on the same pattern;
only a change of the pattern itself (number or type of actuators, DOFs, polygon sides,
saturation mode) sets the problem up again.

The problem is normalised once per configuration (:class:`~allocator_pkg.solvers.problem.ScaledProblem`):
forces by their actuator's range, slacks by their DOF's authority, rows by their largest
coefficient, the cost by its largest curvature, so that the Q >> W weighting of (1.35) does
not cost OSQP thousands of iterations when a request saturates.

``saturation: preserve_direction`` adds a second problem on the same pattern idea, with a
scale lambda in place of the slack: maximise lambda subject to T_e f_e = lambda tau and the
same limits (Durham's direct idea, section 4.3), minus a small multiple of the effort
f_e' W f_e, so that among the forces reaching the largest lambda it takes the cheapest. It is
solved only when the first problem reports the request unattainable.

``saturation: direct`` answers an unattainable request with Durham's boundary solution from a
linear programme instead (:mod:`~.direct`): exact where the scale problem above stops at
OSQP's tolerance, and trading no scale for effort.

DOF priorities (``Vehicle.priority_levels``): when the ordinary solve reports the request
unattainable, a cascade follows, one solve per level, highest first, on a problem of the same
rows plus one bound row per slack, set up once per configuration and changed by values only
(bounds, and the same moving entries as the main problem): the level's equality rows ask for
tau with their slacks free; every lower level's equality rows are switched off (bounds at
infinity) and its slacks pinned at zero; every higher level's equality rows are bounds
around what its own stage achieved, T_k f in [tau_k + min(s_k, 0), tau_k + max(s_k, 0)]
widened by ``PRIORITY_HOLD`` of the DOF's authority, with its slacks pinned at zero: a
level's achieved wrench is held as a constraint for the next (lexicographic: a lower level
may only leave it as it is, or nearer the request). The stages are solved by DAQP, an exact
active-set solver, as the forbidden-sector planner is: held on the face of the attainable set
a saturated level leaves, the feasible set of the next stage is a sliver on which OSQP's
ADMM ran into ``max_iter`` in most samples tried (BlueROV2 Heavy, random requests), where DAQP
needs 20 to 60 iterations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..effectiveness.model import AT_LIMIT, Model, SampleLimits
from ..solvers import BACKENDS, BackendFactory
from ..solvers.backend import NO_BOUND
from ..solvers.problem import Entries, Rows, ScaledProblem, block_index, entry_index
from ..vehicle.config import Vehicle
from .base import CIRCLE_SIDES, AllocationMethod, MethodOutput
from .direct import DirectSolution

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
CASCADE_BACKEND = "daqp"
"""The backend of the priority cascade's stages (see the module docstring)."""


@dataclass
class _Problem:
    """One solver problem and the rows a sample writes (indices into its rows, and into the
    stored entries of A for the values that follow the thrusters' directions)."""

    qp: ScaledProblem
    equality: np.ndarray
    box: np.ndarray
    polygon: np.ndarray
    polygon_minimax: np.ndarray
    along: np.ndarray
    across: np.ndarray
    edge_low: np.ndarray
    edge_high: np.ndarray
    rotated_index: np.ndarray
    edge_index: np.ndarray
    scale_index: np.ndarray
    p_diagonal: np.ndarray
    rows: list[tuple]
    moving: Entries
    index: dict
    t_ec_index: np.ndarray
    slack: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    rotated: np.ndarray = field(default_factory=lambda: np.zeros(0))
    directions: list[float] = field(default_factory=list)
    cos: list[float] = field(default_factory=list)
    sin: list[float] = field(default_factory=list)
    edges: list[float] = field(default_factory=list)
    multiplier: list[float] = field(default_factory=list)
    curvature: list[float] = field(default_factory=list)
    version: int = -1


class QPAllocation(AllocationMethod):
    """Allocation method ``qp``."""

    name = "qp"
    saturation_modes = ("weighted", "preserve_direction", "direct")
    implements_priorities = True

    def __init__(self, model: Model, backend: BackendFactory):
        super().__init__(model, backend)
        self._use(model)
        self._main = self._setup(model, scale=False)
        self._scale = self._setup(model, scale=True) if model.vehicle.saturation == "preserve_direction" else None
        self._direct = DirectSolution(model) if model.vehicle.saturation == "direct" else None
        self.setups += self._direct is not None
        self._stages = self._setup(model, scale=False, stages=True) if model.vehicle.priority_levels else None

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
        """Take a configuration with the same structure: values only, no new set-up."""
        self.model = model
        for problem, scale in ((self._main, False), (self._scale, True), (self._stages, False)):
            if problem is None:
                continue
            # Of A's values only T_e's follow the configuration (the rest is fixed by the
            # structure); the moving entries are written again by the next sample.
            values = problem.qp.a.data.copy()
            values[problem.t_ec_index] = model.t_ec.ravel()
            p, q = self._objective(model, scale)
            self._constant_bounds(problem.qp, model, problem.index, scale)
            problem.qp.update_matrix(values)
            problem.qp.update_objective(p, q)
            problem.qp.update_settings(model.vehicle.solver)
            problem.p_diagonal = p
            problem.directions, problem.edges = [], []
            problem.multiplier, problem.curvature = [0.0] * len(model.rot), [0.0] * len(model.rot)
            problem.version = -1
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
        """The lexicographic solve of DOF priorities, by values only (see the module
        docstring); a stage that fails leaves the last usable answer."""
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

    def _forces(self, problem: _Problem, x: np.ndarray) -> np.ndarray:
        """The extended forces of a solution, rotatable thrusters back in the body frame."""
        force = x[:self.model.m].copy()
        for (c1, c2), cos, sin in zip(self._rot_columns, problem.cos, problem.sin):
            u, v = float(x[c1]), float(x[c2])
            force[c1], force[c2] = cos * u - sin * v, sin * u + cos * v
        return force

    # -- set-up -------------------------------------------------------------------------

    @staticmethod
    def _columns(model: Model, scale: bool) -> tuple[int, int, int]:
        """(first slack or the lambda column, fbar column or -1, number of columns)."""
        if scale:
            return model.m, -1, model.m + 1
        return model.m, model.m + model.n, model.m + model.n + 1

    def _column_scale(self, model: Model, scale: bool) -> np.ndarray:
        force = model.force_scale[model.extended_owner]
        if scale:
            return np.concatenate((force, [1.0]))
        return np.concatenate((force, np.maximum(model.authority, 1e-9), [float(np.max(force))]))

    @staticmethod
    def _objective(model: Model, scale: bool) -> tuple[np.ndarray, np.ndarray]:
        """Diagonal of P and q, physical units (OSQP minimises 1/2 x'Px + q'x)."""
        extra, top, columns = QPAllocation._columns(model, scale)
        q = np.zeros(columns)
        if scale:
            force = model.force_scale[model.extended_owner]
            epsilon = 1e-3 / float(np.sum(model.weight_ext * force * force))
            q[extra] = -1.0
            return np.concatenate((2.0 * epsilon * model.weight_ext, [0.0])), q
        q[top] = model.vehicle.weights.minimax
        return np.concatenate((2.0 * model.weight_ext, 2.0 * model.slack_weights(model.weight), [0.0])), q

    @staticmethod
    def _constraints(model: Model, scale: bool, stages: bool = False) -> tuple[sp.csc_matrix, dict]:
        sides = model.vehicle.azimuth_polygon_sides
        extra, top, columns = QPAllocation._columns(model, scale)
        rows = Rows()
        equality = []
        for k in range(model.n):
            entries = [(c, float(model.t_ec[k, c])) for c in range(model.m)]
            entries.append((extra, 0.0) if scale else (extra + k, -1.0))
            equality.append(rows.add(entries))
        box = [rows.add([(int(c), 1.0)]) for c in model.scalar_columns]
        minimax = []
        if not scale:
            for c in model.scalar_columns:
                minimax.append(rows.add([(int(c), 1.0), (top, -1.0)]))
                minimax.append(rows.add([(int(c), 1.0), (top, 1.0)]))
        normals = [(math.cos(2.0 * math.pi * k / sides), math.sin(2.0 * math.pi * k / sides)) for k in range(sides)]
        polygon, polygon_minimax, along, across, edge_low, edge_high = [], [], [], [], [], []
        for c1, c2 in model.rot_columns:
            c1, c2 = int(c1), int(c2)
            polygon.append([rows.add([(c1, x), (c2, y)]) for x, y in normals])
            if not scale:
                polygon_minimax.append([rows.add([(c1, x), (c2, y), (top, -1.0)]) for x, y in normals])
            along.append(rows.add([(c1, 1.0)]))
            across.append(rows.add([(c2, 1.0)]))
            edge_low.append(rows.add([(c1, 0.0), (c2, 1.0)]))
            edge_high.append(rows.add([(c1, 0.0), (c2, 1.0)]))
        last = rows.add([(extra, 1.0)] if scale else [(top, 1.0)])
        slack = [rows.add([(extra + k, 1.0)]) for k in range(model.n)] if stages else []
        index = dict(equality=np.array(equality, int), box=np.array(box, int), minimax=np.array(minimax, int),
                     polygon=np.array(polygon, int).reshape(len(model.rot), sides),
                     polygon_minimax=np.array(polygon_minimax, int).reshape(len(model.rot), 0 if scale else sides),
                     along=np.array(along, int),
                     across=np.array(across, int), edge_low=np.array(edge_low, int),
                     edge_high=np.array(edge_high, int), last=last, slack=np.array(slack, int))
        return rows.matrix(columns), index

    @staticmethod
    def _constant_bounds(qp: ScaledProblem, model: Model, index: dict, scale: bool) -> None:
        """Bounds that only a configuration changes. Without a minimax weight the fbar rows are
        switched off and fbar pinned at 0: a free, uncosted variable would slow OSQP down."""
        if scale:
            qp.low[index["equality"]] = qp.up[index["equality"]] = 0.0
            qp.low[index["last"]], qp.up[index["last"]] = 0.0, 1.0
            return
        minimax = model.vehicle.weights.minimax > 0.0
        qp.low[index["minimax"][0::2]], qp.up[index["minimax"][0::2]] = -NO_BOUND, (0.0 if minimax else NO_BOUND)
        qp.low[index["minimax"][1::2]], qp.up[index["minimax"][1::2]] = (0.0 if minimax else -NO_BOUND), NO_BOUND
        qp.up[index["polygon_minimax"].ravel()] = 0.0 if minimax else NO_BOUND
        qp.low[index["last"]], qp.up[index["last"]] = 0.0, (float(np.max(model.force_scale)) if minimax else 0.0)

    def _setup(self, model: Model, scale: bool, stages: bool = False) -> _Problem:
        a, index = self._constraints(model, scale, stages)
        p, q = self._objective(model, scale)
        extra = self._columns(model, scale)[0]
        qp = ScaledProblem(p, q, a, self._column_scale(model, scale), model.vehicle.solver,
                           effort=np.arange(0 if not scale else model.m, model.m if not scale else model.m + 1),
                           backend=BACKENDS[CASCADE_BACKEND]() if stages else self.backend())
        self._constant_bounds(qp, model, index, scale)
        rows = index["equality"]
        rotated_index = np.array([[[entry_index(a, int(row), int(col)) for col in pair] for row in rows]
                                  for pair in model.rot_columns], dtype=np.int64).reshape(len(model.rot), 2 * len(rows))
        edge_index = np.array([[entry_index(a, int(row), int(col)) for row in (low, high) for col in pair]
                               for pair, low, high in zip(model.rot_columns, index["edge_low"], index["edge_high"])],
                              dtype=np.int64).reshape(len(model.rot), 4)
        scale_index = np.array([entry_index(a, row, extra) for row in rows] if scale else [], dtype=np.int64)
        self.setups += 1
        rotatable = len(model.rot)
        per_thruster = [(index["polygon"][k], int(index["along"][k]), int(index["across"][k]),
                         int(index["edge_low"][k]), int(index["edge_high"][k])) for k in range(rotatable)]
        return _Problem(qp=qp, equality=rows, box=index["box"], polygon=index["polygon"],
                        polygon_minimax=index["polygon_minimax"], along=index["along"],
                        across=index["across"], edge_low=index["edge_low"], edge_high=index["edge_high"],
                        rotated_index=rotated_index.reshape(-1), edge_index=edge_index.reshape(-1),
                        scale_index=scale_index, p_diagonal=p, rows=per_thruster,
                        moving=qp.entries(np.concatenate((rotated_index.reshape(-1), edge_index.reshape(-1)))),
                        index=index, t_ec_index=block_index(a, rows, model.m),
                        multiplier=[0.0] * rotatable, curvature=[0.0] * rotatable, slack=index["slack"])

    # -- per sample ---------------------------------------------------------------------

    def _solve(self, problem: _Problem, tau: np.ndarray, limits: SampleLimits) -> tuple[MethodOutput, np.ndarray]:
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

    def _prepare(self, problem: _Problem, tau: np.ndarray, limits: SampleLimits) -> None:
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

    def _azimuth_rows(self, problem: _Problem, limits: SampleLimits) -> None:
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

    def _circle_curvature(self, problem: _Problem, bounds: list[float]) -> np.ndarray | None:
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
