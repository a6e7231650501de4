"""The power rows (:mod:`allocator_pkg.effectiveness.power_rows`, docs/theory.md "Power rows")
as columns and rows of a method's problem, on a sparsity pattern fixed per configuration.

Per powered actuator i an epigraph column q_i (power, in units of ``q_unit``), and for a
rotatable thruster a magnitude column rho_i (a fraction of its range F_i). With t_i = f_i / F_i
written by the method as a sum of its own columns (``force_terms``), and R_i = P_ref,i F_i^(3/2)
(P_ref the configured coefficient, 1 W/N^1.5 for one of zero):

    scalar:     (q_unit / R_i) q_i - (P_fwd / P_ref) s_k t_i >= (P_fwd / P_ref) c_k
                (q_unit / R_i) q_i + (P_rev / P_ref) s_k t_i >= (P_rev / P_ref) c_k
    rotatable:  cos(pi/N) rho_i - n_l . (t_x, t_y) >= 0           every face l of the N-gon
                (q_unit / R_i) q_i - (P_fwd / P_ref) s_k rho_i >= (P_fwd / P_ref) c_k
    source j:   sum_i w_ij q_unit q_i <= A_j                         (divided by ``row_unit``)

for every chord k. What a change of feeds, coefficients or available power moves are values:
the chord rows' force entries and lower bounds, the source rows' weights and upper bounds
(:meth:`PowerBlock.values`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..effectiveness.power_rows import BREAKPOINTS, POWER_SIDES, PowerPattern, PowerRows, chord_lines, polygon
from ..solvers.backend import NO_BOUND
from ..solvers.linear_program import LinearProgram
from ..solvers.problem import Rows

Terms = list[tuple[int, float]]
"""A linear expression in a problem's columns: (column, coefficient) pairs."""


@dataclass
class PowerBlock:
    """Where the power rows sit in one problem: the columns they add and, for the values that
    change, the rows and columns of the entries (chord force entries, source weights) and
    the rows of the bounds."""

    pattern: PowerPattern
    columns: int
    q_column: np.ndarray
    rho_column: np.ndarray
    chord_entry: np.ndarray
    chord_base: np.ndarray
    chord_owner: np.ndarray
    chord_row: np.ndarray
    chord_low: np.ndarray
    chord_owner_row: np.ndarray
    polygon_row: np.ndarray
    polygon_owner: np.ndarray
    weight_entry: np.ndarray
    weight_pair: np.ndarray
    source_row: np.ndarray
    reference: np.ndarray
    q_unit: np.ndarray
    row_unit: np.ndarray
    scale_column: int = -1

    def bound_actuators(self, short: np.ndarray) -> np.ndarray:
        """Per actuator, whether it has a weight in a ``short`` row: its chord and polygon rows
        are in force; those of the others, and the rows that are not short, bound nothing (an
        OSQP row without bounds costs it nothing)."""
        return (self.pattern.pattern[:, short]).any(axis=1)

    def values(self, rows: PowerRows, unit: np.ndarray | None = None
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(chord entries, source weight entries, chord rows' lower bounds, source rows' upper
        bounds) at ``rows``; entries in the order of ``chord_entry`` and ``weight_entry``.
        ``unit`` (per actuator): the force per unit of the columns in ``force_terms`` where the
        terms were written with a coefficient of 1 standing for it (a programme whose columns
        are scaled per analysis)."""
        ratio = np.column_stack((rows.forward, rows.reverse)) / self.reference[:, None]
        chord = self.chord_base * ratio[self.chord_owner[:, 0], self.chord_owner[:, 1]]
        if unit is not None:
            chord = chord * unit[self.chord_owner[:, 0]]
        low = self.chord_low * ratio[self.chord_owner_row[:, 0], self.chord_owner_row[:, 1]]
        i, j = self.weight_pair[:, 0], self.weight_pair[:, 1]
        weight = rows.weights[i, j] * self.q_unit[i] / self.row_unit[j]
        up = np.where(np.isfinite(rows.available), rows.available / self.row_unit, NO_BOUND)
        return chord, weight, low, up


def add_power_rows(rows: Rows, first: int, pattern: PowerPattern, force_terms: dict[int, Terms | tuple[Terms, Terms]],
                   rated: np.ndarray, coefficient: np.ndarray, q_unit: np.ndarray | None = None,
                   row_unit: np.ndarray | None = None, count: int = BREAKPOINTS,
                   sides: int = POWER_SIDES, scale_column: int = -1) -> PowerBlock:
    """Append the power columns (from column ``first``) and rows to ``rows``, the values those
    of every coefficient equal to the configured ``coefficient`` and every weight 1 (written
    again by :meth:`PowerBlock.values`). ``force_terms`` per powered actuator: t_i for a scalar
    one, (t_x, t_y) for a rotatable one; ``rated`` F_i [N]. ``scale_column``: a column u that
    scales the available power (sum_i w_ij q_i - u A_j <= 0, a utilisation; -1: none)."""
    powered = pattern.powered
    r = pattern.pattern.shape[0]
    q_unit = np.ones(r) if q_unit is None else q_unit
    row_unit = np.ones(pattern.pattern.shape[1]) if row_unit is None else row_unit
    reference = np.where(coefficient > 0.0, coefficient, 1.0)
    slope, intercept = chord_lines(count)
    normals, apothem = polygon(sides)
    q_column, rho_column = np.full(r, -1), np.full(r, -1)
    column = first
    entry, base, owner, row_of, low, owner_row, faces, face_owner = [], [], [], [], [], [], [], []
    for i in powered.tolist():
        q_column[i], column = column, column + 1
        terms = force_terms[i]
        unit = q_unit[i] / (reference[i] * max(rated[i], 1e-9) ** 1.5)
        if isinstance(terms, tuple):
            rho_column[i], column = column, column + 1
            for nx, ny in normals:
                face_owner.append(i)
                faces.append(rows.add([(int(rho_column[i]), apothem)] + [(c, -nx * v) for c, v in terms[0]]
                         + [(c, -ny * v) for c, v in terms[1]]))
            signed = [(1.0, 0, [(int(rho_column[i]), 1.0)])]
        else:
            signed = [(1.0, 0, terms), (-1.0, 1, terms)]
        for sign, direction, expression in signed:
            for s, c in zip(slope.tolist(), intercept.tolist()):
                row = rows.add([(int(q_column[i]), unit)] + [(col, -sign * s * v) for col, v in expression])
                for col, v in expression:
                    entry.append((row, col))
                    base.append(-sign * s * v)
                    owner.append((i, direction))
                row_of.append(row)
                low.append(c)
                owner_row.append((i, direction))
    source, weight_entry, weight_pair = [], [], []
    for j in range(pattern.pattern.shape[1]):
        members = [i for i in powered.tolist() if pattern.pattern[i, j]]
        scale = [(scale_column, -1.0)] if scale_column >= 0 else []
        row = rows.add([(int(q_column[i]), q_unit[i] / row_unit[j]) for i in members] + scale)
        source.append(row)
        weight_entry += [(row, int(q_column[i])) for i in members]
        weight_pair += [(i, j) for i in members]
    return PowerBlock(pattern=pattern, columns=column - first, q_column=q_column, rho_column=rho_column,
                      chord_entry=np.array(entry, dtype=np.int64).reshape(-1, 2), chord_base=np.array(base),
                      chord_owner=np.array(owner, dtype=np.int64).reshape(-1, 2),
                      chord_row=np.array(row_of, dtype=np.int64), chord_low=np.array(low),
                      chord_owner_row=np.array(owner_row, dtype=np.int64).reshape(-1, 2),
                      polygon_row=np.array(faces, dtype=np.int64),
                      polygon_owner=np.array(face_owner, dtype=np.int64),
                      weight_entry=np.array(weight_entry, dtype=np.int64).reshape(-1, 2),
                      weight_pair=np.array(weight_pair, dtype=np.int64).reshape(-1, 2),
                      source_row=np.array(source, dtype=np.int64), reference=reference, q_unit=q_unit,
                      row_unit=row_unit, scale_column=scale_column)


def write_programme(lp: LinearProgram, block: PowerBlock, rows: PowerRows, unit: np.ndarray,
                    only: int | None = None) -> None:
    """The values of ``rows`` in a HiGHS programme's power rows (``unit`` as in
    :meth:`PowerBlock.values`); ``only``: the chord entries of that actuator alone (its unit
    changed), nothing else."""
    chord, weight, low, up = block.values(rows, unit)
    for (row, col), value, (owner, _) in zip(block.chord_entry.tolist(), chord.tolist(), block.chord_owner.tolist()):
        if only is None or owner == only:
            lp.coefficient(row, col, value)
    if only is not None:
        return
    for (row, col), value in zip(block.weight_entry.tolist(), weight.tolist()):
        lp.coefficient(row, col, value)
    lp.low[block.chord_row], lp.up[block.chord_row] = low, NO_BOUND
    lp.low[block.source_row], lp.up[block.source_row] = -NO_BOUND, up
    if block.scale_column >= 0:                 # sum w q - u A <= 0: the utilisation scales the power
        bounded = up < NO_BOUND
        for row, value, finite in zip(block.source_row.tolist(), up.tolist(), bounded.tolist()):
            lp.coefficient(row, block.scale_column, -value if finite else 0.0)
        lp.up[block.source_row] = np.where(bounded, 0.0, NO_BOUND)
    lp.low[block.polygon_row], lp.up[block.polygon_row] = 0.0, NO_BOUND


def inequalities(block: PowerBlock, matrix: np.ndarray, rows: PowerRows, first_row: int,
                 columns: int) -> tuple[np.ndarray, np.ndarray]:
    """The power rows as dense A_ub x <= b_ub (``matrix``: the dense rows :func:`add_power_rows`
    wrote, from row ``first_row``; ``columns`` of the programme), the values of ``rows``."""
    a = np.array(matrix, dtype=float)
    chord, weight, low, up = block.values(rows)
    for (row, col), value in zip(block.chord_entry.tolist(), chord.tolist()):
        a[row - first_row, col] = value
    for (row, col), value in zip(block.weight_entry.tolist(), weight.tolist()):
        a[row - first_row, col] = value
    b = np.zeros(a.shape[0])
    sign = np.ones(a.shape[0])
    sign[block.chord_row - first_row] = sign[block.polygon_row - first_row] = -1.0      # ">=" rows turned round
    b[block.chord_row - first_row] = -low
    b[block.source_row - first_row] = up
    return sign[:, None] * a[:, :columns], b


def power_columns_scale(block: PowerBlock, rated: np.ndarray) -> np.ndarray:
    """The physical range of each power column (q: R_i [W] in units of q_unit, rho: 1), in
    column order, for a problem that scales its columns."""
    scale = np.ones(block.columns)
    first = int(min(block.q_column[block.q_column >= 0].min(initial=10**9),
                    block.rho_column[block.rho_column >= 0].min(initial=10**9)))
    for i in np.flatnonzero(block.q_column >= 0).tolist():
        scale[block.q_column[i] - first] = block.reference[i] * max(rated[i], 1e-9) ** 1.5 / block.q_unit[i]
    return scale
