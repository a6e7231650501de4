"""The power rule in a sample (allocation/power_stage.py, docs/power.md): a drop of available
power held from the next sample (phase-back) or, without phase-back, the thrust down at its rate
limit with the status saying so; a short source's unused power shared again within the sample
up to the exact optimum under the power constraint, settled without hunting; the bounds carried
to the next sample keep every source within its available power."""

import numpy as np
import pytest
from conftest import ROOT, bench_module, vehicle_from

from allocator_pkg import Allocator

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
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
    """The same vessel asked for 400 kN of surge, more than it can give: the proportional
    bounds alone draw 539 kW of switchboard A's 1000; shared again, the settled sample draws the
    1000 kW and reaches the surge of the exact optimum under the power constraint (scipy SLSQP
    over thrust and angle, bench/power_use.py) to 1 %. By hand: pure surge from azimuth_stbd
    (x = -41.5 m, y = 7 m) and tunnel_fwd (x = 37 m) needs the tunnel's T = -F_y of the azimuth
    and -41.5 F_y - 7 F_x + 37 T = 0, so F_y = -7 F_x / 78.5; the 1000 kW then give
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


def test_the_bounds_carried_to_the_next_sample_keep_every_source_within_its_available_power():
    """A mean (in power) of the proportional bounds and the shared ones, each within the
    available power, is too; and a thruster whose bound rises comes up at its rate limit."""
    allocator = Allocator(vehicle_from(DP_VESSEL))
    allocator.set_group_fault("switchboard_b")
    allocator.set_available_power({"swbd_a": 1000.0})
    budget, limit = allocator.power, allocator.power_limit
    rng = np.random.default_rng(5)
    for _ in range(200):
        thrust = limit.bound * rng.uniform(0.0, 1.0, 4) * rng.choice([0.0, 1.0], 4, p=[0.2, 0.8])
        thrust[0] = limit.bound[0]
        shared = budget.shared(limit, limit.bound, thrust, np.ones(4, dtype=bool))
        if shared is None:
            continue
        relax = rng.uniform(0.0, 1.0)
        mean = (relax * limit.bound ** 1.5 + (1 - relax) * shared ** 1.5) ** (2 / 3)
        for bound in (shared, mean):
            assert budget.draw(np.where(np.isfinite(bound), bound, 0.0), limit)[0] <= 1000.0 * (1 + 1e-9)
    step = allocator.vehicle.actuators[0].thrust_rate_max * allocator.dt
    previous = allocator.allocate([4e5, 0.0, 0.0, 0.0, 0.0, 0.0]).thrust
    for _ in range(40):
        thrust = allocator.allocate([4e5, 0.0, 0.0, 0.0, 0.0, 0.0]).thrust
        assert abs(thrust[0] - previous[0]) <= step * (1 + 1e-9)
        previous = thrust


def test_what_does_not_change_the_power_keeps_the_shares_carried_over():
    """A speed sent every sample (as odometry does) changes neither the available power nor
    the feeds: the sharing carried from sample to sample goes on as without it."""
    plain, with_speed = (Allocator(vehicle_from(DP_VESSEL)) for _ in range(2))
    for allocator in (plain, with_speed):
        allocator.set_group_fault("switchboard_b")
        allocator.set_available_power({"swbd_a": 1000.0})
    for k in range(120):
        tau = [4e5, 1e5 * np.sin(0.05 * k), 0.0, 0.0, 0.0, 2e6]
        with_speed.set_speed(0.0)
        a, b = plain.allocate(tau), with_speed.allocate(tau)
        assert np.array_equal(a.thrust, b.thrust) and np.array_equal(a.azimuth, b.azimuth)
