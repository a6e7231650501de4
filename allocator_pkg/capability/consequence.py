"""Online consequence analysis (IMO MSC/Circ.645, DP equipment class 2 and 3): for each
redundancy group of the vehicle, could the actuators left after its loss hold the present load?

The answer per group is a utilisation u: the smallest u >= 0 such that some extended force f
(1.16) gives the load in the controlled DOFs, T_e f = tau (1.17), with every actuator within
u times its force range: a thruster of fixed direction in [u low_i, u high_i], a rotatable one
inside u times its thrust region in one of its convex pieces (section 4.2; the configured
method's polygon of the thrust circle, cut by the circle where it reaches beyond it, as
:class:`~allocator_pkg.capability.envelope.Capability` has it; the circle as a polygon of
:data:`~allocator_pkg.methods.base.CIRCLE_SIDES` sides for a method without one). u <= 1: the
group's loss leaves enough; u > 1: it does not (the consequence alarm); inf: no force of the
remaining actuators gives the load's direction at all. The margin is 1 - u.

With a method that solves with the power rows (docs/power.md), the programme has the same rows:
the same chords of r^(3/2) (:mod:`~allocator_pkg.effectiveness.power_rows`) and the weights and
available power the allocator would have after the group's loss
(:meth:`~allocator_pkg.allocation.power_budget.PowerBudget.rows`), each source at u times its
available power (sum_i w_ij q_i <= u A_j, linear in u): u is the utilisation of the ranges and
the power together, and u <= 1 exactly when the allocator's own problem after the loss holds
the load.

A group's loss is what the allocator would have after it (:mod:`.group_loss`): the group's
actuators failed on top of the faults in force, the flushing zones of the working thrusters,
and the power rule's bounds with the group's sources at 0 kW and the others at their available
power in force. A rotatable thruster pushing onto a dead one ([3.11.4]) has each piece's radius
cut to the least loss factor over the piece's directions, as the allocator cuts a sample's
thrust over its angle window (:func:`~allocator_pkg.allocation.dead_flushing.cut`), and, unless
it reverses, the pieces with the loss sectors left alone at full radius as well.

Minimise u over each combination of the rotatable thrusters' convex pieces, the smallest over
all combinations the group's. One linear programme per group
(:class:`~allocator_pkg.solvers.linear_program.LinearProgram`) is set up once per configuration;
each analysis changes only coefficients of the same pattern, column and row bounds and the
right-hand side, each solve starting from the last basis.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from ..allocation.pieces import Piece, convex_pieces
from ..effectiveness.flushing import DeadFlushing
from ..effectiveness.model import Model
from ..effectiveness.power_rows import PowerPattern
from ..effectiveness.sectors import in_forbidden_sector
from ..methods import METHODS
from ..methods.base import CIRCLE_SIDES
from ..methods.power_block import PowerBlock, add_power_rows, write_programme
from ..solvers.linear_program import LinearProgram
from ..solvers.outcome import Outcome
from ..solvers.problem import Rows
from ..vehicle.angles import TWO_PI
from ..vehicle.config import RotationConfig, Vehicle
from .group_loss import InForce, Remaining, remaining

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


def force_pieces(rotation: RotationConfig, low: float, high: float, stuck: float | None,
                 losses: Sequence[DeadFlushing] = ()) -> list[Piece]:
    """Convex pieces of the forces a rotatable thruster gives with signed thrust in [low, high]
    (:func:`~allocator_pkg.allocation.pieces.convex_pieces`); a stuck one's line as its forward
    ray (radius ``high``) and, with ``low`` < 0, its reverse ray (radius ``-low``); one piece of
    radius 0 when it gives nothing. With [3.11.4] ``losses``: each piece's radius times the
    least loss factor over its directions, and for a thruster that neither reverses nor is stuck
    also the pieces with the loss sectors forbidden (left alone, as the allocator may)."""
    if max(high, -low) <= 0.0 or (stuck is not None and in_forbidden_sector(rotation, stuck)):
        return [Piece(0.0, 0.0, 0.0)]
    if stuck is None:
        pieces = convex_pieces(rotation, low, high)
    else:
        pieces = [Piece(stuck, stuck, high)] if high > 0.0 else []
        pieces += [Piece(stuck + math.pi, stuck + math.pi, -low)] if low < 0.0 else []
    if not losses:
        return pieces
    cut = [replace(piece, radius=piece.radius * min(loss.lowest(piece.start, piece.end) for loss in losses))
           for piece in pieces]
    if stuck is not None or low < 0.0:
        return cut
    left_alone = replace(rotation, forbidden_sectors=rotation.forbidden_sectors + tuple(loss.sector for loss in losses))
    return cut + convex_pieces(left_alone, low, high)


class Consequence:
    """The consequence analysis of one vehicle (its ``redundancy_groups``) with the thrust
    regions of ``method`` (None: the vehicle's)."""

    def __init__(self, vehicle: Vehicle, method: str | None = None):
        self.vehicle = vehicle
        self.method = method or vehicle.method
        self.model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
        faces = thrust_faces(vehicle, self.method)
        self._rows = METHODS[self.method].power_rows
        pattern = PowerPattern.of(vehicle) if self._rows else None
        self._programmes = [_Programme(self.model, faces, pattern) for _ in vehicle.redundancy_groups]

    @property
    def groups(self) -> tuple[str, ...]:
        return tuple(group.name for group in self.vehicle.redundancy_groups)

    def utilisation(self, load: Sequence[float], in_force: InForce | None = None) -> tuple[GroupUtilisation, ...]:
        """Each group's utilisation for ``load`` [X, Y, Z, K, M, N] (its controlled DOFs), the
        group's loss on top of what is ``in_force`` (:meth:`InForce.of` an allocator; None: a
        new allocator's, :meth:`InForce.intact`)."""
        groups = self.vehicle.redundancy_groups
        if not np.any(np.asarray(load, dtype=float)[self.model.dof_index]):
            return tuple(GroupUtilisation(group.name, 0.0) for group in groups)
        in_force = in_force or InForce.intact(self.vehicle)
        return tuple(self.utilisation_left(k, load, remaining(self.vehicle, in_force, group, self._rows))
                     for k, group in enumerate(groups))

    def utilisation_left(self, index: int, load: Sequence[float], left: Remaining) -> GroupUtilisation:
        """The ``index``-th group's utilisation for ``load`` with what its loss leaves, ``left``
        (:func:`~.group_loss.remaining`)."""
        request = np.asarray(load, dtype=float)[self.model.dof_index] / self.model.dof_scale
        value = self._programmes[index].smallest(request, left) if np.any(request) else 0.0
        return GroupUtilisation(self.vehicle.redundancy_groups[index].name, value)


class _Programme:
    """min u s.t. T_ec D x = tau (rows scaled by each DOF's authority), x_i - u a_i <= 0 and
    -x_i - u b_i <= 0 for a thruster of fixed direction (x_i = f_i / w_i, w_i = max(high_i,
    -low_i), a_i = high_i / w_i, b_i = -low_i / w_i), and for a rotatable one (x = f / R, R its
    piece's radius) the faces n . x - u apothem <= 0, the two sides of its piece's cone and
    "along the cone's middle, not against it". D holds w_i and R; a force range without zero (a
    stuck control surface) is a fixed x, and an actuator that gives nothing has x = 0. With a
    ``pattern``, the power rows (:mod:`~allocator_pkg.methods.power_block`) on x, their force
    per unit of x written with each analysis (w_i, or the piece's R)."""

    def __init__(self, model: Model, faces: list[tuple[float, float, float]], pattern: PowerPattern | None = None):
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
        table = Rows()
        for row in rows:
            table.add(list(row.items()))
        self.block = None if pattern is None else self._power_rows(table, pattern)
        columns = m + 1 + (0 if self.block is None else self.block.columns)
        a = table.matrix(columns)
        low = np.full(table.count, -np.inf)
        up = np.r_[np.zeros(len(rows)), np.full(table.count - len(rows), np.inf)]
        costs = np.zeros(columns)
        costs[m] = 1.0
        column_low = np.r_[np.full(m, -np.inf), 0.0, np.full(columns - m - 1, -np.inf)]
        column_up = np.full(columns, np.inf)
        self.lp = LinearProgram()
        self.lp.setup(costs, column_low, column_up, a, low, up, 0.0)
        self._columns = np.arange(m, dtype=np.int32)
        self._column_low, self._column_up = np.full(m, -np.inf), np.full(m, np.inf)
        self._scaled = model.t_ec / model.dof_scale[:, None]
        self._nonzero = [np.flatnonzero(model.t_ec[:, c]) for c in range(m)]

    def _power_rows(self, table: Rows, pattern: PowerPattern) -> PowerBlock:
        """The power rows on x (placeholders for the force per unit of x), q in units of each
        actuator's rated power and each source row in units of its consumers' rated power."""
        model = self.model
        self._rated = np.maximum(np.abs(model.thrust_min), np.abs(model.thrust_max))
        rated_power = np.maximum(np.where(model.power > 0.0, model.power, 1.0) * self._rated ** 1.5, 1e-9)
        terms: dict = {int(i): [(int(c), 1.0)] for i, c in zip(model.scalar, model.scalar_columns)}
        for i, (c1, c2) in zip(model.rot.tolist(), model.rot_columns.tolist()):
            terms[i] = ([(c1, 1.0)], [(c2, 1.0)])
        return add_power_rows(table, model.m + 1, pattern, terms, self._rated, model.power, q_unit=rated_power,
                              row_unit=np.maximum(rated_power @ pattern.pattern, 1.0), scale_column=model.m)

    def smallest(self, request: np.ndarray, left: Remaining) -> float:
        """The smallest utilisation over every combination of pieces (inf: none gives the request)."""
        model, lp = self.model, self.lp
        n = model.n
        lp.low[:n] = lp.up[:n] = request
        low, high = left.low, left.high
        self._fixed_direction(low, high)
        self._power = left.power if self.block is not None else None
        if self._power is not None:
            self._unit = np.maximum(np.maximum(high, -low), 0.0) / np.maximum(self._rated, 1e-9)
            write_programme(lp, self.block, self._power, self._unit)
        choices = [force_pieces(left.rotations[i], low[i], high[i], left.stuck.get(int(i)), left.losses.get(int(i), ()))
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
        if self._power is not None:
            i = int(self.model.rot[index])
            self._unit[i] = piece.radius / max(self._rated[i], 1e-9)
            write_programme(self.lp, self.block, self._power, self._unit, only=i)
        lp.up[row:row + 3] = np.inf if piece.whole else 0.0
        if piece.whole:
            return
        middle = 0.5 * (piece.start + piece.end)
        sides = ((math.sin(piece.start), -math.cos(piece.start)), (-math.sin(piece.end), math.cos(piece.end)),
                 (-math.cos(middle), -math.sin(middle)))
        for offset, (first, second) in enumerate(sides):
            lp.coefficient(row + offset, c1, first)
            lp.coefficient(row + offset, c2, second)
