"""The solver problems of the qp method: their rows on one pattern that keeps every entry that
can change, the objective of (1.35) and of the scale problem, and the bounds a configuration
fixes. The answers they give are tested in test_qp.py."""

import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from

from allocator_pkg.effectiveness.model import Model
from allocator_pkg.methods.qp_problem import build, constraints, objective
from allocator_pkg.solvers import BACKENDS
from allocator_pkg.solvers.problem import entry_index

EXAMPLE1 = ROOT / "config" / "example1_rov.yaml"


def model_of(**overrides) -> Model:
    """Example 1: two azimuths and two fixed main thrusters on surge, sway and yaw."""
    vehicle = vehicle_from(EXAMPLE1, **overrides)
    return Model.build(vehicle, 1.0 / vehicle.rate_hz)


@pytest.mark.parametrize("scale, stages", [(False, False), (True, False), (False, True)])
def test_the_rows_of_each_problem_and_every_entry_that_can_change_stored(scale, stages):
    """Equality, box, minimax (not in the scale problem), per rotatable thruster N polygon
    faces (and N minimax faces), along, across and two edges, the last row (fbar or lambda),
    and one slack row per DOF in the cascade's problem; T_e stored whole, zeros included."""
    model = model_of()
    sides = model.vehicle.azimuth_polygon_sides
    a, index, block = constraints(model, scale, stages)
    assert block is None                                    # no power sources: no power rows
    scalar, rotatable, n = model.scalar_columns.size, model.rot.size, model.n
    minimax = 0 if scale else 2 * scalar + rotatable * sides
    assert a.shape == (n + scalar + minimax + rotatable * (sides + 4) + 1 + (n if stages else 0),
                       model.m + (1 if scale else n + 1))
    assert index["slack"].size == (n if stages else 0)
    assert np.count_nonzero(model.t_ec == 0.0) > 0
    for k, row in enumerate(index["equality"]):
        stored = [a.data[entry_index(a, int(row), c)] for c in range(model.m)]
        assert stored == model.t_ec[k].tolist()
    for pair, low, high in zip(model.rot_columns, index["edge_low"], index["edge_high"]):
        assert [a.data[entry_index(a, int(row), int(c))] for row in (low, high) for c in pair] == [0.0, 1.0] * 2


def test_the_objective_is_that_of_1_35_and_of_the_scale_problem():
    model = model_of(weights__minimax=3.0)
    p, q = objective(model, scale=False)
    slack = model.slack_weights(model.weight)
    assert p.tolist() == [*(2.0 * model.weight_ext), *(2.0 * slack), 0.0]
    assert q[-1] == 3.0 and not q[:-1].any()
    p, q = objective(model, scale=True)
    force = model.force_scale[model.extended_owner]
    assert q.tolist() == [0.0] * model.m + [-1.0] and p[-1] == 0.0
    assert 0.5 * p[:-1] @ (force * force) == pytest.approx(1e-3)     # the effort: a tie-breaker


@pytest.mark.parametrize("beta", [0.0, 3.0])
def test_without_a_minimax_weight_fbar_is_pinned_and_its_rows_switched_off(beta):
    model = model_of(weights__minimax=beta)
    problem = build(model, False, BACKENDS["osqp"]())
    qp, index = problem.qp, problem.index
    rows = index["minimax"]
    if beta == 0.0:
        assert (qp.low[index["last"]], qp.up[index["last"]]) == (0.0, 0.0)
        assert np.all(np.isinf(qp.low[rows])) and np.all(np.isinf(qp.up[rows]))
        assert np.all(qp.up[index["polygon_minimax"]] == math.inf)
    else:
        assert (qp.low[index["last"]], qp.up[index["last"]]) == (0.0, float(np.max(model.force_scale)))
        assert np.all(qp.up[rows[0::2]] == 0.0) and np.all(qp.low[rows[1::2]] == 0.0)
        assert np.all(qp.up[index["polygon_minimax"]] == 0.0)
