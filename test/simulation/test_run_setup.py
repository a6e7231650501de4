"""allocator_pkg.simulation.run_setup: the warm-up's length for a vehicle, the controller's
set-point vector and the supply voltage over a ramp."""

import math

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.simulation.run_setup import WARM_UP_MARGIN, Voltage, setpoint_vector, warm_up_steps
from allocator_pkg.simulation.scenario import load_scenario


def test_the_warm_up_lasts_as_long_as_the_slowest_actuator_plus_the_margin():
    vessel = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
    # azimuths turn half a circle at 0.21 rad/s (14.96 s), longer than 655 kN at 100 kN/s (6.55 s)
    assert warm_up_steps(vessel, 0.1) == math.ceil((math.pi / 0.21 + WARM_UP_MARGIN) / 0.1) == 200
    rov = load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml")           # no rate limits: the margin alone
    assert warm_up_steps(rov, 0.02) == 250


def test_the_set_point_vector_of_each_hull():
    assert setpoint_vector((1.0, 2.0, 3.0), 0.5, planar=True) == pytest.approx([1.0, 2.0, 0.5])
    assert np.array_equal(setpoint_vector((1.0, 2.0, 3.0), 0.5, planar=False), [1.0, 2.0, 3.0, 0.0, 0.0, 0.5])


def test_the_voltage_follows_its_ramp():
    voltage = Voltage(load_scenario(ROOT / "config" / "scenarios" / "rov_battery_sag.yaml"))
    assert [voltage.at(t) for t in (0.0, 20.0, 50.0, 80.0, 100.0)] == pytest.approx([16.0, 16.0, 14.0, 12.0, 12.0])
