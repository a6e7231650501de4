"""The Level 1 balances of one case (intact, or what a redundancy group's loss leaves) on linear
programmes set up once and kept between balances.

The balances of a case (every condition and heading) share the programme's shape and differ in
values only: the request, the thrust ranges of the working thrusters (T_nominal times beta_misc
and beta_vent [3.9.2]-[3.9.4] of the condition and heading) and so the radius of each rotatable
thruster's convex piece. :meth:`CaseBalance.attains` answers as
:meth:`~..capability.envelope.Capability.attains` (and
:meth:`~.standard.power_balance.PoweredCapability.attains` with the power rows [3.12]) of the
variant would: the same programme per combination of pieces, with the same rows, bounds and
coefficients, the combinations in the same order, and with the power rows the programme without
them first where that decides the answer. What is kept: per shape of a combination (each piece's
cone, line, half-planes and whether it has thrust; a fixed powered thruster's directions) a
:class:`~..solvers.linear_program.LinearProgram` without and one with the power rows, whose
values each balance sets (a piece row's bound, its radius times the number of its shape; a
fixed thruster's range as its column's bounds; the request's column; the power rows' thrust
fractions, :func:`~.standard.power_balance.fraction_entries`), each solve starting from the last
basis (dual simplex). Not verified by DNV.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..allocation.conditions import Conditions
from ..capability.envelope import Capability
from ..capability.thrust_profile import ForceProfile
from ..capability.thruster_pieces import thruster_pieces
from ..effectiveness.faults import FaultSet
from ..solvers.linear_program import LinearProgram
from ..solvers.outcome import Solution
from ..vehicle.config import Vehicle
from .standard.power_balance import CHORDS, PowerLimits, fraction_entries, power_rows, within

DUAL_TOLERANCE = 1e-10
"""HiGHS's dual feasibility tolerance of the kept programmes (its least): a warm start from the
basis of a neighbouring balance stops where no reduced cost is beyond it, and its default
(1e-7) can leave a multiple 1e-4 short of the optimum with the forces in newtons."""
COLD_BAND = 1e-6
"""A warm answer within this share of the multiple asked is solved again from no basis."""
TIE = 1e-6
"""Two combinations whose largest multiples are this close (relative) are not told apart."""
MARGIN = 1e-9
"""A balance holds when the largest multiple of the load is at least 1 - MARGIN."""


def authority_scale(tau: np.ndarray, dof_index: np.ndarray, authority: np.ndarray) -> float:
    """The largest ratio of ``tau`` [X, Y, Z, K, M, N] to the authority in a controlled DOF: a
    balance asks for ``tau`` over it, so that its multiple is in units of authority."""
    return float(np.max(np.abs(tau[dof_index]) / np.maximum(authority, 1e-12)))


@dataclass
class _Programme:
    """One kept programme: the HiGHS model, the inequality rows whose bound is a piece's radius
    times a number (``piece_rows``, ``owners``: the piece of each, ``numbers``), the equality
    rows (``equalities``), the request's column and the first power row (None: without power
    rows)."""

    lp: LinearProgram
    piece_rows: np.ndarray
    owners: np.ndarray
    numbers: np.ndarray
    equalities: np.ndarray
    column: int
    first_power_row: int | None


class CaseBalance:
    """The balances of one case: ``capability``, the capability analysis of one of its variants
    (its model's columns and its method's polygon: the same for every variant of the case),
    ``limits`` the power rows of the case (None: without)."""

    def __init__(self, capability: Capability, limits: PowerLimits | None):
        if capability.sides is None:
            raise ValueError(f"method {capability.method} cannot redistribute force; it has no programme to keep")
        self.capability = capability
        self.limits = limits
        self._programmes: dict[tuple, _Programme] = {}

    def attains(self, variant: Vehicle, profiles: Mapping[str, ForceProfile], tau: np.ndarray,
                first: int = 0) -> tuple[bool, int]:
        """Whether the variant (this case's working thrusters with the condition's and heading's
        ranges; ``profiles`` its thrust profiles) gives ``tau`` [X, Y, Z, K, M, N] (nonzero in a
        controlled DOF), and the index of the combination of pieces that does (-1: none), trying
        ``first`` first: :meth:`Capability.attains` of ``tau`` over its largest ratio to the
        variant's authority, ``multiple`` that ratio times 1 - MARGIN."""
        low, high, request, scale, combinations = self._prepare(variant, profiles, tau)
        multiple = scale * (1.0 - MARGIN)
        for k in sorted(range(len(combinations)), key=lambda k: k != first):
            if self._reach(variant, request, low, high, combinations[k], multiple) >= multiple:
                return True, k
        return False, -1

    def largest(self, variant: Vehicle, profiles: Mapping[str, ForceProfile], tau: np.ndarray) -> int | None:
        """The index of the combination of pieces (in :meth:`attains`' order) whose programme, the
        power rows in force, gives the largest multiple of ``tau``; None where none gives any or
        another comes within TIE of it."""
        low, high, request, _, combinations = self._prepare(variant, profiles, tau)
        multiples = []
        for pieces in combinations:
            solution = self._solve(variant, request, low, high, pieces, self.limits is not None, None)
            multiples.append(float(solution.x[self.capability.model.m]) if solution.usable else 0.0)
        best = int(np.argmax(multiples))
        if multiples[best] <= 0.0 or any(multiple >= (1.0 - TIE) * multiples[best]
                                         for k, multiple in enumerate(multiples) if k != best):
            return None
        return best

    def _prepare(self, variant: Vehicle, profiles: Mapping[str, ForceProfile], tau: np.ndarray) -> tuple:
        """(low, high, request, scale, combinations): the variant's force ranges with the zones in
        force, ``tau`` over its largest ratio to the variant's authority (``scale``) in the
        controlled DOFs, and every combination of its rotatable thrusters' convex pieces."""
        model = self.capability.model
        if any(a.is_surface for a in variant.actuators):
            raise ValueError("a Level 1 variant has no control surfaces: a rudder is its propeller's profile")
        conditions = Conditions.of(variant, FaultSet.of(variant, None), 0.0, None)
        low, high = conditions.low, conditions.high
        force_scale = np.array([max(a.thrust_max, -a.thrust_min) for a in variant.actuators])
        scale = authority_scale(tau, model.dof_index, np.abs(model.t_ec) @ force_scale[model.extended_owner])
        choices = []
        for i in model.rot:
            name = variant.actuators[i].name
            choices.append(thruster_pieces(conditions.rotations[i], conditions.faults.faults.get(name), low[i],
                                           high[i], profiles.get(name), conditions.losses.get(int(i), ())))
        return low, high, np.asarray(tau / scale, dtype=float)[model.dof_index], scale, list(
            itertools.product(*choices))

    def _reach(self, variant: Vehicle, request: np.ndarray, low: np.ndarray, high: np.ndarray, pieces,
               multiple: float) -> float:
        """The largest multiple of ``request`` within one combination of pieces: without the
        power rows, and with them where the forces of that answer scaled to ``multiple`` would
        take a source beyond its power."""
        model = self.capability.model
        plain = self._solve(variant, request, low, high, pieces, False, multiple)
        if not plain.usable:
            return 0.0
        if self.limits is None or plain.x[-1] < multiple or within(
                self.limits, model, variant.actuators, plain.x[:-1] * (multiple / plain.x[-1]), pieces):
            return float(plain.x[-1])
        powered = self._solve(variant, request, low, high, pieces, True, multiple)
        return float(powered.x[model.m]) if powered.usable else 0.0

    def _solve(self, variant: Vehicle, request: np.ndarray, low: np.ndarray, high: np.ndarray, pieces,
               powered: bool, multiple: float | None) -> Solution:
        """One kept programme with this balance's values, solved from the last basis, and again
        from none where the answer is within COLD_BAND of ``multiple`` (None: not again)."""
        model = self.capability.model
        key = (powered, tuple((start, end, line, chords, radius > 0.0) for start, end, radius, line, chords in pieces),
               self._directions(variant) if powered else ())
        programme = self._programmes.get(key)
        if programme is None:
            programme = self._programmes[key] = self._setup(variant, request, low, high, pieces, powered)
        lp = programme.lp
        radii = np.array([piece[2] for piece in pieces])
        lp.up[programme.piece_rows] = radii[programme.owners] * programme.numbers
        lp.column_bounds(model.scalar_columns.astype(np.int32), low[model.scalar], high[model.scalar])
        for row, value in zip(programme.equalities, request):
            lp.coefficient(int(row), programme.column, -float(value))
        if programme.first_power_row is not None:
            row = programme.first_power_row
            for fractions in fraction_entries(self.limits, model, variant.actuators, pieces):
                for entries in fractions:
                    for column, coefficient in entries:
                        lp.coefficient(row, int(column), coefficient)
                    row += 1
                row += len(CHORDS)
        solution = lp.solve()
        if multiple is not None and solution.usable and abs(solution.x[model.m] - multiple) <= COLD_BAND * multiple:
            solution = lp.solve(cold=True)
        return solution

    def _directions(self, variant: Vehicle) -> tuple:
        """Which ways each fixed thruster of the power rows pushes (its rows)."""
        actuators = {a.name: a for a in variant.actuators}
        return tuple((actuators[name].thrust_max > 0.0, actuators[name].thrust_min < 0.0)
                     for name in self.limits.thrusters if not actuators[name].rotatable)

    def _setup(self, variant: Vehicle, request: np.ndarray, low: np.ndarray, high: np.ndarray, pieces,
               powered: bool) -> _Programme:
        """The programme of a combination's shape, from the capability's own rows: the pieces
        with radius 1 give the number of each piece row."""
        capability, model = self.capability, self.capability.model
        shapes = [(start, end, 1.0 if radius > 0.0 else radius, line, chords)
                  for start, end, radius, line, chords in pieces]
        cost, a_ub, b_ub, a_eq, bounds = capability._constraints(request, low, high, shapes, capability.sides)
        base = len(cost)
        head = np.array(a_ub).reshape(-1, base) if a_ub else np.zeros((0, base))
        owners = np.array([next(k for k, (c1, c2) in enumerate(model.rot_columns) if row[c1] != 0.0 or row[c2] != 0.0)
                           for row in head], dtype=int)
        right = np.array(b_ub, dtype=float)
        first_power_row = None
        if powered:
            rows, power_right = power_rows(self.limits, model, variant.actuators, base, pieces)
            extra = rows.shape[1] - base
            cost = np.concatenate([cost, np.zeros(extra)])
            first_power_row = len(head)
            head = np.vstack([np.hstack([head, np.zeros((len(head), extra))]), rows])
            right = np.concatenate([right, power_right])
            a_eq = np.hstack([a_eq, np.zeros((a_eq.shape[0], extra))])
            bounds = [*bounds, *[(0.0, None)] * extra]
        matrix = np.vstack([head, a_eq])
        column_low = np.array([-np.inf if lo is None else lo for lo, _ in bounds], dtype=float)
        column_up = np.array([np.inf if hi is None else hi for _, hi in bounds], dtype=float)
        lp = LinearProgram(DUAL_TOLERANCE)
        lp.setup(cost, column_low, column_up, sp.csc_matrix(matrix),
                 np.concatenate([np.full(len(head), -np.inf), np.zeros(len(a_eq))]),
                 np.concatenate([right, np.zeros(len(a_eq))]), 0.0)
        return _Programme(lp, np.arange(len(owners)), owners, right[:len(owners)],
                          np.arange(len(head), len(head) + len(a_eq)), model.m, first_power_row)

