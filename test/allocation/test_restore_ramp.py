"""The restore ramp (allocation/restore_ramp.py, ``power.restore_ramp``; docs/power.md): the
available power in use falls at once and rises at capacity / T per second, by hand for a source
and through the allocator (its slope per sample, the thrust bound rising with it, a group fault
cleared), and over random sequences of targets and times."""

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg import Allocator, ConfigError
from allocator_pkg.allocation.restore_ramp import RestoreRamp

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
CAPACITY = np.array([5600.0, 7800.0])


def test_a_drop_holds_at_once_and_the_power_comes_back_at_capacity_over_t():
    """T = 10 s: swbd_a rises at 5600 / 10 = 560 kW/s, swbd_b at 780 kW/s."""
    ramp = RestoreRamp(CAPACITY, 10.0)
    full = CAPACITY.copy()
    ramp.follow(full)
    ramp.follow(np.array([0.0, 7800.0]))
    np.testing.assert_array_equal(ramp.in_use(full), [0.0, 7800.0])
    for step in range(1, 120):
        ramp.advance(full, 0.1)
        assert ramp.in_use(full)[0] == pytest.approx(min(5600.0, 56.0 * step), abs=1e-9)
    assert not ramp.rising(full)
    ramp.follow(np.array([1000.0, 2000.0]))
    np.testing.assert_array_equal(ramp.in_use(np.array([1000.0, 2000.0])), [1000.0, 2000.0])


def test_without_a_ramp_the_power_is_the_target_at_once():
    ramp = RestoreRamp(CAPACITY, 0.0)
    ramp.follow(np.array([0.0, 0.0]))
    np.testing.assert_array_equal(ramp.in_use(CAPACITY), CAPACITY)
    assert not ramp.advance(CAPACITY, 1.0)


@settings(deadline=None, max_examples=80)
@given(st.lists(st.tuples(st.floats(0.0, 9000.0), st.floats(0.0, 9000.0), st.floats(0.001, 2.0)), min_size=1,
                max_size=30), st.floats(0.5, 60.0))
def test_the_power_in_use_never_rises_faster_than_the_ramp_nor_above_its_target(steps, seconds):
    ramp = RestoreRamp(CAPACITY, seconds)
    target = CAPACITY.copy()
    ramp.follow(target)
    for a, b, dt in steps:
        before = ramp.in_use(target)
        target = np.array([a, b])
        ramp.follow(target)
        dropped = ramp.in_use(target)
        assert np.all(dropped <= target) and np.all(dropped <= before)
        ramp.advance(target, dt)
        after = ramp.in_use(target)
        assert np.all(after <= target + 1e-9)
        assert np.all(after - dropped <= CAPACITY / seconds * dt * (1.0 + 1e-12) + 1e-9)
        assert np.all((after == target) | (after - dropped >= CAPACITY / seconds * dt * (1.0 - 1e-9)))


def test_the_allocator_raises_the_power_in_use_one_sample_period_a_sample():
    """dp_vessel at 10 Hz with T = 20 s: swbd_a down to 500 kW holds at once; back at 5600 kW it
    rises 5600 / 20 x 0.1 = 28 kW a sample, the power row of qp with it, and azimuth_stbd's
    proportional bound: while the use u is below its consumers' largest draw
    D = 0.0074 x 420000^1.5 + 0.0113 x 300000^1.5 W, the bound is 420 kN (u / D)^(2/3)."""
    allocator = Allocator(vehicle_from(DP_VESSEL, power__restore_ramp=20.0))
    allocator.set_available_power({"swbd_a": 500.0})
    assert allocator.power.available[0] == 500.0
    allocator.set_available_power({"swbd_a": 5600.0})
    assert allocator.power.available[0] == 500.0
    demand = 0.0074 * 420e3 ** 1.5 + 0.0113 * 300e3 ** 1.5
    for sample in range(1, 60):
        allocator.allocate([0, 0, 0, 0, 0, 0])
        used = allocator.power.available[0]
        assert used == pytest.approx(500.0 + 28.0 * sample, abs=1e-6)
        limit = allocator.power_limit
        assert limit.rows.available[0] == pytest.approx(used * 1e3, rel=1e-12)
        assert limit.proportional[0] == pytest.approx(420e3 * (used * 1e3 / demand) ** (2 / 3), rel=1e-9)


def test_a_cleared_group_fault_comes_back_along_the_ramp():
    allocator = Allocator(vehicle_from(DP_VESSEL, power__restore_ramp=10.0))
    allocator.set_group_fault("switchboard_b")
    assert allocator.power.available[1] == 0.0
    allocator.clear_faults()
    assert allocator.power.available[1] == 0.0
    for sample in range(1, 5):
        allocator.allocate([0, 0, 0, 0, 0, 0])
        assert allocator.power.available[1] == pytest.approx(78.0 * sample, abs=1e-6)


def test_a_ramp_longer_than_ten_minutes_is_refused():
    with pytest.raises(ConfigError) as error:
        vehicle_from(DP_VESSEL, power__restore_ramp=601.0)
    assert error.value.problems == [("power.restore_ramp", "must be <= 600, got 601")]
