"""One sample's allocation limits as a linear programme (section 5.3) on HiGHS
(:class:`~allocator_pkg.solvers.linear_program.LinearProgram`), kept between samples so that
each solve starts from the last basis (the survey's iterative LP).

Variables, in units of each actuator's force range F (and of each DOF's authority D for the
slack): one signed force per non-rotating actuator, split f = p - m with p, m >= 0, so that
its magnitude p + m is linear; the two extended components (f_x, f_y) of every rotatable
thruster (1.16), free, with a_x >= |f_x| and a_y >= |f_y| their magnitudes in the x/y plane;
and either the slack s = s+ - s- of each controlled DOF (``objective="effort"``) or one scale
lambda of the request (``objective="scale"``).

    effort:  minimise  sum_i g_i w_i F_i (p_i + m_i) + sum_j g_j w_j F_j (a_xj + a_yj) + sum_k q_k D_k (s+_k + s-_k)
             subject to  T_e f_e - s = tau
    scale:   maximise   lambda - eps * (the same effort)
             subject to  T_e f_e = lambda tau,  0 <= lambda <= lambda_max

with g the tie-break of :func:`tie_break` (1 for ``scale``), and, for both, this sample's limits:

- a non-rotating actuator: low_i <= f_i <= high_i (bounds on p and m);
- a rotatable thruster: the thrust circle |f| <= B as a polygon of N faces fixed in the body
  frame, face normals at 2 pi k / N, each at distance ``apothem`` * B (the survey's polygon,
  or the inscribed one); the angles this sample allows (feasible sector, the piece free of
  forbidden sectors, the rate step) as the cone between two half-planes through the origin;
  a thrust that a rate limit keeps above zero as f . d >= F_low along the thruster's present
  direction d; a single allowed direction (STUCK, or a window narrower than PINNED) as the
  line through the origin along it.

Ties: where several force vectors reach the same optimum (two thrusters of equal weight
along one line, the four vertical thrusters of a BlueROV2 Heavy with one failed), a plain
simplex returns whichever vertex its starting basis leads to, so that the answer to a request
would depend on the samples before it. The effort's tie-break g makes the optimum unique
(:func:`tie_break`); HiGHS's dual feasibility tolerance is set to DUAL_TOLERANCE so that it
sees the tie-break.

Only values change between samples: the bounds, and the coefficients of the cone's edges and
of the along-row of each rotatable thruster (sent when they differ from the last sample's).
A vehicle with power sources has the power rows after every other row and column
(:mod:`~.power_block`, docs/power.md), their values written when the available power, the
feeds or the coefficients change.
"""

from __future__ import annotations

import math

import numpy as np

from ..effectiveness.model import AzimuthLimits, Model, SampleLimits
from ..effectiveness.power_rows import PowerPattern, PowerRows
from ..solvers.backend import NO_BOUND
from ..solvers.linear_program import LinearProgram
from ..solvers.outcome import Solution
from ..solvers.problem import Rows
from .power_block import PowerBlock, add_power_rows, write_programme

PINNED = 1e-12
"""[rad] A window of angles narrower than this is a single direction."""
SLACK_RATIO = 1e4
"""Default weight of a DOF's |slack| against the effort (see :meth:`SampleLP._slack_weights`)."""
TIE_BREAK = 1e-6
"""The effort's weight in the scale objective, against lambda, per unit of effort of all
actuators at full force: among the forces reaching the largest lambda it takes the cheapest
and costs lambda at most this fraction."""

ORDER_SHARE = 1e-6
"""Relative size of the effort's tie-break (:func:`tie_break`)."""
DUAL_TOLERANCE = 1e-10
"""HiGHS's dual feasibility tolerance for the effort objective (its default is 1e-7, its
smallest 1e-10): the tie-break changes the reduced cost of a tied direction by about
ORDER_SHARE x its cost x 1 / r^2, well above this."""


def tie_break(count: int) -> np.ndarray:
    """The weights g_k = 1 + ORDER_SHARE (k / r)^2, k = 1 ... r in configuration order, that
    multiply each actuator's effort in the objective: among force vectors of equal effort the
    one that loads the actuators early in the configuration more (a tied direction moves
    effort between actuators; its cost now changes by ORDER_SHARE x the difference of their
    squared indices, nonzero for mirrored layouts, where linear weights would cancel).

    Size: the tie-break changes the objective of any force vector by at most ORDER_SHARE of
    its effort, so it picks another vertex only among those whose effort lies within a
    millionth of the optimum's: within what HiGHS, at its default dual tolerance of 1e-7 per
    unit of a force range over up to r force ranges, already accepted as optimal. A
    non-tied optimum further from every other vertex than that stays the same vertex."""
    return 1.0 + ORDER_SHARE * ((np.arange(count) + 1.0) / count) ** 2


def survey_apothem(sides: int) -> float:
    """Face distance, as a fraction of the radius, of the polygon between the inscribed and the
    circumscribed ones: its magnitude error is +-tan^2(pi / 2N) (3.96 % for the octagon, the
    survey's +-4 %), below the circle at the faces' middles and above it at the corners."""
    c = math.cos(math.pi / sides)
    return 2.0 * c / (1.0 + c)


def polygon_error(sides: int, apothem: float) -> tuple[float, float]:
    """(smallest, largest) extent of the polygon over all directions, as a fraction of the
    radius, minus one: the worst-case magnitude errors of the thrust circle's polygon."""
    return apothem - 1.0, apothem / math.cos(math.pi / sides) - 1.0


class SampleLP:
    """One HiGHS LP per configuration: the sample's limits as rows and bounds (see module)."""

    def __init__(self, model: Model, sides: int, apothem: float, objective: str, scale_max: float = 1.0):
        if objective not in ("effort", "scale"):
            raise ValueError(f"objective is effort or scale, got {objective!r}")
        self.sides, self.apothem, self.objective, self.scale_max = sides, apothem, objective, scale_max
        self._lp = LinearProgram(DUAL_TOLERANCE if objective == "effort" else None)
        self._power: PowerRows | None = None
        self._build(model)

    # -- set-up ---------------------------------------------------------------------------

    def _build(self, model: Model, keep_basis: bool = False) -> None:
        """Columns, rows and the constant coefficients; bounds are filled per sample."""
        self.model = model
        force = np.maximum(model.force_scale, 1e-9)
        self._force = force
        self._dof = model.dof_scale
        columns: list[float] = []                       # cost per column, physical units x scale
        scalar_p, scalar_m = {}, {}
        order = tie_break(len(model.vehicle.actuators)) if self.objective == "effort" else \
            np.ones(len(model.vehicle.actuators))
        for i in model.scalar:
            scalar_p[int(i)] = len(columns)
            columns.append(model.weight[i] * force[i] * order[i])
            scalar_m[int(i)] = len(columns)
            columns.append(model.weight[i] * force[i] * order[i])
        rotatable = []                                  # (f_x, f_y, a_x, a_y) per rotatable thruster
        for j in model.rot:
            first = len(columns)
            columns += [0.0, 0.0, model.weight[j] * force[j] * order[j], model.weight[j] * force[j] * order[j]]
            rotatable.append((first, first + 1, first + 2, first + 3))
        effort = float(sum(columns)) or 1.0
        if self.objective == "effort":
            slack_weight = self._slack_weights(model, effort)
            self._slack = len(columns)
            columns += [w for w in slack_weight for _ in range(2)]
            costs = np.array(columns) / effort
        else:
            self._lambda = len(columns)
            costs = np.append(np.array(columns) * (TIE_BREAK / effort), -1.0)
        self._scalar_p = np.array([scalar_p[int(i)] for i in model.scalar], dtype=np.int32)
        self._scalar_m = np.array([scalar_m[int(i)] for i in model.scalar], dtype=np.int32)
        self._rot_columns = rotatable
        rows = Rows()
        self._equality = self._equality_rows(rows, model, force, scalar_p, scalar_m, rotatable)
        # Rotatable thrusters: magnitudes, polygon, along-row, the cone's two edges.
        normals = [(math.cos(2.0 * math.pi * k / self.sides), math.sin(2.0 * math.pi * k / self.sides))
                   for k in range(self.sides)]
        self._polygon, self._along, self._edges = [], [], []
        magnitude_rows = []
        for fx, fy, ax, ay in rotatable:
            magnitude_rows += [rows.add([(ax, 1.0), (fx, -1.0)]), rows.add([(ax, 1.0), (fx, 1.0)]),
                               rows.add([(ay, 1.0), (fy, -1.0)]), rows.add([(ay, 1.0), (fy, 1.0)])]
            self._polygon.append([rows.add([(fx, x), (fy, y)]) for x, y in normals])
            self._along.append(rows.add([(fx, 1.0), (fy, 0.0)]))
            self._edges.append((rows.add([(fx, 0.0), (fy, 1.0)]), rows.add([(fx, 0.0), (fy, 1.0)])))
        self._block = self._power_rows(rows, model, len(costs), force, scalar_p, scalar_m, rotatable)
        if self._block is not None:
            costs = np.concatenate((costs, np.zeros(self._block.columns)))
        lower = np.zeros(len(costs))
        upper = np.full(len(costs), NO_BOUND)
        if self._block is not None:
            lower[len(costs) - self._block.columns:] = -NO_BOUND
        for fx, fy, _, _ in rotatable:
            lower[[fx, fy]] = -NO_BOUND
        if self.objective == "scale":
            upper[self._lambda] = self.scale_max
        row_low = np.full(rows.count, -NO_BOUND)
        row_up = np.full(rows.count, NO_BOUND)
        row_low[magnitude_rows] = 0.0
        row_low[self._equality] = row_up[self._equality] = 0.0
        self._lp.setup(costs, lower, upper, rows.matrix(len(costs)), row_low, row_up, model.vehicle.solver.time_limit,
                       keep_basis)
        self._version = -1
        if self._block is not None and self._power is not None:
            write_programme(self._lp, self._block, self._power, self._unit)

    def _equality_rows(self, rows: Rows, model: Model, force: np.ndarray, scalar_p: dict, scalar_m: dict,
                       rotatable: list) -> list[int]:
        """The equality rows T f = tau (with the slack or lambda column), each divided by its
        DOF's authority; their indices."""
        t = model.t_ec / self._dof[:, None]
        owner = model.extended_owner
        equality = []
        for k in range(model.n):
            entries = []
            for c in range(model.m):
                i = int(owner[c])
                if not model.rotatable[i]:
                    entries += [(scalar_p[i], t[k, c] * force[i]), (scalar_m[i], -t[k, c] * force[i])]
            for (fx, fy, _, _), (c1, c2) in zip(rotatable, model.rot_columns):
                i = int(owner[c1])
                entries += [(fx, t[k, c1] * force[i]), (fy, t[k, c2] * force[i])]
            if self.objective == "effort":
                entries += [(self._slack + 2 * k, -1.0), (self._slack + 2 * k + 1, 1.0)]
            else:
                entries.append((self._lambda, 0.0))
            equality.append(rows.add(entries))
        return equality

    def _power_rows(self, rows: Rows, model: Model, first: int, force: np.ndarray, scalar_p: dict, scalar_m: dict,
                    rotatable: list) -> PowerBlock | None:
        """The power rows (:mod:`~.power_block`) on this programme's force columns, for a
        vehicle with power sources: t_i = (p_i - m_i) force_i / F_i, a rotatable thruster's
        (f_x, f_y) force_i / F_i; q in units of the rated power, each source row in units of
        its consumers' rated power."""
        pattern = PowerPattern.of(model.vehicle)
        if pattern is None:
            return None
        rated = np.maximum(np.abs(model.thrust_min), np.abs(model.thrust_max))
        self._unit = force / np.maximum(rated, 1e-9)
        terms: dict = {int(i): [(scalar_p[int(i)], 1.0), (scalar_m[int(i)], -1.0)] for i in model.scalar}
        for (fx, fy, _, _), j in zip(rotatable, model.rot.tolist()):
            terms[j] = ([(fx, 1.0)], [(fy, 1.0)])
        rated_power = np.maximum(np.where(model.power > 0.0, model.power, 1.0) * rated ** 1.5, 1e-9)
        return add_power_rows(rows, first, pattern, terms, rated, model.power, q_unit=rated_power,
                              row_unit=np.maximum(rated_power @ pattern.pattern, 1.0))

    def set_power(self, power: PowerRows | None) -> None:
        """The power rows' values (values only; the programme is set up again for another
        pattern)."""
        self._power = power
        if power is None or self._block is None:
            return
        if not power.pattern.same(self._block.pattern):
            self._build(self.model, keep_basis=True)
            return
        write_programme(self._lp, self._block, power, self._unit)

    @staticmethod
    def _slack_weights(model: Model, effort: float) -> list[float]:
        """The weight of one DOF's |s| in units of its authority: weights.slack when configured
        (per newton or newton-metre of error), else SLACK_RATIO times the effort of every
        actuator at full force, so that an error of 1/SLACK_RATIO of a DOF's authority costs
        as much as all of them."""
        if model.vehicle.weights.slack:
            return list(np.array(model.vehicle.weights.slack) * model.dof_scale)
        return [SLACK_RATIO * effort] * model.n

    def update_model(self, model: Model) -> None:
        """A configuration of the same structure: the model is built again with the new values
        (a few hundred coefficients; the basis of the last solve is kept as the start)."""
        self._build(model, keep_basis=True)

    # -- per sample -----------------------------------------------------------------------

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> Solution:
        """The LP of ``tau`` within ``limits``; read its answer with :meth:`force`,
        :meth:`slack` (objective ``effort``) and :meth:`scale` (objective ``scale``)."""
        model = self.model
        lp = self._lp
        request = tau / self._dof
        if self.objective == "effort":
            lp.low[self._equality] = lp.up[self._equality] = request
        else:
            for row, value in zip(self._equality, request.tolist()):
                lp.coefficient(row, self._lambda, -value)
        if limits.version < 0 or limits.version != self._version:
            force = self._force[model.scalar]
            low, high = limits.low[model.scalar] / force, limits.high[model.scalar] / force
            if model.scalar.size:
                lp.column_bounds(self._scalar_p, np.maximum(low, 0.0), np.maximum(high, 0.0))
                lp.column_bounds(self._scalar_m, np.maximum(-high, 0.0), np.maximum(-low, 0.0))
            self._version = limits.version
        for k, lim in enumerate(limits.azimuth):
            self._azimuth_rows(k, lim, float(limits.angle[model.rot[k]]))
        return lp.solve()

    def force(self, solution: Solution) -> np.ndarray:
        """The extended force vector (1.16) of a solution, in newtons (zero when it failed)."""
        model = self.model
        force = np.zeros(model.m)
        if not solution.usable:
            return force
        x, scale = solution.x, self._force
        force[model.scalar_columns] = (x[self._scalar_p] - x[self._scalar_m]) * scale[model.scalar]
        for (fx, fy, _, _), (c1, c2), j in zip(self._rot_columns, model.rot_columns, model.rot):
            force[c1], force[c2] = x[fx] * scale[j], x[fy] * scale[j]
        return force

    def slack(self, solution: Solution) -> np.ndarray:
        """The wrench error s of each controlled DOF (objective ``effort``)."""
        x, n = solution.x, self.model.n
        return (x[self._slack::2][:n] - x[self._slack + 1::2][:n]) * self._dof

    def scale(self, solution: Solution) -> float:
        """lambda, the scale of the request reached (objective ``scale``)."""
        return float(solution.x[self._lambda])

    def _azimuth_rows(self, k: int, lim: AzimuthLimits, alpha0: float) -> None:
        """Bounds and coefficients of rotatable thruster k for this sample (see the module)."""
        fx, fy, _, _ = self._rot_columns[k]
        scale = float(self._force[self.model.rot[k]])
        polygon, along = self._polygon[k], self._along[k]
        edge_low, edge_high = self._edges[k]
        low, up = self._lp.low, self._lp.up
        if lim.line or lim.high - lim.low < PINNED or lim.magnitude_max == 0.0:
            direction = lim.low if math.isfinite(lim.low) else alpha0
            up[polygon] = NO_BOUND
            self._row(along, fx, fy, math.cos(direction), math.sin(direction), lim.thrust_low / scale,
                      lim.thrust_high / scale)
            self._row(edge_low, fx, fy, -math.sin(direction), math.cos(direction), 0.0, 0.0)
            low[edge_high], up[edge_high] = -NO_BOUND, NO_BOUND
            return
        reverse = lim.sigma < 0
        direction = alpha0 + math.pi if reverse else alpha0
        smallest, largest = (lim.thrust_low, lim.thrust_high) if not reverse else (-lim.thrust_high, -lim.thrust_low)
        bound = max(min(lim.physical_max, largest), smallest)
        pitch = 2.0 * math.pi / self.sides
        offset = math.remainder(direction, pitch)
        # The polygon reaches at least the thrust a rate limit keeps, along the present direction.
        up[polygon] = max(self.apothem * bound, smallest * math.cos(offset)) / scale
        self._row(along, fx, fy, math.cos(direction), math.sin(direction),
                  smallest / scale if smallest > 0.0 else -NO_BOUND, NO_BOUND)
        shift = math.pi if reverse else 0.0
        if math.isfinite(lim.low):
            start = lim.low + shift
            self._row(edge_low, fx, fy, -math.sin(start), math.cos(start), 0.0, NO_BOUND)
        else:
            low[edge_low], up[edge_low] = -NO_BOUND, NO_BOUND
        if math.isfinite(lim.high):
            end = lim.high + shift
            self._row(edge_high, fx, fy, math.sin(end), -math.cos(end), 0.0, NO_BOUND)
        else:
            low[edge_high], up[edge_high] = -NO_BOUND, NO_BOUND

    def _row(self, row: int, fx: int, fy: int, cx: float, cy: float, low: float, up: float) -> None:
        self._lp.coefficient(row, fx, cx)
        self._lp.coefficient(row, fy, cy)
        self._lp.low[row], self._lp.up[row] = low, up
