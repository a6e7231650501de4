"""A generator set's governor: the droop reference, the first-order lag, the turbocharged
engine's load acceptance (a step of ``step_allowance``, then ``ramp_max``), its limits, and the
breaker."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from allocator_pkg.simulation.generator_set import GeneratorSet, GeneratorSetSpec


def spec(**changes) -> GeneratorSetSpec:
    values = dict(name="g", switchboard="a", rating=9100.0, power_factor=0.85, inertia=2.4054, droop=0.02,
                  governor_time_constant=0.5, p_max=1.1, step_allowance=0.19882, ramp_max=0.08109741,
                  under_frequency=0.9, over_frequency=1.1, trip_delay=0.1)
    return GeneratorSetSpec(**(values | changes))


@given(st.floats(0.005, 0.1), st.floats(0.9, 1.1))
def test_the_droop_reference_is_nominal_frequency_at_half_load(droop, frequency):
    s = spec(droop=droop, p_max=100.0)
    g = GeneratorSet(s)
    assert g.reference(1.0) == pytest.approx(0.5)
    assert g.reference(frequency) == pytest.approx(max(0.0, 0.5 + (1.0 - frequency) / droop))


@pytest.mark.parametrize("allowance, ramp", [(0.19882, 0.08109741), (0.1, 0.05), (0.3, 0.2)])
@pytest.mark.parametrize("start", [0.2, 0.4])
def test_load_acceptance_is_a_step_then_the_ramp(allowance, ramp, start):
    g = GeneratorSet(spec(step_allowance=allowance, ramp_max=ramp, governor_time_constant=0.05), load=start)
    dt, power = 0.005, []
    for _ in range(round(3.0 / dt)):
        g.advance(0.9, dt)                            # the reference far above: p_max
        power.append(g.p_m)
    power = np.array(power)
    t = dt * np.arange(1, len(power) + 1)
    assert power[round(0.5 / dt)] == pytest.approx(start + allowance + ramp * 0.5, abs=ramp * 0.02 + 1e-3)
    late = (t > 1.0) & (power < 1.05)                # clear of the lag onto p_max
    slope = np.polyfit(t[late], power[late], 1)[0]
    assert slope == pytest.approx(ramp, rel=0.01)


def test_the_lag_is_first_order_below_the_allowance():
    g = GeneratorSet(spec(governor_time_constant=0.5), load=0.5)
    for _ in range(100):                               # 0.5 s = T toward 0.5 + 0.002 / 0.02
        g.advance(0.998, 0.005)
    target = g.reference(0.998)
    assert target - 0.5 == pytest.approx(0.1)
    assert g.p_m == pytest.approx(target - 0.1 * math.exp(-1.0), rel=1e-9)


def test_power_stays_within_the_engine():
    g = GeneratorSet(spec(), load=1.0)
    for _ in range(2000):
        g.advance(0.5, 0.005)
    assert g.p_m == pytest.approx(1.1)
    for _ in range(2000):
        g.advance(1.5, 0.005)
    assert g.p_m == pytest.approx(0.0, abs=1e-6) and g.p_m >= 0.0


def test_a_disconnected_set_gives_nothing_and_stays_off():
    g = GeneratorSet(spec(), load=0.6)
    g.disconnect(12.5)
    g.advance(0.95, 0.005)
    assert (g.connected, g.p_m, g.tripped_at) == (False, 0.0, 12.5)
    assert not g.protect(0.5, 1.0, 13.0)
    assert GeneratorSet(spec(connected=False)).p_m == 0.0
