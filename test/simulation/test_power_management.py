"""The power management system's power available after a fault (held, then the floor and the
ramp, MarPowSim's PowerAvailable) and the fast load reduction's limits (the reduced level after
the reaction time, the restore ramp, the frequency rule)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from allocator_pkg.simulation.power_management import (
    Fault,
    LoadReduction,
    LoadReductionSpec,
    PowerAvailableReport,
    PowerManagementSpec,
)

BUS = ("swbd_3",)


@given(st.floats(0.1, 5.0), st.floats(5.0, 90.0), st.floats(-3000.0, 5000.0), st.floats(5000.0, 20000.0))
def test_the_reported_power_rises_from_the_floor_at_the_rated_power_over_the_ramp_time(reaction, ramp, floor, rated):
    report = PowerAvailableReport(PowerManagementSpec(reaction, ramp))
    report.faults.append(Fault(100.0, {BUS: floor}, {}, {}))
    available = 1e9                                     # the hold binds throughout
    assert report.bus(BUS, available, rated, 100.0 + reaction * 0.5) == available
    for dt in (0.0, 1.0, 3.0):
        expected = max(floor + rated * dt / ramp, 0.0)
        assert report.bus(BUS, available, rated, 100.0 + reaction + dt) == pytest.approx(expected, abs=1e-6)
    assert report.bus(("other",), 700.0, rated, 100.0 + reaction + 1.0) == 700.0


def spec(**changes) -> LoadReductionSpec:
    values = dict(enabled=True, reaction_time=0.2, restore_time=5.0, frequency_start=0.97, frequency_zero=0.9)
    return LoadReductionSpec(**(values | changes))


@pytest.mark.parametrize("reaction, restore", [(0.2, 5.0), (0.1, 2.0), (0.0, 10.0)])
def test_a_trip_signal_cuts_after_the_reaction_and_restores_along_the_ramp(reaction, restore):
    rated = np.array([5000.0, 5000.0, 4000.0])
    reduction = LoadReduction(spec(reaction_time=reaction, restore_time=restore), rated)
    reduction.pending.append(Fault(10.0, {}, {0: 800.0, 1: 1200.0}, {}))
    dt, seen = 0.05, []
    for k in range(1, round(20.0 / dt)):
        time = 10.0 + k * dt
        reduction.update(time, dt, np.zeros(3), {}, {})
        seen.append((time, reduction.limit.copy()))
    before = [limit for time, limit in seen if time < 10.0 + reaction - 1e-9]
    assert all(np.isinf(limit).all() for limit in before)
    first = next(limit for time, limit in seen if time >= 10.0 + reaction - 1e-9)
    assert first[:2] == pytest.approx([800.0, 1200.0]) and math.isinf(first[2])
    rising = [(time, limit[0]) for time, limit in seen if np.isfinite(limit[0])]
    slope = (rising[-1][1] - rising[1][1]) / (rising[-1][0] - rising[1][0])
    assert slope == pytest.approx(5000.0 / restore, rel=1e-9)
    assert np.isinf(seen[-1][1]).all()                   # back at rated: no limit
    assert rising[-1][0] == pytest.approx(10.0 + reaction + (5000.0 - 800.0) / 5000.0 * restore, abs=dt + 1e-9)


@given(st.floats(0.9, 0.97, exclude_max=True), st.floats(0.0, 5000.0))
def test_below_the_start_frequency_the_limit_follows_the_frequency(frequency, power):
    reduction = LoadReduction(spec(), np.array([5000.0, 5000.0]))
    reduction.update(1.0, 0.1, np.array([power, power]), {BUS: frequency}, {BUS: [1]})
    assert math.isinf(reduction.limit[0])
    assert reduction.limit[1] == pytest.approx(power * (frequency - 0.9) / 0.07, abs=1e-6)


def test_the_limit_is_taken_against_the_power_when_the_frequency_first_fell():
    reduction = LoadReduction(spec(), np.array([5000.0]))
    reduction.update(1.0, 0.1, np.array([3000.0]), {BUS: 0.95}, {BUS: [0]})
    reduction.update(1.1, 0.1, np.array([100.0]), {BUS: 0.935}, {BUS: [0]})
    assert reduction.limit[0] == pytest.approx(3000.0 * 0.5)


def test_off_it_limits_nothing():
    reduction = LoadReduction(spec(enabled=False), np.array([5000.0]))
    reduction.pending.append(Fault(0.0, {}, {0: 0.0}, {}))
    reduction.update(1.0, 0.1, np.array([3000.0]), {BUS: 0.91}, {BUS: [0]})
    assert math.isinf(reduction.limit[0])
