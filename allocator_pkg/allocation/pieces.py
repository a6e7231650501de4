"""A rotatable thruster's attainable forces as a finite union of convex pieces (survey section
4.2), and the choice among them: which side of a forbidden sector each thruster should be on.

The forces a rotatable thruster can give are a disk (|f| <= R) less the forbidden sectors and
outside the feasible sector: not convex once a sector cuts it. :func:`convex_pieces` splits
them into convex pieces: the whole disk when nothing cuts it, else cones at most pi wide
(with the reverse side's cones for a reversible thruster, and a line for a stuck one).

Every convex problem of the allocation is then convex on each combination of pieces, and
its global optimum is the best of those. The per-sample methods only move each thruster a
rate step from where it is, so they find the optimum of the combination they are in; the
:class:`PiecePlanner` compares all combinations and says where each thruster should go,
which `azimuth.plan` turns into a crossing of the forbidden sector when needed. It only has
work to do where a forbidden sector or the feasible sector's end is in reach: a minimum with
every thruster clear of those edges is a minimum of the convex problem without them, hence
global (a convex function over a disk less a convex wedge has no other local minima).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..effectiveness.model import Model
from ..effectiveness.sectors import allowed_arcs, in_forbidden_sector
from ..effectiveness.zones import potential_rotations
from ..solvers import BACKENDS, BackendFactory
from ..solvers.problem import Rows, ScaledProblem, block_index, entry_index
from ..vehicle.config import RotationConfig


@dataclass(frozen=True)
class Piece:
    """Forces of directions [start, end] (absolute, end - start <= pi, or the whole circle
    when both are infinite) and magnitude up to ``radius``. A ``line`` is a stuck thruster's
    direction ``start``, with the signed thrust its range allows (``radius`` 0: none)."""

    start: float
    end: float
    radius: float
    line: bool = False

    @property
    def whole(self) -> bool:
        return math.isinf(self.start)

    def contains(self, angle: float) -> bool:
        """Whether a force along ``angle`` lies in this piece's cone."""
        if self.whole:
            return True
        offset = (angle - self.start) % (2.0 * math.pi)
        return offset <= self.end - self.start + 1e-9


def convex_pieces(rotation: RotationConfig, low: float, high: float, stuck: float | None = None,
                  whole: bool = True) -> list[Piece]:
    """The convex pieces (survey 4.2) of the forces a rotatable thruster can give with signed
    thrust in [low, high] (faults applied): forward arcs with radius ``high``, and for negative
    ``low`` the opposite arcs with radius ``-low``, each cut into cones at most pi wide; a stuck
    thruster is a line, its signed thrust in [low, high] (radius 0 stuck in a forbidden sector).
    A thruster that turns all round without a forbidden sector is the whole disk of radius
    max(high, -low), or with ``whole`` False its forward and reverse cones (where a caller
    needs to tell thrust ahead from thrust astern, as the power at part thrust does)."""
    if stuck is not None:
        radius = 0.0 if in_forbidden_sector(rotation, stuck) else max(high, -low)
        return [Piece(stuck, stuck, radius, line=True)]
    if whole and rotation.continuous and not rotation.forbidden_sectors:
        return [Piece(-math.inf, math.inf, max(high, -low))]
    arcs = allowed_arcs(rotation)
    pieces = [(start, end, high) for start, end in arcs]
    if low < 0.0:
        pieces += [(start + math.pi, end + math.pi, -low) for start, end in arcs]
    split = []
    for start, end, radius in pieces:
        while end - start > math.pi:
            split.append(Piece(start, start + math.pi, radius))
            start += math.pi
        split.append(Piece(start, end, radius))
    return split


PLAN_MARGIN = 0.02
"""Another piece is chosen only if it lowers the problem's cost by this fraction (crossing a
sector costs a transient: thrust ramped to zero and a turn)."""

REPLAN_CHANGE = 1e-2
"""The plan stands until the request moves by this fraction of a DOF's authority, or the
faults, speed or configuration change."""

MAX_COMBINATIONS = 64
"""Beyond this many combinations of pieces, only one thruster's pieces vary at a time."""

INSIDE = 0.1
"""[rad] A target direction at a piece's edge is moved this far into the piece (at most half
its width): an optimum against a forbidden sector's far edge must read as beyond the sector,
or the thruster would stay parked at its near edge. The method then finds the edge itself."""

PLANNER_BACKEND = "daqp"
"""The planner's solver: exact and dense. A planner run is a handful of cold solves of the
Q >> W problem, where an active set needs a few iterations and ADMM (OSQP) thousands, and
at its default iteration limit leaves some combinations unsolved."""

PLAN_SIDES = 32
"""Sides of the planner's thrust polygons, circumscribed: they overestimate a thruster's force
by at most 1/cos(pi/N) - 1 (0.5 %), which only a near tie between pieces could notice."""


class PiecePlanner:
    """The best combination of pieces for the static problem (1.35) without rate limits:
    minimise f'Wf + s'Qs subject to T_e f - s = tau, every thruster's static force range,
    and each rotatable thruster's force in its piece (a circumscribed N-gon and the cone's two
    half-planes, or a line), one small problem set up once and changed by values for each
    combination."""

    needed: bool
    """Whether any rotatable thruster's forces are not one convex piece (set with the model)."""

    def __init__(self, model: Model, backend: BackendFactory | None = None):
        self._backend = backend or BACKENDS[PLANNER_BACKEND]
        self.setups = 0
        self.last_targets: dict[int, tuple[float, float]] = {}
        self._problem = None
        self.update_model(model)

    def update_model(self, model: Model) -> None:
        old = getattr(self, "model", None)
        self.model = model
        self.needed = any(not (rotation.continuous and not rotation.forbidden_sectors)
                          for rotation in potential_rotations(model.vehicle) if rotation is not None)
        self._rotations = [a.rotation for a in model.vehicle.actuators]
        self._key = None
        self.last_targets = {}
        self._replan = REPLAN_CHANGE * model.dof_scale
        self._slack_weights = model.slack_weights(model.weight)
        if not self.needed:
            self._problem = None
        elif self._problem is None or old.structure != model.structure:
            self._setup(model)
        else:
            values = self._problem.a.data.copy()         # T_e's values follow; the rest is structure
            values[self._t_ec_index] = model.t_ec.ravel()
            self._problem.update_matrix(values)
            self._problem.update_objective(self._p(model))

    def use_rotations(self, rotations: Sequence[RotationConfig | None]) -> None:
        """Plan with these rotations (every actuator's; None for those that do not rotate): the
        sectors in force as flushing zones lift and return. Values only."""
        self._rotations = list(rotations)
        self._key = None

    @staticmethod
    def _p(model: Model) -> np.ndarray:
        return np.concatenate((2.0 * model.weight_ext, 2.0 * model.slack_weights(model.weight)))

    @staticmethod
    def _constraints(model: Model):
        """Rows: the equality, a box per non-rotating actuator, and per rotatable thruster the
        polygon, the cone's two half-planes and the component along a line."""
        rows = Rows()
        for k in range(model.n):
            rows.add([(c, float(model.t_ec[k, c])) for c in range(model.m)] + [(model.m + k, -1.0)])
        for c in model.scalar_columns:
            rows.add([(int(c), 1.0)])
        normals = [(math.cos(2.0 * math.pi * k / PLAN_SIDES), math.sin(2.0 * math.pi * k / PLAN_SIDES))
                   for k in range(PLAN_SIDES)]
        for c1, c2 in model.rot_columns:
            c1, c2 = int(c1), int(c2)
            for x, y in normals:
                rows.add([(c1, x), (c2, y)])
            for _ in range(3):
                rows.add([(c1, 1.0), (c2, 1.0)])
        return rows.matrix(model.m + model.n)

    def _setup(self, model: Model) -> None:
        a = self._constraints(model)
        n, scalars, p = model.n, model.scalar.size, model.rot.size
        first = n + scalars
        per = PLAN_SIDES + 3
        self._polygon = np.array([[first + k * per + j for j in range(PLAN_SIDES)] for k in range(p)], int)
        self._piece_rows = np.array([[first + k * per + PLAN_SIDES + j for j in range(3)] for k in range(p)], int)
        self._piece_index = np.array([[entry_index(a, int(row), int(col)) for row in rows for col in pair]
                                      for rows, pair in zip(self._piece_rows, model.rot_columns)], np.int64)
        column_scale = np.concatenate((model.force_scale[model.extended_owner], np.maximum(model.authority, 1e-9)))
        self._t_ec_index = block_index(a, np.arange(n), model.m)
        self._problem = ScaledProblem(self._p(model), np.zeros(model.m + n), a, column_scale, model.vehicle.solver,
                                      effort=np.arange(model.m), backend=self._backend())
        self.setups += 1

    def targets(self, tau: np.ndarray, low: np.ndarray, high: np.ndarray, stuck: dict[int, float],
                angles: np.ndarray) -> dict[int, tuple[float, float]]:
        """The force each rotatable thruster (by actuator index) should give, from the best
        combination of pieces; kept while the request, faults and speed stay."""
        key = (low.tobytes(), high.tobytes(), tuple(sorted(stuck.items())))
        if self._key == key and np.all(np.abs(tau - self._tau) <= self._replan):
            return self.last_targets
        model = self.model
        rotations = self._rotations
        choices = [convex_pieces(rotations[i], low[i], high[i], stuck.get(int(i))) for i in model.rot]
        here = [[k for k, piece in enumerate(pieces) if _reachable(piece, rotations[i], float(angles[i]))]
                for i, pieces in zip(model.rot, choices)]
        problem = self._problem
        problem.low[:model.n] = problem.up[:model.n] = tau
        problem.low[model.n:model.n + model.scalar.size] = low[model.scalar]
        problem.up[model.n:model.n + model.scalar.size] = high[model.scalar]
        best, best_cost, stay, stay_cost = None, math.inf, None, math.inf
        best_pieces = stay_pieces = None
        for combination in _combinations(choices, here):
            pieces = [choices[j][k] for j, k in enumerate(combination)]
            force, cost = self._solve(tau, low, high, pieces)
            if cost < best_cost:
                best, best_cost, best_pieces = force, cost, pieces
            if all(k in options for k, options in zip(combination, here)) and cost < stay_cost:
                stay, stay_cost, stay_pieces = force, cost, pieces
        chosen = best if stay is None or best_cost < (1.0 - PLAN_MARGIN) * stay_cost else stay
        combination = best_pieces if chosen is best else stay_pieces
        self.last_targets = {} if chosen is None else {
            int(i): _inside(piece, (float(chosen[c1]), float(chosen[c2])))
            for i, (c1, c2), piece in zip(model.rot, model.rot_columns, combination)}
        self._key, self._tau = key, tau.copy()
        return self.last_targets

    def _solve(self, tau: np.ndarray, low: np.ndarray, high: np.ndarray,
               pieces: list[Piece]) -> tuple[np.ndarray | None, float]:
        """Extended forces and cost f'Wf + s'Qs of the static problem on one combination."""
        model = self.model
        problem = self._problem
        values = np.zeros((len(pieces), 6))
        for k, (i, piece) in enumerate(zip(model.rot, pieces)):
            rows = self._piece_rows[k]
            problem.up[self._polygon[k]] = piece.radius / math.cos(math.pi / PLAN_SIDES)
            problem.low[rows], problem.up[rows] = -math.inf, math.inf
            if piece.line:
                cos, sin = math.cos(piece.start), math.sin(piece.start)
                values[k] = (-sin, cos, 0.0, 0.0, cos, sin)
                problem.low[rows[0]] = problem.up[rows[0]] = 0.0            # nothing across the line
                usable = piece.radius > 0.0
                problem.low[rows[2]] = low[i] if usable else 0.0           # signed thrust along it
                problem.up[rows[2]] = high[i] if usable else 0.0
            elif not piece.whole:
                values[k] = (-math.sin(piece.start), math.cos(piece.start), -math.sin(piece.end), math.cos(piece.end),
                             0.0, 0.0)
                problem.low[rows[0]], problem.up[rows[1]] = 0.0, 0.0        # inside the cone [start, end]
        problem.update_matrix(values.reshape(-1), self._piece_index.reshape(-1))
        solution = problem.solve(problem.low, problem.up)
        if not solution.usable:
            return None, math.inf
        force = solution.x[:model.m]
        slack = model.t_ec @ force - tau
        cost = float(model.weight_ext @ (force * force) + self._slack_weights @ (slack * slack))
        return force, cost


def _inside(piece: Piece, force: tuple[float, float]) -> tuple[float, float]:
    """The force turned, if it lies within INSIDE of its piece's edge, that far into the piece."""
    if piece.whole or piece.line:
        return force
    margin = min(INSIDE, 0.5 * (piece.end - piece.start))
    direction = math.atan2(force[1], force[0])
    offset = (direction - piece.start) % (2.0 * math.pi)
    if offset > piece.end - piece.start + margin:            # just before the start (wrapped round)
        offset -= 2.0 * math.pi
    turned = piece.start + min(max(offset, margin), piece.end - piece.start - margin)
    magnitude = math.hypot(force[0], force[1])
    return (magnitude * math.cos(turned), magnitude * math.sin(turned))


def _reachable(piece: Piece, rotation: RotationConfig, angle: float) -> bool:
    """Whether a thruster at ``angle`` reaches the piece without crossing a forbidden sector:
    the piece lies in the allowed arc the angle is in (either side, for a reversible one)."""
    if piece.whole or piece.line:
        return True
    for start, end in allowed_arcs(rotation):
        for shift in (0.0, math.pi):
            arc = Piece(start + shift, end + shift, 0.0)
            within = arc.contains(angle + shift) if shift else arc.contains(angle)
            if within and arc.contains(piece.start) and arc.contains(piece.end):
                return True
    return False


def _combinations(choices: list[list[Piece]], here: list[list[int]]):
    """Every combination of pieces, or, beyond MAX_COMBINATIONS, the combinations that change
    one thruster's piece from one where it is."""
    if math.prod(len(pieces) for pieces in choices) <= MAX_COMBINATIONS:
        yield from itertools.product(*(range(len(pieces)) for pieces in choices))
        return
    base = [options[0] if options else 0 for options in here]
    yield tuple(base)
    for j, pieces in enumerate(choices):
        for k in range(len(pieces)):
            if k != base[j]:
                yield (*base[:j], k, *base[j + 1:])
