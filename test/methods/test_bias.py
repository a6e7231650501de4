"""Thrust bias in method qp's objective, judged against the closed form of the biased
problem: the wrench stays the one requested, each pair's forces differ from the unbiased
allocation by the opposed offsets of bias.thrust, every limit is kept, and switching the bias,
its thrust or its pairs updates the solver without a new set-up."""

from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg import Allocator, FaultMode, read_parameters, vehicle_from_parameters
from allocator_pkg.effectiveness.sectors import in_forbidden_sector

PARAMETERS = {**read_parameters(ROOT / "config" / "dp_vessel.yaml"), "bias.enabled": True}
NAMES = PARAMETERS["actuators.names"]
FREE = {**PARAMETERS, **{f"actuators.{name}.thrust_rate_max": 0.0 for name in NAMES},
        **{f"actuators.{name}.azimuth_rate_max": 0.0 for name in NAMES[:2]}}
"""dp_vessel without rate limits: each sample reaches the optimum of its request."""
BIAS = 60000.0
DOFS = [0, 1, 5]
SOLVED = 50.0
"""[N, N m] How far two solves of OSQP (eps_abs 1e-5 of a 655 kN range) may lie apart: 0.1 % of the bias."""


def extended(result) -> np.ndarray:
    """The body-frame extended force (1.16) of a result: each azimuth's (x, y), each tunnel's."""
    azimuths = [(f * np.cos(a), f * np.sin(a)) for f, a in zip(result.thrust[:2], result.azimuth[:2])]
    return np.concatenate([*azimuths, result.thrust[2:]])


def closed_form(allocator: Allocator, tau: np.ndarray, offset: np.ndarray) -> np.ndarray:
    """argmin (f - b)'W(f - b) subject to T_e f = tau, by numpy: b + W^-1 T'(T W^-1 T')^-1 (tau - T b)."""
    t, w = allocator.model.t_ec, allocator.model.weight_ext
    gain = (t / w).T @ np.linalg.inv((t / w) @ t.T)
    return offset + gain @ (tau[DOFS] - t @ offset)


def requests():
    """Calm-weather requests, below bias.fade_start (3 % of each DOF's authority): up to 2.3 % of
    surge's, 2.4 % of sway's and 1.4 % of yaw's."""
    return st.tuples(st.floats(-2.5e4, 2.5e4), st.floats(-4.0e4, 4.0e4), st.floats(-1.0e6, 1.0e6)).map(
        lambda x: np.array([x[0], x[1], 0.0, 0.0, 0.0, x[2]]))


@settings(deadline=None, max_examples=25)
@given(tau=requests())
def test_the_wrench_is_the_one_asked_and_the_pair_pushes_apart_by_the_bias(tau):
    biased = Allocator(vehicle_from_parameters(FREE))
    for _ in range(5):
        result = biased.allocate(tau)
    assert result.achieved[DOFS] == pytest.approx(tau[DOFS], abs=SOLVED)
    assert not result.saturated
    offset = np.array([0.0, -BIAS, 0.0, BIAS, 0.0, 0.0])
    force = extended(result)
    assert force == pytest.approx(closed_form(biased, tau, offset), abs=SOLVED)
    # the same as the optimum without bias, the pair pushing apart by bias.thrust each
    assert force - closed_form(biased, tau, np.zeros(6)) == pytest.approx(offset, abs=SOLVED)


@settings(deadline=None, max_examples=30)
@given(tau=st.tuples(st.floats(-1.2e6, 1.2e6), st.floats(-1.8e6, 1.8e6), st.floats(-6e7, 6e7)),
       scale=st.sampled_from([0.05, 0.2, 1.0]), thrust=st.floats(1.0e4, 4.1e5), fade_end=st.floats(0.05, 1.0))
def test_the_bias_costs_no_capability_and_keeps_every_limit(tau, scale, thrust, fade_end):
    """Whatever the bias and the fade, a request the allocation meets without bias is met with
    it once both have settled (a thruster may have to turn through a forbidden sector at zero
    thrust first), inside every thrust limit and outside the forbidden sectors."""
    vehicle = vehicle_from_parameters({**FREE, "bias.thrust": thrust, "bias.fade_start": 0.0,
                                       "bias.fade_end": fade_end})
    biased = Allocator(vehicle)
    plain = Allocator(vehicle_from_parameters({**FREE, "bias.enabled": False}))
    request = scale * np.array([tau[0], tau[1], 0.0, 0.0, 0.0, tau[2]])
    for _ in range(60):
        with_bias, without = biased.allocate(request), plain.allocate(request)
    if not without.saturated:
        assert np.all(np.abs(with_bias.achieved[DOFS] - request[DOFS]) <= biased.dof_tolerance)
    assert np.all(with_bias.thrust >= biased.ranges[0] - 1e-6) and np.all(with_bias.thrust <= biased.ranges[1] + 1e-6)
    for i, actuator in enumerate(vehicle.actuators[:2]):
        assert with_bias.thrust[i] <= 1e-6 or not in_forbidden_sector(actuator.rotation, with_bias.azimuth[i])


def test_a_pair_with_a_failed_thruster_pushes_none():
    biased = Allocator(vehicle_from_parameters(FREE))
    plain = Allocator(vehicle_from_parameters({**FREE, "bias.enabled": False}))
    tau = np.array([2e4, 1e4, 0, 0, 0, 5e5])
    for allocator in (biased, plain):
        allocator.set_fault("azimuth_port", FaultMode.FAILED)
        for _ in range(5):
            result = allocator.allocate(tau)
    assert extended(biased.allocate(tau)) == pytest.approx(extended(result), abs=SOLVED)
    biased.clear_faults()
    for _ in range(5):
        result = biased.allocate(tau)
    assert np.linalg.norm(extended(result)[0:2]) > 0.5 * BIAS           # back with the thruster


def test_switching_the_bias_updates_the_solver_without_a_new_setup():
    vehicle = vehicle_from_parameters(FREE)
    allocator = Allocator(vehicle)
    plain = Allocator(vehicle_from_parameters({**FREE, "bias.enabled": False}))
    tau = np.array([2e4, -1e4, 0, 0, 0, -3e5])
    setups = allocator.stats.solver_setups
    for bias in (replace(vehicle.bias, enabled=False), replace(vehicle.bias, thrust=1e5), vehicle.bias,
                 replace(vehicle.bias, pairs=(("azimuth_port", "azimuth_stbd"),)),
                 replace(vehicle.bias, enabled=False)):
        allocator.reconfigure(replace(vehicle, bias=bias))
        for _ in range(5):
            result = allocator.allocate(tau)
        force = extended(result)
        beta = bias.thrust if bias.enabled else 0.0
        offset = np.array([0.0, -beta, 0.0, beta, 0.0, 0.0])
        assert force == pytest.approx(closed_form(allocator, tau, offset), abs=SOLVED), bias
    assert allocator.stats.solver_setups == setups
    for _ in range(5):
        reference = plain.allocate(tau)
    assert extended(result) == pytest.approx(extended(reference), abs=SOLVED)          # its own q again


def test_above_the_fade_the_allocation_is_the_unbiased_one():
    biased = Allocator(vehicle_from_parameters(FREE))
    plain = Allocator(vehicle_from_parameters({**FREE, "bias.enabled": False}))
    tau = np.array([0.25 * biased.model.dof_scale[0], 0, 0, 0, 0, 0])              # a load of 25 %
    for _ in range(5):
        with_bias, without = biased.allocate(tau), plain.allocate(tau)
    assert extended(with_bias) == pytest.approx(extended(without), abs=SOLVED)
