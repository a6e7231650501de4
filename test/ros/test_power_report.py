"""The diagnostics' words for power per source: nothing without sources; the draw and the
available power of each source, the bounds the power sets, failed groups and a stale input."""

import numpy as np
from conftest import ROOT

from allocator_pkg import Allocator, load_vehicle, read_parameters, vehicle_from_parameters
from allocator_pkg.ros.power_report import power_diagnostics

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"


def test_a_vehicle_without_sources_says_nothing_of_power():
    allocator = Allocator(load_vehicle(ROOT / "config" / "example1_rov.yaml"))
    assert power_diagnostics(allocator, allocator.allocate(np.zeros(6)), None, 0) == ([], [], {})


def test_the_power_per_source_the_bounds_and_a_failed_group():
    allocator = Allocator(load_vehicle(DP_VESSEL))
    errors, warnings, values = power_diagnostics(allocator, None, ("/power_available", True, False), 0)
    assert errors == warnings == []
    assert values == {"power swbd_a [kW]": "0.0 of 5600 available", "power swbd_b [kW]": "0.0 of 7800 available",
                      "available power from": "power.<source>.capacity (no power_available)",
                      "rejected power messages": "0", "thrust limited by power": "none",
                      "failed redundancy groups": "none"}
    allocator.set_available_power({"swbd_a": 1000.0})
    allocator.set_group_fault("switchboard_b")
    for _ in range(50):
        last = allocator.allocate([5e5, 0.0, 0.0, 0.0, 0.0, 0.0])
    errors, warnings, values = power_diagnostics(allocator, last, ("/power_available", False, True), 2)
    assert errors == ["stale available power: nothing valid on /power_available for power_timeout, holding "
                      "swbd_a 1000 kW, swbd_b 0 kW"]
    assert values["available power from"] == "/power_available (stale: held at swbd_a 1000 kW, swbd_b 0 kW)"
    assert warnings == ["no power from swbd_b", "power-limited: thrust held back by the available power",
                        "redundancy group failed: switchboard_b"]
    drawn, available = values["power swbd_a [kW]"].split(" of ")
    assert 990.0 < float(drawn) <= 1000.0 and available == "1000 available"
    assert values["thrust limited by power"] == "none"    # the power rows hold it back, no range narrowed
    assert allocator.power_bounds.tolist() == [420000.0, 0.0, 300000.0, 0.0]
    assert values["failed redundancy groups"] == "switchboard_b" and values["rejected power messages"] == "2"


def test_the_bus_ties_and_a_restore_ramp_under_way_are_named():
    parameters = read_parameters(DP_VESSEL)
    parameters.update({"power.bus_ties": ["bt_ab"], "power.bus_tie.bt_ab.sources": ["swbd_a", "swbd_b"],
                       "power.restore_ramp": 10.0})
    allocator = Allocator(vehicle_from_parameters(parameters))
    _, _, values = power_diagnostics(allocator, None, None, 0)
    assert values["bus ties"] == "bt_ab closed (swbd_a + swbd_b)" and "restoring available power" not in values
    allocator.set_bus_tie("bt_ab", False)
    allocator.set_available_power({"swbd_a": 0.0})
    allocator.set_available_power({"swbd_a": 5600.0})
    allocator.allocate(np.zeros(6))
    _, _, values = power_diagnostics(allocator, None, None, 0)
    assert values["bus ties"] == "bt_ab open (swbd_a + swbd_b)"
    assert values["restoring available power"] == "swbd_a 56 kW, swbd_b 7800 kW in use, rising at capacity / 10 s"
