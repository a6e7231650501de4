"""The limits stage: static ranges under faults, and the rate windows around the last thrust."""

import numpy as np
import pytest
from conftest import ROOT, vehicle_from

from allocator_pkg import Allocator, FaultMode

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


def test_rate_limits_narrow_the_static_range_around_the_last_thrust():
    vehicle = vehicle_from(EXAMPLE)
    alloc = Allocator(vehicle)
    for _ in range(50):
        alloc.allocate([300.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    before = alloc.thrust
    limits = alloc._limits.sample(np.array([0.0, 0.0, 0.0]), alloc._state)
    dt = 1.0 / vehicle.rate_hz
    for i, actuator in enumerate(vehicle.actuators):
        if actuator.rotatable:
            continue
        step = actuator.thrust_rate_max * dt
        assert limits.low[i] == pytest.approx(max(before[i] - step, actuator.thrust_min))
        assert limits.high[i] == pytest.approx(min(before[i] + step, actuator.thrust_max))


def test_faults_shape_the_static_ranges():
    vehicle = vehicle_from(EXAMPLE)
    alloc = Allocator(vehicle)
    port, stbd = vehicle.names.index("main_port"), vehicle.names.index("main_stbd")
    alloc.set_fault("main_port", FaultMode.FAILED)
    alloc.set_fault("main_stbd", FaultMode.DEGRADED, efficiency=0.4)
    low, high = alloc.ranges
    assert (low[port], high[port]) == (0.0, 0.0)
    stbd_config = vehicle.actuators[stbd]
    assert (low[stbd], high[stbd]) == pytest.approx((0.4 * stbd_config.thrust_min, 0.4 * stbd_config.thrust_max))
    version = alloc._limits.version
    alloc.clear_faults()
    assert alloc._limits.version == version + 1
    assert alloc.ranges[1][port] == stbd_config.thrust_max
