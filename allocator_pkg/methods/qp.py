"""Constrained allocation (1.35) as one warm-started OSQP problem per configuration.

Decision vector z = [f_e, s, fbar] (1.38): extended forces (two per rotatable thruster),
one slack per controlled DOF, and the largest force fbar:

    minimise   f_e' W f_e + s' Q s + beta fbar
    subject to T_e f_e - s = tau                          (equality of (1.35))
               low_i <= f_i <= high_i                     (thrust box, tightened by rate limits)
               -fbar <= f_i <= fbar                       (minimax, scalar actuators)
               n_k . f_j <= R_j cos(pi/N),  k = 1..N      (|f_j| <= R_j, inscribed N-gon, rotatable j)
               n_k . f_j <= fbar cos(pi/N)                (minimax, rotatable j)
               f_j inside the cone of this sample's angles (two half-planes and the mid-ray row)

The polygon is inscribed in the circle |f| = R, so |f| <= R always holds and the worst-case
loss of magnitude is 1 - cos(pi/N) (7.6 % for the survey's octagon, 1.9 % for N = 16).

The matrices are built once per configuration with every entry that can ever be non-zero
stored explicitly (T_e dense, both components of every half-plane), so that each sample
only calls ``update(l=, u=)`` and, when rotatable thrusters turn, ``update(Ax=, Ax_idx=)``;
OSQP keeps its previous primal and dual iterates and starts the next sample from them
(warm start). A configuration change of values only (positions, directions, weights,
limits) updates ``Ax``/``Px``/``q`` on the same pattern; only a change of the pattern itself
(number or type of actuators, DOFs, polygon sides, saturation mode) sets the problem up again.

The problem is normalised once per configuration (:class:`~allocator_pkg.solvers.problem.ScaledProblem`):
forces by their actuator's range, slacks by their DOF's authority, rows by their largest
coefficient, the cost by its largest curvature, so that the Q >> W weighting of (1.35) does
not cost OSQP thousands of iterations when a request saturates.

``saturation: preserve_direction`` adds a second problem on the same pattern idea, with a
scale lambda in place of the slack: maximise lambda subject to T_e f_e = lambda tau and the
same limits (Durham's direct idea, section 4.3), minus a small multiple of the effort
f_e' W f_e, so that among the forces reaching the largest lambda it takes the cheapest. It is
solved only when the first problem reports the request unattainable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..model import MethodOutput, Model, SampleLimits
from ..solvers import BackendFactory
from ..solvers.problem import Rows, ScaledProblem, entry_index
from ..vehicle import Vehicle
from .base import AllocationMethod

INFINITY = math.inf
HALF_PLANE = math.pi - 1e-9
"""A cone this wide is the half-plane of its mid row alone; its edge rows are switched off."""
PINNED = 1e-12
"""[rad] A cone narrower than this is a single direction."""
NARROWEST = 1e-3
"""Smallest wedge factor e: a cone of zero width (a stuck thruster) keeps v bounded and costed."""
SATURATION_SLACK = 1e-6
"""Slack, as a fraction of its DOF's authority, above which a request counts as unattainable."""


@dataclass
class _Problem:
    """One OSQP problem and the rows a sample writes."""

    qp: ScaledProblem
    equality: np.ndarray
    box: np.ndarray
    polygon: np.ndarray
    cone_a: np.ndarray
    cone_b: np.ndarray
    mid: np.ndarray
    pair_index: list[np.ndarray]
    pair_base: list[np.ndarray]
    pair_rows: list[np.ndarray]
    p_diagonal: np.ndarray
    scale_index: np.ndarray
    transform: np.ndarray
    pair_values: np.ndarray | None = None
    narrowing: np.ndarray | None = None


class QPAllocation(AllocationMethod):
    """Allocation method ``qp``."""

    name = "qp"

    def __init__(self, model: Model, backend: BackendFactory):
        super().__init__(model, backend)
        self._main = self._setup(model, scale=False)
        self._scale = self._setup(model, scale=True) if model.vehicle.saturation == "preserve_direction" else None

    @classmethod
    def thrust_region_sides(cls, vehicle: Vehicle) -> int | None:
        return vehicle.azimuth_polygon_sides

    def update_model(self, model: Model) -> None:
        """Take a configuration with the same structure: values only, no new set-up."""
        self.model = model
        for problem, scale in ((self._main, False), (self._scale, True)):
            if problem is None:
                continue
            a, index = self._constraints(model, scale)
            p, q = self._objective(model, scale)
            self._constant_bounds(problem.qp, model, index, scale)
            problem.qp.update_matrix(a.data)
            problem.qp.update_objective(p, q)
            problem.qp.update_settings(model.vehicle.solver)
            problem.pair_base = [np.column_stack((a[rows, c1].toarray().ravel(), a[rows, c2].toarray().ravel()))
                                 for rows, (c1, c2) in zip(problem.pair_rows, model.rot_columns)]
            problem.p_diagonal = p
            problem.pair_values = problem.narrowing = None

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        output, x = self._solve(self._main, tau, limits)
        if self._scale is None or not output.solved:
            return output
        slack = x[self.model.m:self.model.m + self.model.n]
        if np.all(np.abs(slack) <= SATURATION_SLACK * self.model.authority):
            return output
        scaled, _ = self._solve(self._scale, tau, limits)
        scaled.iterations += output.iterations
        return scaled if scaled.solved else output

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
    def _constraints(model: Model, scale: bool) -> tuple[sp.csc_matrix, dict]:
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
        polygon, polygon_minimax, cone_a, cone_b, mid = [], [], [], [], []
        for c1, c2 in model.rot_columns:
            c1, c2 = int(c1), int(c2)
            polygon.append([rows.add([(c1, x), (c2, y)]) for x, y in normals])
            if not scale:
                polygon_minimax.append([
                    rows.add([(c1, x), (c2, y), (top, -math.cos(math.pi / sides))]) for x, y in normals
                ])
            cone_a.append(rows.add([(c1, 0.0), (c2, 1.0)]))
            cone_b.append(rows.add([(c1, 0.0), (c2, 1.0)]))
            mid.append(rows.add([(c1, 1.0), (c2, 0.0)]))
        last = rows.add([(extra, 1.0)] if scale else [(top, 1.0)])
        index = dict(equality=np.array(equality, int), box=np.array(box, int), minimax=np.array(minimax, int),
                     polygon=np.array(polygon, int).reshape(len(model.rot), sides),
                     polygon_minimax=np.array(polygon_minimax, int), cone_a=np.array(cone_a, int),
                     cone_b=np.array(cone_b, int), mid=np.array(mid, int), last=last)
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
        qp.low[index["minimax"][0::2]], qp.up[index["minimax"][0::2]] = -INFINITY, (0.0 if minimax else INFINITY)
        qp.low[index["minimax"][1::2]], qp.up[index["minimax"][1::2]] = (0.0 if minimax else -INFINITY), INFINITY
        qp.up[index["polygon_minimax"].ravel()] = 0.0 if minimax else INFINITY
        qp.low[index["last"]], qp.up[index["last"]] = 0.0, (float(np.max(model.force_scale)) if minimax else 0.0)

    def _setup(self, model: Model, scale: bool) -> _Problem:
        a, index = self._constraints(model, scale)
        p, q = self._objective(model, scale)
        extra = self._columns(model, scale)[0]
        qp = ScaledProblem(p, q, a, self._column_scale(model, scale), model.vehicle.solver,
                           effort=np.arange(0 if not scale else model.m, model.m if not scale else model.m + 1),
                           backend=self.backend())
        self._constant_bounds(qp, model, index, scale)
        pair_rows = [np.sort(a.indices[a.indptr[int(c1)]:a.indptr[int(c1) + 1]]) for c1, _ in model.rot_columns]
        pair_index = [np.array([entry_index(a, int(row), int(col)) for col in cols for row in rows], dtype=np.int64)
                      for rows, cols in zip(pair_rows, model.rot_columns)]
        pair_base = [np.column_stack((a[rows, c1].toarray().ravel(), a[rows, c2].toarray().ravel()))
                     for rows, (c1, c2) in zip(pair_rows, model.rot_columns)]
        scale_index = np.array([entry_index(a, row, extra) for row in index["equality"]] if scale else [],
                               dtype=np.int64)
        self.setups += 1
        return _Problem(qp=qp, equality=index["equality"], box=index["box"], polygon=index["polygon"],
                        cone_a=index["cone_a"], cone_b=index["cone_b"], mid=index["mid"], pair_index=pair_index,
                        pair_base=pair_base, pair_rows=pair_rows, p_diagonal=p, scale_index=scale_index,
                        transform=np.tile(np.eye(2), (len(model.rot), 1, 1)))

    # -- per sample ---------------------------------------------------------------------

    def _solve(self, problem: _Problem, tau: np.ndarray, limits: SampleLimits) -> tuple[MethodOutput, np.ndarray]:
        model = self.model
        qp = problem.qp
        if problem.scale_index.size:
            qp.update_matrix(-tau, problem.scale_index)
        else:
            qp.low[problem.equality] = qp.up[problem.equality] = tau
        qp.low[problem.box] = limits.low[model.scalar]
        qp.up[problem.box] = limits.high[model.scalar]
        if model.rot.size:
            self._azimuth_rows(problem, limits)
        solution = qp.solve(qp.low, qp.up)
        force = solution.x[:model.m].copy()
        for transform, (c1, c2) in zip(problem.transform, model.rot_columns):
            force[[c1, c2]] = transform @ solution.x[[c1, c2]]
        output = MethodOutput(force=force if solution.usable else np.zeros(model.m),
                              status=solution.status, iterations=solution.iterations, solved=solution.usable)
        return output, solution.x

    def _azimuth_rows(self, problem: _Problem, limits: SampleLimits) -> None:
        """Bounds of the rotatable thrusters' rows, and their wedge coordinates.

        Each rotatable thruster's force is written f = R(c) diag(1, e) (u, v), with c the
        middle of this sample's cone of directions and e = tan(half width) (at most 1): the
        cone, often a sliver a few degrees wide because of the rate limit, becomes the right
        angle |v| <= u, which OSQP converges on quickly (a thin wedge costs it thousands of
        iterations). Only values change: the rows' two entries (Ax) and the curvature W e^2 of
        v (Px, when the cone's width changes).
        """
        model = self.model
        sides = model.vehicle.azimuth_polygon_sides
        inscribed = math.cos(math.pi / sides)
        values = []
        narrowing = np.empty(len(limits.azimuth))
        for k, lim in enumerate(limits.azimuth):
            pinned = lim.line or lim.high - lim.low < PINNED or lim.magnitude_max == 0.0
            if pinned:
                a = b = lim.low if lim.high - lim.low < PINNED else float(limits.angle[model.rot[k]])
            else:
                flip = math.pi if lim.sigma < 0 else 0.0
                a, b = lim.low + flip, lim.high + flip
            half_width = 0.5 * (b - a)
            centre = a + half_width
            narrowing[k] = max(math.tan(half_width), NARROWEST) if half_width < 0.25 * math.pi else 1.0
            cos, sin = math.cos(centre), math.sin(centre)
            transform = np.array([[cos, -narrowing[k] * sin], [sin, narrowing[k] * cos]])
            problem.transform[k] = transform
            base = problem.pair_base[k]
            rows = problem.pair_rows[k]
            mechanical = a if pinned else 0.5 * (lim.low + lim.high)
            base[rows == problem.cone_a[k]] = (-math.sin(a), math.cos(a))
            base[rows == problem.cone_b[k]] = (-math.sin(b), math.cos(b))
            base[rows == problem.mid[k]] = (math.cos(mechanical), math.sin(mechanical))
            local = base @ transform
            edges = (rows == problem.cone_a[k]) | (rows == problem.cone_b[k])
            local[edges] /= np.linalg.norm(local[edges], axis=1, keepdims=True)   # rows with zero bounds
            values.append(local.T.ravel())
            self._azimuth_bounds(problem, k, lim, pinned, inscribed)
        values = np.concatenate(values)
        if problem.pair_values is None or not np.array_equal(values, problem.pair_values):
            problem.qp.update_matrix(values, np.concatenate(problem.pair_index))
            problem.pair_values = values
        if problem.narrowing is None or not np.array_equal(narrowing, problem.narrowing):
            p = problem.p_diagonal.copy()
            p[model.rot_columns[:, 1]] *= narrowing ** 2
            problem.qp.update_objective(p)
            problem.narrowing = narrowing


    @staticmethod
    def _azimuth_bounds(problem: _Problem, k: int, lim, pinned: bool, inscribed: float) -> None:
        """Row bounds of one rotatable thruster; no row that another already implies is left
        active (such degenerate corners slow OSQP down by orders of magnitude)."""
        low, up = problem.qp.low, problem.qp.up
        polygon, cone_a, cone_b, mid = problem.polygon[k], problem.cone_a[k], problem.cone_b[k], problem.mid[k]
        if pinned:
            # One direction: the force is F along it with F in [thrust_low, thrust_high].
            low[cone_a], up[cone_a] = 0.0, 0.0
            low[cone_b], up[cone_b] = -INFINITY, INFINITY
            low[mid], up[mid] = lim.thrust_low, lim.thrust_high
            up[polygon] = INFINITY
            return
        half_plane = lim.high - lim.low >= HALF_PLANE
        low[cone_a], up[cone_a] = (-INFINITY if half_plane else 0.0), INFINITY
        low[cone_b], up[cone_b] = -INFINITY, (INFINITY if half_plane else 0.0)
        up[polygon] = _polygon_bound(lim, inscribed)
        if lim.sigma > 0:
            low[mid], up[mid] = (lim.thrust_low if lim.thrust_low > 0.0 or half_plane else -INFINITY), INFINITY
        else:
            low[mid], up[mid] = -INFINITY, (lim.thrust_high if lim.thrust_high < 0.0 or half_plane else INFINITY)


def _polygon_bound(lim, inscribed: float) -> float:
    """Right-hand side of the N-gon rows, n_k . f <= bound.

    The actuator's own limit is inscribed (bound = f_max cos(pi/N): |f| <= f_max holds
    exactly, at a worst-case loss of 1 - cos(pi/N)). A rate limit below it is circumscribed
    (bound = F0 + rate dt): inscribing it would lose 1 - cos(pi/N) every sample and cap a
    rate-limited thrust at about rate dt / (1 - cos(pi/N)). The final thrust is clipped to
    the exact rate limit anyway. The bound never cuts off the smallest thrust the sample
    demands (a rate limit from below, a ramp, a stuck thruster)."""
    if lim.line:
        return max(abs(lim.thrust_low), abs(lim.thrust_high))
    smallest, largest = (lim.thrust_low, lim.thrust_high) if lim.sigma > 0 else (-lim.thrust_high, -lim.thrust_low)
    return max(min(lim.physical_max * inscribed, largest), smallest)
