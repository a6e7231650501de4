"""The diagnostics statuses as pure functions of the allocator, the counters and the input state."""

import numpy as np
import pytest
from conftest import ROOT
from diagnostic_msgs.msg import DiagnosticStatus

from allocator_pkg import Allocator, FaultMode, load_vehicle
from allocator_pkg.ros.diagnostics import Counters, diagnostic_statuses

EXAMPLE = ROOT / "config" / "example1_rov.yaml"
NODE = "/rov1/thrust_allocator"


def statuses(allocator, counters, stale=False, last=None, foreign=()):
    result = diagnostic_statuses(NODE, allocator, counters, stale, last, list(foreign))
    return result, [{kv.key: kv.value for kv in status.values} for status in result]


def test_ok_while_allocating_and_named_after_the_node():
    allocator = Allocator(load_vehicle(EXAMPLE))
    counters = Counters()
    last = allocator.allocate(np.zeros(6))
    counters.count(last)
    result, values = statuses(allocator, counters, last=last)
    assert [status.name for status in result] == [
        "/rov1/thrust_allocator: thrust allocation", "/rov1/thrust_allocator: actuator azimuth_fwd",
        "/rov1/thrust_allocator: actuator azimuth_aft", "/rov1/thrust_allocator: actuator main_port",
        "/rov1/thrust_allocator: actuator main_stbd"]
    assert {status.hardware_id for status in result} == {NODE}
    assert result[0].level == DiagnosticStatus.OK and result[0].message == "allocating"
    assert values[0]["samples in period"] == "1" and values[0]["mode main_port"] == "NOMINAL"
    assert values[0]["solver status"] == "solved" and values[0]["stale input"] == "false"
    assert all(status.level == DiagnosticStatus.OK for status in result[1:])
    assert result[3].message == "NOMINAL, 0 % of its limit"


def test_warn_on_faults_saturation_and_rejected_input_and_error_when_stale():
    allocator = Allocator(load_vehicle(EXAMPLE))
    allocator.set_fault("main_port", FaultMode.FAILED)
    counters = Counters(rejected_wrenches=2, rejected_in_period=2)
    last = allocator.allocate([1e6, 0.0, 0.0, 0.0, 0.0, 0.0])
    counters.count(last)
    result, values = statuses(allocator, counters, last=last)
    assert result[0].level == DiagnosticStatus.WARN
    # main_stbd alone pushes and turns the vehicle: the first sample's azimuths cannot cancel it yet
    assert result[0].message == "main_port FAILED; 1 saturated samples (short in surge, yaw); 2 rejected inputs"
    assert values[0]["mode main_port"] == "FAILED" and values[0]["rejected wrenches"] == "2"
    assert values[0]["short DOFs in period"] == "surge, yaw"
    result, _ = statuses(allocator, counters, stale=True)
    assert result[0].level == DiagnosticStatus.ERROR and result[0].message.startswith("stale wrench input")
    counters.reset_period()
    assert (counters.samples, counters.saturated, counters.rejected_in_period, counters.short) == (0, 0, 0, set())
    assert counters.rejected_wrenches == 2


def test_short_dofs_are_those_beyond_the_saturation_tolerance():
    allocator = Allocator(load_vehicle(EXAMPLE))
    result = allocator.allocate([1e6, 0.0, 0.0, 0.0, 0.0, 0.0])         # far more surge than there is
    assert result.saturated and result.short == ("surge",)
    for _ in range(200):                                                 # let the azimuths turn
        result = allocator.allocate([10.0, 10.0, 0.0, 0.0, 0.0, 1.0])
    assert not result.saturated and result.short == ()


def test_one_status_per_actuator_with_mode_efficiency_angle_and_fraction_of_its_limit():
    vehicle = load_vehicle(EXAMPLE)
    allocator = Allocator(vehicle)
    allocator.set_fault("main_port", FaultMode.FAILED)
    allocator.set_fault("main_stbd", FaultMode.DEGRADED, efficiency=0.5)
    allocator.set_fault("azimuth_fwd", FaultMode.STUCK, angle=0.3)
    for _ in range(100):                                                  # thrust rate limits: ramp up
        last = allocator.allocate([1e6, 0.0, 0.0, 0.0, 0.0, 0.0])
    result, values = statuses(allocator, Counters(), last=last)
    fwd, aft, port, stbd = result[1:]
    assert port.level == DiagnosticStatus.ERROR and port.message.startswith("FAILED")
    assert stbd.level == DiagnosticStatus.WARN and stbd.message.startswith("DEGRADED, efficiency 0.5")
    assert values[4]["efficiency"] == "0.5"
    limit = 0.5 * vehicle.actuator("main_stbd").thrust_max                        # all that is left
    thrust = float(values[4]["thrust [N]"])
    assert thrust == pytest.approx(limit, rel=2e-3)
    assert float(values[4]["fraction of limit"]) == pytest.approx(thrust / limit, abs=1e-3)
    assert values[4]["limits in force [N]"] == f"[{-0.5 * 200:g}, {limit:g}]"
    assert fwd.level == DiagnosticStatus.WARN and "stuck at 0.3 rad (17.2 deg)" in fwd.message
    assert values[1]["stuck angle [rad]"] == "0.3" and float(values[1]["azimuth [rad]"]) == 0.3
    assert aft.level == DiagnosticStatus.OK


def test_a_fault_changed_after_the_last_sample_is_reported_as_it_is_now():
    """A fault service may run between a sample and the diagnostics timer: the statuses say
    what holds now (and do not read the efficiency of a fault that is gone)."""
    allocator = Allocator(load_vehicle(EXAMPLE))
    allocator.set_fault("main_stbd", FaultMode.DEGRADED, efficiency=0.5)
    last = allocator.allocate([100.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    allocator.clear_faults()
    allocator.set_fault("main_port", FaultMode.FAILED)
    result, values = statuses(allocator, Counters(), last=last)
    assert result[4].level == DiagnosticStatus.OK and "efficiency" not in values[4]
    assert result[3].level == DiagnosticStatus.ERROR and values[3]["limits in force [N]"] == "[0, 0]"


def test_publishers_of_another_type_are_a_warning():
    allocator = Allocator(load_vehicle(EXAMPLE))
    result, values = statuses(allocator, Counters(), foreign=["/controller (geometry_msgs/msg/WrenchStamped)"])
    assert result[0].level == DiagnosticStatus.WARN
    assert "wrench_command publishers of another type: /controller" in result[0].message
    assert values[0]["wrong-type publishers"] == "/controller (geometry_msgs/msg/WrenchStamped)"


def test_the_voltage_in_use_and_a_missing_battery_voltage_are_reported():
    allocator = Allocator(load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml"))
    counters = Counters()
    last = allocator.allocate(np.zeros(6))
    result = diagnostic_statuses(NODE, allocator, counters, False, last, [], ("/battery_state", True))
    values = {kv.key: kv.value for kv in result[0].values}
    assert result[0].level == DiagnosticStatus.WARN
    assert "no valid battery voltage on /battery_state: thrust limits at nominal_voltage 16 V" in result[0].message
    assert values["voltage [V]"] == "16" and values["voltage source"] == "nominal_voltage (no battery voltage)"
    allocator.set_voltage(12.5)
    counters.rejected_battery = 2
    result = diagnostic_statuses(NODE, allocator, counters, False, last, [], ("/battery_state", False))
    values = {kv.key: kv.value for kv in result[0].values}
    assert result[0].level == DiagnosticStatus.OK
    assert values["voltage [V]"] == "12.5" and values["voltage source"] == "/battery_state"
    assert values["rejected battery states"] == "2"
    thruster = {kv.key: kv.value for kv in result[1].values}
    quarter = 0.25                                           # 12.5 V: a quarter of the way from 12 to 14 V
    assert thruster["limits in force [N]"] == f"[{-28.4 - quarter * 6.1:.6g}, {36.4 + quarter * 7.9:.6g}]"
