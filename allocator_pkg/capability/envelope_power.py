"""The capability programme's power rows (docs/power.md, "Power rows"; docs/capability.md): the
allocator's rows (:meth:`~allocator_pkg.allocation.power_budget.PowerBudget.rows`: the same
pooled weights of the ties in force, available power, forward and reverse coefficients and
chords, :mod:`~allocator_pkg.methods.power_block`) appended to the dense linear programme of
:meth:`~allocator_pkg.capability.envelope.Capability.reach_forces`, its power columns after
lambda's."""

from __future__ import annotations

import numpy as np

from ..effectiveness.model import Model
from ..effectiveness.power_rows import PowerRows
from ..methods.power_block import add_power_rows, inequalities
from ..solvers.problem import Rows


def with_power_rows(model: Model, rows: PowerRows, cost: np.ndarray, a_ub: list, b_ub: list, a_eq: np.ndarray,
                    bounds: list) -> tuple:
    """(cost, inequality rows, their bounds, equality rows, column bounds) of a programme over
    the model's m columns and lambda with the power rows of ``rows`` added: their columns
    (free) after lambda's, sum_i w_ij q_i <= A_j and the chords q_i >= P_i l_k(|f_i|)."""
    columns = model.m + 1
    rated = np.maximum(np.abs(model.thrust_min), np.abs(model.thrust_max))
    scale = np.maximum(rated, 1e-9)
    terms: dict = {int(i): [(int(c), 1.0 / scale[i])] for i, c in zip(model.scalar, model.scalar_columns)}
    for i, (c1, c2) in zip(model.rot.tolist(), model.rot_columns.tolist()):
        terms[i] = ([(c1, 1.0 / scale[i])], [(c2, 1.0 / scale[i])])
    rated_power = np.maximum(np.where(model.power > 0.0, model.power, 1.0) * rated ** 1.5, 1e-9)
    table = Rows()
    block = add_power_rows(table, columns, rows.pattern, terms, rated, model.power, q_unit=rated_power,
                           row_unit=np.maximum(rated_power @ rows.pattern.pattern, 1.0))
    total = columns + block.columns
    extra_a, extra_b = inequalities(block, table.matrix(total).toarray(), rows, 0, total)
    a_ub = [np.r_[row, np.zeros(block.columns)] for row in a_ub] + list(extra_a)
    return (np.r_[cost, np.zeros(block.columns)], a_ub, list(b_ub) + extra_b.tolist(),
            np.hstack((a_eq, np.zeros((a_eq.shape[0], block.columns)))), bounds + [(None, None)] * block.columns)
