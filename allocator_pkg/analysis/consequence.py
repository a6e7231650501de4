"""Online consequence analysis (IMO MSC/Circ.645, DP equipment class 2 and 3): for each
redundancy group of the vehicle, could the actuators left after its loss hold the present load?

The answer per group is a utilisation u: the smallest u >= 0 such that some extended force f
(1.16) gives the load in the controlled DOFs, T_e f = tau (1.17), with every actuator within
u times its force range: a thruster of fixed direction in [u low_i, u high_i], a rotatable one
inside u times its thrust region in one of its convex pieces (section 4.2; the configured
method's polygon of the thrust circle, cut by the circle where it reaches beyond it, as
:class:`~allocator_pkg.analysis.capability.Capability` has it; the circle as a polygon of
:data:`~allocator_pkg.methods.base.CIRCLE_SIDES` sides for a method without one). u <= 1: the
group's loss leaves enough; u > 1: it does not (the consequence alarm); inf: no force of the
remaining actuators gives the load's direction at all. The margin is 1 - u.

A group's loss, the rule of the DNV-ST-0111 analysis (:mod:`~allocator_pkg.analysis.dp_capability`):
its actuators fail; a thruster fed by its sources (or by sources already lost) keeps the share
s of its power that its other feeds give, and with power P ~ |f|^(3/2) (1.44) the thrust
s^(2/3) of its range; one fed only by lost sources keeps nothing. On top of the faults in force:
the force ranges of the allocator (faults, voltage, speed) and the stuck angles.

Minimise u over each combination of the rotatable thrusters' convex pieces, the smallest over
all combinations the group's. One linear programme per group
(:class:`~allocator_pkg.solvers.linear_program.LinearProgram`) is set up once per configuration;
each analysis changes only coefficients of the same pattern, column and row bounds and the
right-hand side, each solve starting from the last basis.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..allocation.pieces import Piece, convex_pieces
from ..effectiveness.faults import Fault, FaultMode
from ..effectiveness.model import Model
from ..effectiveness.sectors import in_forbidden_sector
from ..methods import METHODS
from ..methods.base import CIRCLE_SIDES
from ..solvers.linear_program import LinearProgram
from ..solvers.outcome import Outcome
from ..vehicle.angles import TWO_PI
from ..vehicle.config import RedundancyGroup, RotationConfig, Vehicle

POWER_TO_THRUST = 2.0 / 3.0
"""Thrust follows power to this power: P ~ |f|^(3/2) (1.44)."""
PLACEHOLDER = 1.0
"""The value of a coefficient at set-up that every analysis sets before solving."""


@dataclass(frozen=True)
class GroupUtilisation:
    """One group's answer: the utilisation ``u`` the remaining actuators need (inf: they cannot
    give the load at all)."""

    group: str
    utilisation: float

    @property
    def margin(self) -> float:
        """1 - u: the share of the remaining capability left over (negative: short)."""
        return 1.0 - self.utilisation

    @property
    def alarm(self) -> bool:
        """Whether the group's loss leaves too little to hold the load (u > 1)."""
        return self.utilisation > 1.0


def thrust_faces(vehicle: Vehicle, method: str) -> list[tuple[float, float, float]]:
    """(n_x, n_y, apothem) of every face of a rotatable thruster's thrust region per unit of
    its thrust limit: the method's polygon, cut by the circle where it reaches beyond it (the
    allocator clips every thrust to its limit); the circle for a method without a polygon."""
    sides = METHODS[method].thrust_region_sides(vehicle)
    circle = (CIRCLE_SIDES, math.cos(math.pi / CIRCLE_SIDES))
    polygons = [circle if sides is None else (sides, METHODS[method].thrust_region_apothem(vehicle))]
    if sides is not None and polygons[0][1] > math.cos(math.pi / sides) + 1e-12:
        polygons.append(circle)
    return [(math.cos(TWO_PI * k / count), math.sin(TWO_PI * k / count), apothem)
            for count, apothem in polygons for k in range(count)]


def remaining_share(vehicle: Vehicle, group: RedundancyGroup, lost_sources: Collection[str] = ()) -> np.ndarray:
    """The share of its power each actuator keeps after the group's loss: 0 for the group's
    actuators, the sum of the feed shares of its feeds neither the group nor ``lost_sources``
    takes for a fed thruster, 1 for an actuator without feeds."""
    lost = set(group.sources) | set(lost_sources)
    share = np.ones(len(vehicle.actuators))
    for i, actuator in enumerate(vehicle.actuators):
        if actuator.name in group.actuators:
            share[i] = 0.0
        elif actuator.feeds:
            share[i] = sum(s for feed, s in zip(actuator.feeds, actuator.feed_shares) if feed not in lost)
    return share


def force_pieces(rotation: RotationConfig, low: float, high: float, stuck: float | None) -> list[Piece]:
    """Convex pieces of the forces a rotatable thruster gives with signed thrust in [low, high]
    (:func:`~allocator_pkg.allocation.pieces.convex_pieces`); a stuck one's line as its forward
    ray (radius ``high``) and, with ``low`` < 0, its reverse ray (radius ``-low``); one piece of
    radius 0 when it gives nothing."""
    if max(high, -low) <= 0.0 or (stuck is not None and in_forbidden_sector(rotation, stuck)):
        return [Piece(0.0, 0.0, 0.0)]
    if stuck is None:
        return convex_pieces(rotation, low, high)
    rays = [Piece(stuck, stuck, high)] if high > 0.0 else []
    return rays + ([Piece(stuck + math.pi, stuck + math.pi, -low)] if low < 0.0 else [])


class Consequence:
    """The consequence analysis of one vehicle (its ``redundancy_groups``) with the thrust
    regions of ``method`` (None: the vehicle's)."""

    def __init__(self, vehicle: Vehicle, method: str | None = None):
        self.vehicle = vehicle
        self.method = method or vehicle.method
        self.model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
        faces = thrust_faces(vehicle, self.method)
        self._programmes = [_Programme(self.model, faces) for _ in vehicle.redundancy_groups]

    @property
    def groups(self) -> tuple[str, ...]:
        return tuple(group.name for group in self.vehicle.redundancy_groups)

    def utilisation(self, load: Sequence[float], low: np.ndarray, high: np.ndarray,
                    faults: Mapping[str, Fault] | None = None,
                    lost_sources: Collection[str] = ()) -> tuple[GroupUtilisation, ...]:
        """Each group's utilisation for ``load`` [X, Y, Z, K, M, N] (its controlled DOFs), with
        the force ranges [low, high] in force (``Allocator.ranges``), the ``faults`` in force
        (their stuck angles) and the power sources already lost."""
        model = self.model
        request = np.asarray(load, dtype=float)[model.dof_index] / model.dof_scale
        stuck = {i: fault.angle for i, name in enumerate(self.vehicle.names)
                 if (fault := (faults or {}).get(name)) is not None and fault.mode == FaultMode.STUCK}
        answers = []
        for group, programme in zip(self.vehicle.redundancy_groups, self._programmes):
            factor = remaining_share(self.vehicle, group, lost_sources) ** POWER_TO_THRUST
            value = programme.smallest(request, low * factor, high * factor, stuck) if np.any(request) else 0.0
            answers.append(GroupUtilisation(group.name, value))
        return tuple(answers)


class _Programme:
    """min u s.t. T_ec D x = tau (rows scaled by each DOF's authority), x_i - u a_i <= 0 and
    -x_i - u b_i <= 0 for a thruster of fixed direction (x_i = f_i / w_i, w_i = max(high_i,
    -low_i), a_i = high_i / w_i, b_i = -low_i / w_i), and for a rotatable one (x = f / R, R its
    piece's radius) the faces n . x - u apothem <= 0, the two sides of its piece's cone and
    "along the cone's middle, not against it". D holds w_i and R; a force range without zero (a
    stuck control surface) is a fixed x, and an actuator that gives nothing has x = 0."""

    def __init__(self, model: Model, faces: list[tuple[float, float, float]]):
        self.model = model
        n, m = model.n, model.m
        self.u = m
        rows: list[dict[int, float]] = [dict.fromkeys(np.flatnonzero(model.t_ec[k]), PLACEHOLDER) for k in range(n)]
        self._limit_rows = []
        for column in model.scalar_columns:
            self._limit_rows.append(len(rows))
            rows += [{column: 1.0, m: -PLACEHOLDER}, {column: -1.0, m: -PLACEHOLDER}]
        self._cone_rows = []
        for c1, c2 in model.rot_columns:
            rows += [{c1: nx, c2: ny, m: -apothem} for nx, ny, apothem in faces]
            self._cone_rows.append(len(rows))
            rows += [{c1: PLACEHOLDER, c2: PLACEHOLDER} for _ in range(3)]
        entries = [(k, c, v) for k, row in enumerate(rows) for c, v in row.items()]
        k, c, v = zip(*entries)
        a = sp.csc_matrix((v, (k, c)), shape=(len(rows), m + 1))
        low = np.full(len(rows), -np.inf)
        up = np.zeros(len(rows))
        costs = np.zeros(m + 1)
        costs[m] = 1.0
        column_low = np.r_[np.full(m, -np.inf), 0.0]
        column_up = np.full(m + 1, np.inf)
        self.lp = LinearProgram()
        self.lp.setup(costs, column_low, column_up, a, low, up, 0.0)
        self._columns = np.arange(m, dtype=np.int32)
        self._column_low, self._column_up = np.full(m, -np.inf), np.full(m, np.inf)
        self._scaled = model.t_ec / model.dof_scale[:, None]
        self._nonzero = [np.flatnonzero(model.t_ec[:, c]) for c in range(m)]

    def smallest(self, request: np.ndarray, low: np.ndarray, high: np.ndarray, stuck: Mapping[int, float]) -> float:
        """The smallest utilisation over every combination of pieces (inf: none gives the request)."""
        model, lp = self.model, self.lp
        n = model.n
        lp.low[:n] = lp.up[:n] = request
        self._fixed_direction(low, high)
        choices = [force_pieces(model.vehicle.actuators[i].rotation, low[i], high[i], stuck.get(int(i)))
                   for i in model.rot]
        best = math.inf
        for combination in itertools.product(*choices):
            for index, piece in enumerate(combination):
                self._piece(index, piece)
            lp.column_bounds(self._columns, self._column_low, self._column_up)
            solution = lp.solve()
            if solution.outcome is Outcome.SOLVED:
                best = min(best, float(solution.x[self.u]))
        return best

    def _scale(self, column: int, scale: float) -> None:
        """Column ``column`` of the equality rows as T_ec times ``scale`` (the force per unit of x)."""
        for k in self._nonzero[column]:
            self.lp.coefficient(int(k), column, float(self._scaled[k, column] * scale))

    def _fixed_direction(self, low: np.ndarray, high: np.ndarray) -> None:
        for i, column, row in zip(self.model.scalar, self.model.scalar_columns, self._limit_rows):
            scale = max(high[i], -low[i], 0.0)
            if scale <= 0.0:
                self._column_low[column] = self._column_up[column] = 0.0
                continue
            self._scale(int(column), scale)
            pinned = low[i] > 0.0 or high[i] < 0.0             # a fixed force, whatever u
            self.lp.up[row:row + 2] = np.inf if pinned else 0.0
            if pinned:
                self._column_low[column], self._column_up[column] = low[i] / scale, high[i] / scale
                continue
            self._column_low[column], self._column_up[column] = -np.inf, np.inf
            self.lp.coefficient(row, self.u, -high[i] / scale)
            self.lp.coefficient(row + 1, self.u, low[i] / scale)

    def _piece(self, index: int, piece: Piece) -> None:
        """The cone and radius of the ``index``-th rotatable thruster's piece."""
        c1, c2 = (int(c) for c in self.model.rot_columns[index])
        row = self._cone_rows[index]
        lp = self.lp
        if piece.radius <= 0.0:
            self._column_low[[c1, c2]] = self._column_up[[c1, c2]] = 0.0
            return
        self._column_low[[c1, c2]], self._column_up[[c1, c2]] = -np.inf, np.inf
        self._scale(c1, piece.radius)
        self._scale(c2, piece.radius)
        lp.up[row:row + 3] = np.inf if piece.whole else 0.0
        if piece.whole:
            return
        middle = 0.5 * (piece.start + piece.end)
        sides = ((math.sin(piece.start), -math.cos(piece.start)), (-math.sin(piece.end), math.cos(piece.end)),
                 (-math.cos(middle), -math.sin(middle)))
        for offset, (first, second) in enumerate(sides):
            lp.coefficient(row + offset, c1, first)
            lp.coefficient(row + offset, c2, second)
