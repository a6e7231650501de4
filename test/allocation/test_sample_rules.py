"""The node's rules for each sample: the stale-input watchdog on nanosecond stamps, the float32
supply voltage, what a fault request carries, the available power, the consequence period."""

import math

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.allocation.allocator import Allocator
from allocator_pkg.allocation.sample_rules import (
    Watchdog,
    consequence_period,
    fault_request,
    set_available_power,
    set_fault,
    set_supply_voltage,
)
from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.effectiveness.faults import FaultMode

BLUEROV = load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml")
VESSEL = load_vehicle(ROOT / "config" / "dp_vessel.yaml")

S = 10**9


def test_stale_before_any_input_after_the_timeout_and_never_when_disabled():
    watchdog = Watchdog(0.5)
    assert watchdog.check(1 * S, None) == (True, ("info", "waiting for wrench_command: commanding zero thrust"))
    assert watchdog.check(2 * S, None) == (True, None)                     # said once per change
    assert watchdog.check(2 * S, 2 * S) == (False, ("info", "wrench input resumed"))
    assert watchdog.check(2 * S + S // 2, 2 * S) == (False, None)         # exactly the timeout: not yet
    assert watchdog.check(2 * S + S // 2 + 1, 2 * S) == \
        (True, ("warn", "no valid wrench for 0.5 s: commanding zero thrust"))
    watchdog.timeout = 0.0
    assert watchdog.check(100 * S, 2 * S) == (False, ("info", "wrench input resumed"))


def test_the_voltage_is_the_float32_of_the_message_and_a_refused_one_leaves_the_last():
    allocator = Allocator(BLUEROV)
    set_supply_voltage(allocator, 15.3)
    assert allocator.voltage == float(np.float32(15.3)) != 15.3
    with pytest.raises(ValueError):
        set_supply_voltage(allocator, math.nan)
    assert allocator.voltage == float(np.float32(15.3))


def test_a_fault_request_carries_the_efficiency_of_degraded_and_the_angle_of_stuck_only():
    assert fault_request(FaultMode.DEGRADED, 0.4) == (0.4, 0.0)
    assert fault_request(FaultMode.STUCK, 0.3) == (0.0, 0.3)
    assert fault_request(FaultMode.FAILED, 0.7) == (0.0, 0.0)
    allocator = Allocator(VESSEL)
    assert set_fault(allocator, "azimuth_stbd", FaultMode.STUCK, *fault_request(FaultMode.STUCK, 0.3)) == \
        "azimuth_stbd: STUCK from the next sample"
    assert allocator.faults["azimuth_stbd"].angle == 0.3


def test_available_power_is_refused_whole_when_the_lists_differ():
    allocator = Allocator(VESSEL)
    with pytest.raises(ValueError, match="2 sources but 1 values"):
        set_available_power(allocator, ["swbd_a", "swbd_b"], [500.0])
    set_available_power(allocator, ["swbd_a"], [450.0])
    assert allocator.power.reported[allocator.power.sources.index("swbd_a")] == 450.0


def test_the_consequence_period_and_rate_zero_off():
    assert consequence_period(1.0) == S
    assert consequence_period(4.0) == S // 4
    assert consequence_period(0.0) is None


def test_is_stale_answers_without_changing_what_check_reports():
    watchdog = Watchdog(0.5)
    assert watchdog.is_stale(1 * S, None) and watchdog.is_stale(2 * S + 1, S + S // 2)
    assert not watchdog.is_stale(2 * S, S + S // 2)
    assert watchdog.check(1 * S, None) == (True, ("info", "waiting for wrench_command: commanding zero thrust"))
