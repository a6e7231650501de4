"""The diagnostics status as a pure function of the allocator, the counters and the input state."""

import numpy as np
from conftest import ROOT
from diagnostic_msgs.msg import DiagnosticStatus

from allocator_pkg import Allocator, FaultMode, load_vehicle
from allocator_pkg.diagnostics import Counters, diagnostic_status

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


def status(allocator, counters, stale=False, last=None):
    result = diagnostic_status("thrust_allocator: thrust allocation", "/thrust_allocator", allocator, counters,
                               stale, last)
    return result, {kv.key: kv.value for kv in result.values}


def test_ok_while_allocating():
    allocator = Allocator(load_vehicle(EXAMPLE))
    counters = Counters()
    last = allocator.allocate(np.zeros(6))
    counters.count(last)
    result, values = status(allocator, counters, last=last)
    assert result.level == DiagnosticStatus.OK and result.message == "allocating"
    assert values["samples in period"] == "1" and values["mode main_port"] == "NOMINAL"
    assert values["solver status"] == "solved" and values["stale input"] == "false"


def test_warn_on_faults_saturation_and_rejected_input_and_error_when_stale():
    allocator = Allocator(load_vehicle(EXAMPLE))
    allocator.set_fault("main_port", FaultMode.FAILED)
    counters = Counters(rejected_wrenches=2, rejected_in_period=2)
    counters.count(allocator.allocate([1e6, 0.0, 0.0, 0.0, 0.0, 0.0]))
    result, values = status(allocator, counters)
    assert result.level == DiagnosticStatus.WARN
    assert result.message == "main_port FAILED; 1 saturated samples; 2 rejected inputs"
    assert values["mode main_port"] == "FAILED" and values["rejected wrenches"] == "2"
    result, _ = status(allocator, counters, stale=True)
    assert result.level == DiagnosticStatus.ERROR and result.message.startswith("stale wrench input")
    counters.reset_period()
    assert (counters.samples, counters.saturated, counters.rejected_in_period) == (0, 0, 0)
    assert counters.rejected_wrenches == 2
