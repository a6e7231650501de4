"""The power rule in a sample (allocation/power_stage.py, docs/power.md): a drop of available
power held from the next sample (phase-back) or, without phase-back, the thrust down at its rate
limit with the status saying so; a saturated request under a short source settles at the exact
optimum of the power constraint without hunting, in one solve a sample; with no fault and no
change of power no thruster moves by more than its rate step (a property)."""

from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT, bench_module, vehicle_from
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg import Allocator

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
PLAIN_VESSEL = vehicle_from(DP_VESSEL)
SPLIT_VESSEL = vehicle_from(DP_VESSEL, actuators__azimuth_stbd__feeds=["swbd_a", "swbd_b"],
                            actuators__azimuth_stbd__feed_shares=[0.7, 0.3])
OVER = 0.01
"""A source may be asked for at most 1 % more than it has (rounding)."""


def test_the_next_sample_respects_a_drop_of_available_power_faster_than_the_rate_limit():
    allocator = Allocator(vehicle_from(DP_VESSEL))
    tau = [4e5, 0.0, 0.0, 0.0, 0.0, 0.0]
    for _ in range(100):
        result = allocator.allocate(tau)
    before = result.thrust.copy()
    allocator.set_available_power({"swbd_a": 300.0, "swbd_b": 500.0})
    result = allocator.allocate(tau)
    draw = allocator.power.draw(result.thrust, allocator.power_limit)
    assert np.all(draw <= np.array([300.0, 500.0]) * (1 + OVER))
    assert np.max(before - result.thrust) > allocator.vehicle.actuators[0].thrust_rate_max * allocator.dt
    assert allocator.power.reading(result.thrust, allocator.power_limit).limited


def test_without_phase_back_the_thrust_comes_down_at_its_rate_limit_and_the_status_says_so():
    allocator = Allocator(vehicle_from(DP_VESSEL, power__phase_back=False))
    tau = [4e5, 0.0, 0.0, 0.0, 0.0, 0.0]
    for _ in range(100):
        result = allocator.allocate(tau)
    step = np.array([a.thrust_rate_max for a in allocator.vehicle.actuators]) * allocator.dt
    allocator.set_available_power({"swbd_a": 300.0, "swbd_b": 500.0})
    has = np.array([300.0, 500.0])
    over = []
    for _ in range(60):
        before = result.thrust
        result = allocator.allocate(tau)
        assert np.all(np.abs(result.thrust - before) <= step * (1 + 1e-9))
        draw = allocator.power.draw(result.thrust, allocator.power_limit)
        over.append(bool(np.any(draw > has * (1 + OVER))))
        if over[-1]:
            assert allocator.power.reading(result.thrust, allocator.power_limit).limited
    assert over[0] and not over[-1]                      # over while it comes down, then inside
    assert over == sorted(over, reverse=True)            # and never over again


def test_a_saturated_surge_uses_the_power_the_source_has_as_far_as_the_exact_optimum():
    """The same vessel asked for 400 kN of surge, more than it can give: the settled sample draws
    the 1000 kW (less the chords' overestimate) and reaches the surge of the exact optimum under
    the power constraint (scipy SLSQP over thrust and angle, bench/power_use.py) to 1 %. By hand:
    pure surge from azimuth_stbd (x = -41.5 m, y = 7 m) and tunnel_fwd (x = 37 m) needs the
    tunnel's T = -F_y of the azimuth and -41.5 F_y - 7 F_x + 37 T = 0, so F_y = -7 F_x / 78.5; the 1000 kW then give
    F_x^1.5 (0.0074 (1 + (7 / 78.5)^2)^0.75 + 0.0113 (7 / 78.5)^1.5) = 1e6 W: F_x = 255.5 kN."""
    allocator = Allocator(vehicle_from(DP_VESSEL))
    allocator.set_group_fault("switchboard_b")
    allocator.set_available_power({"swbd_a": 1000.0})
    settled = []
    for _ in range(150):
        result = allocator.allocate([4e5, 0.0, 0.0, 0.0, 0.0, 0.0])
        settled = [*settled[-19:], result.thrust]
    assert np.ptp(settled, axis=0) == pytest.approx(np.zeros(4), abs=1.0)         # steady: no hunting
    draw = allocator.power.draw(result.thrust, allocator.power_limit)[0]
    assert 990.0 <= draw <= 1000.0 * (1 + OVER)
    best = bench_module("power_use").reference_scale(allocator, np.array([1.0, 0.0, 0.0])) * 1e6
    lever = 7.0 / 78.5
    assert best == pytest.approx((1e6 / (0.0074 * (1 + lever ** 2) ** 0.75 + 0.0113 * lever ** 1.5)) ** (2 / 3),
                                 rel=1e-4)
    assert result.achieved[0] >= 0.99 * best


@st.composite
def power_limited_runs(draw):
    """A DP vessel (single or 70/30 split feeds) at random available power, and a run of
    random requests each held for a random number of samples."""
    split = draw(st.booleans())
    available = {s: draw(st.floats(50.0, c)) for s, c in (("swbd_a", 5600.0), ("swbd_b", 7800.0))}
    requests = draw(st.lists(st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(-1.0, 1.0),
                                       st.integers(1, 8)), min_size=3, max_size=8))
    return split, available, requests


@settings(deadline=None, max_examples=40)
@given(power_limited_runs())
def test_with_no_fault_and_no_change_of_power_no_thruster_moves_by_more_than_its_rate_step(run):
    """The power in the optimisation: no bounds move between samples, so the rate limit holds
    in every sample of every run (40 runs of up to 64 samples)."""
    split, available, requests = run
    allocator = Allocator(SPLIT_VESSEL if split else PLAIN_VESSEL)
    allocator.set_available_power(available)
    step = allocator.model.thrust_step
    previous = allocator.thrust
    for x, y, n, held in requests:
        tau = [6e5 * x, 4e5 * y, 0.0, 0.0, 0.0, 2e7 * n]
        for _ in range(held):
            thrust = allocator.allocate(tau).thrust
            assert np.all(np.abs(thrust - previous) <= step * (1 + 1e-9) + 1e-6), (thrust - previous, step)
            previous = thrust


def test_what_does_not_change_the_power_changes_no_sample():
    """A speed sent every sample (as odometry does) changes neither the available power nor
    the feeds: the power-limited samples go on as without it."""
    plain, with_speed = (Allocator(vehicle_from(DP_VESSEL)) for _ in range(2))
    for allocator in (plain, with_speed):
        allocator.set_group_fault("switchboard_b")
        allocator.set_available_power({"swbd_a": 1000.0})
    for k in range(120):
        tau = [4e5, 1e5 * np.sin(0.05 * k), 0.0, 0.0, 0.0, 2e6]
        with_speed.set_speed(0.0)
        a, b = plain.allocate(tau), with_speed.allocate(tau)
        assert np.array_equal(a.thrust, b.thrust) and np.array_equal(a.azimuth, b.azimuth)


def test_a_switch_of_method_mid_ramp_keeps_the_thrust_at_its_rate_limit_down_to_the_power():
    vehicle = vehicle_from(DP_VESSEL, power__phase_back=False)
    allocator = Allocator(vehicle)
    tau = [4e5, 0.0, 0.0, 0.0, 0.0, 0.0]
    for _ in range(100):
        result = allocator.allocate(tau)
    step = np.array([a.thrust_rate_max for a in allocator.vehicle.actuators]) * allocator.dt
    allocator.set_available_power({"swbd_a": 300.0, "swbd_b": 500.0})
    result = allocator.allocate(tau)
    allocator.reconfigure(replace(vehicle, method="pseudoinverse"))
    for _ in range(60):
        before = result.thrust
        result = allocator.allocate(tau)
        assert np.all(np.abs(result.thrust - before) <= step * (1 + 1e-9))
    draw = allocator.power.draw(result.thrust, allocator.power_limit)
    assert np.all(draw <= np.array([300.0, 500.0]) * (1 + OVER))
