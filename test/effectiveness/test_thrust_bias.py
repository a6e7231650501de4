"""The thrust bias offset b: opposed forces of bias.thrust along each pair's line, free of wrench
in the controlled DOFs, faded by the filtered load, and none for a pair that a fault leaves
unable."""

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg import read_parameters, vehicle_from_parameters
from allocator_pkg.effectiveness.model import Model
from allocator_pkg.effectiveness.thrust_bias import ThrustBias, fade

PARAMETERS = {**read_parameters(ROOT / "config" / "dp_vessel.yaml"), "bias.enabled": True}
MODEL = Model.build(vehicle_from_parameters(PARAMETERS), 0.1)
HIGH = MODEL.thrust_max.copy()


def bias(model=MODEL, high=HIGH, stuck=None) -> ThrustBias:
    term = ThrustBias()
    term.configure(model)
    term.refresh(high, stuck or {})
    return term


@pytest.mark.parametrize("load, share", [(0.0, 1.0), (0.1, 1.0), (0.15, 0.5), (0.2, 0.0), (0.9, 0.0)])
def test_the_bias_is_full_up_to_the_start_and_gone_from_the_end(load, share):
    assert fade(load, 0.1, 0.2) == pytest.approx(share)


@settings(deadline=None, max_examples=60)
@given(tau=st.lists(st.floats(-1.0, 1.0), min_size=3, max_size=3))
def test_the_offset_is_opposed_by_the_set_thrust_and_free_of_wrench(tau):
    request = np.array(tau) * 0.08 * MODEL.dof_scale
    offset = bias().offsets(request)                          # a first sample: the load as it is
    load = float(np.max(np.abs(request) / MODEL.dof_scale))
    share = fade(load, 0.03, 0.06)
    if share == 0.0:
        assert offset is None
        return
    stbd, port = offset[0:2], offset[2:4]
    assert np.linalg.norm(stbd) == pytest.approx(60000.0 * share) and np.array_equal(stbd, -port)
    assert stbd[1] < 0.0 and stbd[0] == pytest.approx(0.0, abs=1e-9)     # starboard unit pushes to port
    assert np.all(offset[4:] == 0.0)                                      # the tunnels get none
    assert MODEL.t_ec @ offset == pytest.approx(np.zeros(3), abs=1e-6)


def test_a_pair_that_a_fault_leaves_unable_pushes_none():
    assert bias().offsets(np.zeros(3)) is not None
    assert bias(stuck={1: 0.0}).offsets(np.zeros(3)) is None
    failed = HIGH.copy()
    failed[0] = 0.0
    assert bias(high=failed).offsets(np.zeros(3)) is None
    degraded = HIGH.copy()
    degraded[1] = 60000.0                                                 # no more than the bias left
    assert bias(high=degraded).offsets(np.zeros(3)) is None
    degraded[1] = 0.5 * HIGH[1]
    assert bias(high=degraded).offsets(np.zeros(3)) is not None


def test_the_fade_follows_the_load_through_a_first_order_filter():
    term = bias()
    gain = 1.0 - np.exp(-0.1 / 60.0)
    calm, rough = np.zeros(3), np.array([0.0, 0.1 * MODEL.dof_scale[1], 0.0])
    assert np.linalg.norm(term.offsets(calm)[0:2]) == pytest.approx(60000.0)
    for k in range(1, 601):                                    # a minute of the rough load
        offset = term.offsets(rough)
        assert term.load == pytest.approx(0.1 * (1.0 - (1.0 - gain) ** k))
        beta = 0.0 if offset is None else np.linalg.norm(offset[0:2])
        assert beta == pytest.approx(60000.0 * fade(term.load, 0.03, 0.06))
    assert 0.06 < term.load < 0.065 and offset is None         # 1 - 1/e of the step
    off = Model.build(vehicle_from_parameters({**PARAMETERS, "bias.enabled": False}), 0.1)
    term.configure(off)
    assert term.load is None                                   # off: the filter starts again


def test_no_offset_while_the_bias_is_off():
    off = Model.build(vehicle_from_parameters({**PARAMETERS, "bias.enabled": False}), 0.1)
    assert bias(model=off).offsets(np.zeros(3)) is None
