"""The solver problems of method ``qp`` (:mod:`~.qp`), built once per configuration: (1.35) in
z = [f_e, s, fbar] (1.38), the scale problem of ``saturation: preserve_direction`` in
z = [f_e, lambda], and the priority cascade's, which adds one bound row per slack.

Each is rows, a diagonal objective and bounds on one sparsity pattern that stores every entry
that can ever be non-zero, so that a sample, a fault or a configuration of the same structure
changes values only. :class:`QPProblem` keeps the solver problem and the indices of what a
sample writes. docs/theory.md (section `qp`) has the rows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..effectiveness.model import Model
from ..effectiveness.power_rows import PowerPattern, PowerRows
from ..solvers.backend import NO_BOUND, Backend
from ..solvers.problem import Entries, Rows, ScaledProblem, block_index, entry_index
from .power_block import PowerBlock, add_power_rows, power_columns_scale


@dataclass
class QPProblem:
    """One solver problem and the rows a sample writes (indices into its rows, and into the
    stored entries of A for the values that follow the thrusters' directions); ``q`` its own
    linear term, ``biased`` whether the solver holds the thrust bias's instead (:mod:`~.bias`)."""

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
    q: np.ndarray = field(default_factory=lambda: np.zeros(0))
    biased: bool = False
    slack: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    rotated: np.ndarray = field(default_factory=lambda: np.zeros(0))
    directions: list[float] = field(default_factory=list)
    cos: list[float] = field(default_factory=list)
    sin: list[float] = field(default_factory=list)
    edges: list[float] = field(default_factory=list)
    multiplier: list[float] = field(default_factory=list)
    curvature: list[float] = field(default_factory=list)
    version: int = -1
    power: PowerBlock | None = None
    power_entries: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))


def layout(model: Model, scale: bool) -> tuple[int, int, int]:
    """(first slack or the lambda column, fbar column or -1, number of columns)."""
    if scale:
        return model.m, -1, model.m + 1
    return model.m, model.m + model.n, model.m + model.n + 1


def column_scale(model: Model, scale: bool) -> np.ndarray:
    """The physical range of each variable (the problem's normalisation)."""
    force = model.force_scale[model.extended_owner]
    if scale:
        return np.concatenate((force, [1.0]))
    return np.concatenate((force, np.maximum(model.authority, 1e-9), [float(np.max(force))]))


def objective(model: Model, scale: bool) -> tuple[np.ndarray, np.ndarray]:
    """Diagonal of P and q, physical units (OSQP minimises 1/2 x'Px + q'x)."""
    extra, top, columns = layout(model, scale)
    q = np.zeros(columns)
    if scale:
        force = model.force_scale[model.extended_owner]
        epsilon = 1e-3 / float(np.sum(model.weight_ext * force * force))
        q[extra] = -1.0
        return np.concatenate((2.0 * epsilon * model.weight_ext, [0.0])), q
    q[top] = model.vehicle.weights.minimax
    return np.concatenate((2.0 * model.weight_ext, 2.0 * model.slack_weights(model.weight), [0.0])), q


def constraints(model: Model, scale: bool, stages: bool = False,
                pattern: PowerPattern | None = None) -> tuple[sp.csc_matrix, dict, PowerBlock | None]:
    """A, the indices of its rows by kind and the power rows' block (with a ``pattern``), every
    entry that can ever be non-zero stored: T_e dense, both components of every polygon face
    and angle edge (``stages``: one bound row per slack besides), the power rows
    (:mod:`~.power_block`) after every other row, their columns after every other column."""
    sides = model.vehicle.azimuth_polygon_sides
    extra, top, columns = layout(model, scale)
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
    block = None
    if pattern is not None:
        block = add_power_rows(rows, columns, pattern, power_terms(model), rated(model), model.power)
        columns += block.columns
    index = dict(equality=np.array(equality, int), box=np.array(box, int), minimax=np.array(minimax, int),
                 polygon=np.array(polygon, int).reshape(len(model.rot), sides),
                 polygon_minimax=np.array(polygon_minimax, int).reshape(len(model.rot), 0 if scale else sides),
                 along=np.array(along, int),
                 across=np.array(across, int), edge_low=np.array(edge_low, int),
                 edge_high=np.array(edge_high, int), last=last, slack=np.array(slack, int))
    return rows.matrix(columns), index, block


def rated(model: Model) -> np.ndarray:
    """F_i [N]: the largest magnitude of each actuator's configured range, the chords' range."""
    return np.maximum(np.abs(model.thrust_min), np.abs(model.thrust_max))


def power_terms(model: Model) -> dict[int, list | tuple]:
    """t_i = f_i / F_i in the problem's columns: a scalar actuator's column, a rotatable
    thruster's two (its frame turns with it; the polygon of the magnitude is safe in any)."""
    scale = np.maximum(rated(model), 1e-9)
    terms: dict[int, list | tuple] = {int(i): [(int(c), 1.0 / scale[i])] for i, c in zip(model.scalar,
                                                                                        model.scalar_columns)}
    for i, (c1, c2) in zip(model.rot.tolist(), model.rot_columns.tolist()):
        terms[i] = ([(c1, 1.0 / scale[i])], [(c2, 1.0 / scale[i])])
    return terms


def write_power(problem: QPProblem, rows: PowerRows, margin: float) -> None:
    """The values of ``rows`` in a problem's power rows: entries and bounds, no new set-up.
    Each source row's bound is A_j (1 - ``margin``): a solution within the solver's tolerance
    keeps the source within A_j."""
    block, qp = problem.power, problem.qp
    chord, weight, low, up = block.values(rows)
    up = up * (1.0 - margin)
    short = rows.short()
    bound = block.bound_actuators(short)
    qp.update_matrix(np.concatenate((chord, weight)), problem.power_entries)
    qp.low[block.chord_row] = np.where(bound[block.chord_owner_row[:, 0]], low, -NO_BOUND)
    qp.up[block.chord_row] = NO_BOUND
    qp.low[block.source_row], qp.up[block.source_row] = -NO_BOUND, np.where(short, up, NO_BOUND)
    qp.low[block.polygon_row] = np.where(bound[block.polygon_owner], 0.0, -NO_BOUND)
    qp.up[block.polygon_row] = NO_BOUND


def constant_bounds(qp: ScaledProblem, model: Model, index: dict, scale: bool) -> None:
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


def build(model: Model, scale: bool, backend: Backend, stages: bool = False,
          pattern: PowerPattern | None = None) -> QPProblem:
    """The problem (``scale``: the scale problem of ``preserve_direction``; ``stages``: the
    priority cascade's; ``pattern``: with the power rows) on ``backend``, with its constant
    bounds and the indices a sample writes."""
    a, index, block = constraints(model, scale, stages, pattern)
    p, q = objective(model, scale)
    columns = column_scale(model, scale)
    if block is not None:
        p, q = np.concatenate((p, np.zeros(block.columns))), np.concatenate((q, np.zeros(block.columns)))
        columns = np.concatenate((columns, power_columns_scale(block, rated(model))))
    extra = layout(model, scale)[0]
    qp = ScaledProblem(p, q, a, columns, model.vehicle.solver,
                       effort=np.arange(0 if not scale else model.m, model.m if not scale else model.m + 1),
                       backend=backend)
    constant_bounds(qp, model, index, scale)
    rows = index["equality"]
    rotated_index = np.array([[[entry_index(a, int(row), int(col)) for col in pair] for row in rows]
                              for pair in model.rot_columns], dtype=np.int64).reshape(len(model.rot), 2 * len(rows))
    edge_index = np.array([[entry_index(a, int(row), int(col)) for row in (low, high) for col in pair]
                           for pair, low, high in zip(model.rot_columns, index["edge_low"], index["edge_high"])],
                          dtype=np.int64).reshape(len(model.rot), 4)
    scale_index = np.array([entry_index(a, row, extra) for row in rows] if scale else [], dtype=np.int64)
    rotatable = len(model.rot)
    per_thruster = [(index["polygon"][k], int(index["along"][k]), int(index["across"][k]),
                     int(index["edge_low"][k]), int(index["edge_high"][k])) for k in range(rotatable)]
    return QPProblem(qp=qp, equality=rows, box=index["box"], polygon=index["polygon"],
                     polygon_minimax=index["polygon_minimax"], along=index["along"],
                     across=index["across"], edge_low=index["edge_low"], edge_high=index["edge_high"],
                     rotated_index=rotated_index.reshape(-1), edge_index=edge_index.reshape(-1),
                     scale_index=scale_index, p_diagonal=p, q=q, rows=per_thruster,
                     moving=qp.entries(np.concatenate((rotated_index.reshape(-1), edge_index.reshape(-1)))),
                     index=index, t_ec_index=block_index(a, rows, model.m),
                     multiplier=[0.0] * rotatable, curvature=[0.0] * rotatable, slack=index["slack"],
                     power=block, power_entries=power_entries(a, block))


def power_entries(a: sp.csc_matrix, block: PowerBlock | None) -> np.ndarray:
    """CSC positions of the power rows' changing entries: chord force entries, then weights."""
    if block is None:
        return np.zeros(0, np.int64)
    pairs = np.concatenate((block.chord_entry, block.weight_entry))
    return np.array([entry_index(a, int(row), int(col)) for row, col in pairs.tolist()], dtype=np.int64)
