"""Faults and static ranges: validation, the per-actuator arrays, and the ranges the
allocator and the capability analysis share (numbers derived by hand from the files)."""

import math

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg import Fault, FaultMode, FaultSet, load_vehicle
from allocator_pkg.effectiveness.faults import static_ranges

EXAMPLE = ROOT / "config" / "example1_rov.yaml"
INFANTE = ROOT / "config" / "infante_auv.yaml"


def test_arrays_of_a_fault_set():
    vehicle = load_vehicle(EXAMPLE)          # azimuth_fwd, azimuth_aft, main_port, main_stbd
    faults = (FaultSet(vehicle).with_fault("main_port", FaultMode.DEGRADED, efficiency=0.4)
              .with_fault("main_stbd", FaultMode.FAILED).with_fault("azimuth_aft", FaultMode.STUCK, angle=0.7))
    assert faults.efficiency.tolist() == [1.0, 1.0, 0.4, 0.0]
    assert faults.command_efficiency.tolist() == [1.0, 1.0, 0.4, 1.0]
    assert faults.stuck == {1: 0.7}
    assert faults.modes.tolist() == [0, 3, 1, 2]
    assert faults.with_fault("main_stbd", FaultMode.NOMINAL).modes.tolist() == [0, 3, 1, 0]
    assert faults.cleared().faults == {}


@pytest.mark.parametrize("name, mode, values, message", [
    ("nope", FaultMode.FAILED, {}, "unknown actuator 'nope'; actuators: azimuth_fwd, azimuth_aft"),
    ("main_port", 9, {}, "unknown fault mode 9; modes: NOMINAL=0, DEGRADED=1, FAILED=2, STUCK=3"),
    ("main_port", FaultMode.DEGRADED, {"efficiency": 1.5}, r"efficiency in \(0, 1\], got 1.5"),
    ("main_port", FaultMode.DEGRADED, {}, r"efficiency in \(0, 1\], got None"),
    ("main_port", FaultMode.STUCK, {"angle": 0.1}, "these can be stuck: azimuth_fwd, azimuth_aft"),
    ("azimuth_fwd", FaultMode.STUCK, {"angle": math.nan}, "STUCK needs a finite angle"),
])
def test_invalid_faults_are_refused_and_leave_the_set_as_it_was(name, mode, values, message):
    faults = FaultSet(load_vehicle(EXAMPLE)).with_fault("main_stbd", FaultMode.FAILED)
    with pytest.raises(ValueError, match=message):
        faults.with_fault(name, mode, **values)
    assert faults.modes.tolist() == [0, 0, 0, 2]


def test_a_fault_set_from_bare_modes():
    vehicle = load_vehicle(EXAMPLE)
    faults = FaultSet.of(vehicle, {"main_port": FaultMode.FAILED, "azimuth_fwd": FaultMode.STUCK,
                                   "main_stbd": Fault(FaultMode.DEGRADED, efficiency=0.5)})
    assert faults.stuck == {0: 0.0} and faults.efficiency.tolist() == [1.0, 1.0, 0.0, 0.5]
    with pytest.raises(ValueError, match="efficiency"):
        FaultSet.of(vehicle, {"main_port": FaultMode.DEGRADED})


def test_static_ranges_of_thrusters_scale_with_efficiency():
    vehicle = load_vehicle(EXAMPLE)          # azimuths 150 N; mains 300 N ahead, 200 N astern
    faults = FaultSet(vehicle).with_fault("main_port", FaultMode.DEGRADED, efficiency=0.5) \
        .with_fault("azimuth_aft", FaultMode.FAILED)
    low, high = static_ranges(vehicle, faults, speed=0.0)
    assert low.tolist() == [0.0, 0.0, -100.0, -200.0]
    assert high.tolist() == [150.0, 0.0, 150.0, 300.0]


def test_static_ranges_of_control_surfaces_follow_the_speed_and_a_stuck_deflection():
    vehicle = load_vehicle(INFANTE)
    rudder = vehicle.names.index("rudder_port")
    surface = vehicle.actuators[rudder].surface
    speed = 2.0
    flow = speed * (surface.wake_speed_factor if surface.flow == "propeller_wake" else 1.0)
    k_lift = 0.5 * vehicle.water_density * surface.area * flow ** 2 * surface.lift_coefficient      # (1.48)
    low, high = static_ranges(vehicle, FaultSet(vehicle), speed)
    assert high[rudder] == pytest.approx(k_lift * surface.deflection_max) and low[rudder] == -high[rudder]
    stuck = FaultSet(vehicle).with_fault("rudder_port", FaultMode.STUCK, angle=0.1)
    low, high = static_ranges(vehicle, stuck, speed)
    assert low[rudder] == high[rudder] == pytest.approx(k_lift * 0.1)
    low, high = static_ranges(vehicle, FaultSet(vehicle), 0.0)
    assert low[rudder] == high[rudder] == 0.0
    assert np.all(high[[i for i, a in enumerate(vehicle.actuators) if not a.is_surface]] > 0.0)
