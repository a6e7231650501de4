"""allocator_pkg.simulation.electric_plant: the drilling rig's plant on its own (the buses a tie
splits, what the power management system reports after the loss of a set, the drives' limits
on a dead switchboard) and in the closed loop, in process: the benchmark's events in a short
run, with the load reduction (no set trips) and without it (the trip cascade)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.simulation.closed_loop import ClosedLoop
from allocator_pkg.simulation.electric_plant import RELAY, ElectricPlant
from allocator_pkg.simulation.in_process import in_process_link
from allocator_pkg.simulation.scenario import load_scenario

SCENARIOS = ROOT / "config" / "scenarios"
RIG = SCENARIOS / "drilling_rig_power.yaml"
THRUST = np.full(6, 250e3)
"""[N] each thruster: 0.010989 x 250000^1.5 = 1373.6 kW."""


def plant(scenario=RIG) -> ElectricPlant:
    electric = ElectricPlant(load_scenario(scenario).power_plant, load_vehicle(ROOT / "config" / "drilling_rig.yaml"))
    electric.start(THRUST)
    return electric


def test_the_thrusters_draw_the_allocators_power_model():
    electric = plant()
    assert electric.thruster_power == pytest.approx(np.full(6, 0.010989 * 250e3 ** 1.5 / 1000.0))
    assert electric.rated == pytest.approx(np.full(6, 5000.0), rel=1e-4)
    loads = electric._loads(0.0)
    assert loads["swbd_2"] == pytest.approx(2000.0 + 2 * 1373.6, abs=0.1)
    assert loads["swbd_1"] == pytest.approx(2000.0 + 1000.0 + 3000.0 + 2 * 1373.6, abs=0.1)


def test_a_reverse_thrust_draws_its_reverse_coefficients_power_and_a_degraded_one_its_set_points():
    vehicle = vehicle_from(ROOT / "config" / "drilling_rig.yaml", actuators__thruster_1__thrust_min=-300e3,
                           actuators__thruster_1__reversible=True,
                           actuators__thruster_1__reverse_power_coefficient=0.02)
    electric = ElectricPlant(load_scenario(RIG).power_plant, vehicle)
    thrust = np.array([-200e3, 200e3, 200e3, 0.0, 0.0, 0.0])
    electric.start(thrust, np.array([1.0, 0.5, 1.0, 1.0, 1.0, 1.0]))
    assert electric.thruster_power[:3] == pytest.approx([0.02 * 200e3 ** 1.5 / 1000.0,
                                                         0.010989 * 400e3 ** 1.5 / 1000.0,
                                                         0.010989 * 200e3 ** 1.5 / 1000.0])


def test_opening_the_ties_splits_the_buses_at_one_frequency():
    electric = plant()
    assert [b.switchboards for b in electric.buses] == [("swbd_1", "swbd_2", "swbd_3")]
    electric.set_bus_tie("tie_12", False)
    electric.set_bus_tie("tie_23", False)
    assert [b.switchboards for b in electric.buses] == [("swbd_1",), ("swbd_2",), ("swbd_3",)]
    assert len({b.frequency for b in electric.buses}) == 1
    for _ in range(200):
        electric.advance(THRUST, 0.1)
    frequency = {b.switchboards[0]: b.frequency for b in electric.buses}
    assert frequency["swbd_2"] > frequency["swbd_1"]             # the lighter bus runs up its droop
    assert frequency["swbd_1"] == pytest.approx(1.01 - 0.02 * electric._loads(electric.time)["swbd_1"] / 18200.0,
                                                abs=1e-4)


def test_after_a_set_is_lost_the_report_is_held_then_starts_from_what_the_others_gave():
    electric = plant(SCENARIOS / "drilling_rig_power_no_reduction.yaml")
    electric.set_bus_tie("tie_12", False)
    electric.set_bus_tie("tie_23", False)
    for _ in range(400):                        # past the ties' own hold and ramp
        electric.advance(THRUST, 0.1)
    before = dict(electric.reported)
    given = electric.buses[2].electrical(electric._loads(electric.time)["swbd_3"])
    electric.lose_set("g5")
    reported = []
    for _ in range(30):
        electric.advance(THRUST * 0.5, 0.1)
        reported.append(electric.reported["swbd_3"])
    assert reported[:9] == pytest.approx([before["swbd_3"]] * 9)            # the 1 s reaction
    floor = given["g6"] - (2000.0 + 1000.0 + 3000.0)
    assert floor < 0.0 and reported[11] == pytest.approx(max(0.0, floor + 7735.0 * 0.2 / 45.0), abs=1.0)
    assert electric.reported["swbd_1"] == before["swbd_1"]


def test_with_the_load_reduction_the_drives_are_cut_after_its_reaction_and_the_report_with_them():
    electric = plant()
    electric.set_bus_tie("tie_12", False)
    electric.set_bus_tie("tie_23", False)
    for _ in range(100):
        electric.advance(THRUST, 0.1)
    electric.lose_set("g5")
    caps, reported = [], []
    for _ in range(20):
        electric.advance(np.clip(THRUST, *electric.thrust_caps()), 0.1)      # the drives obey
        caps.append(electric.drive_limits()[4])
        reported.append(electric.reported["swbd_3"])
    # the remaining set gave less than the other consumers: 0 kW at 0.2 s, then 5000 kW over 5 s
    rated = electric.rated[4]
    ramp = rated * 0.1 * np.arange(19) / 5.0
    assert math.isinf(caps[0]) and caps[1:5] == pytest.approx(ramp[:4])
    # never above the ramp; below it where the frequency rule holds the set's load acceptance back
    assert np.all(np.array(caps[1:]) <= ramp + 1e-9)
    # the report: the drives' limits while the PMS holds its value (1 s), then its own ramp below them
    assert reported[1:9] == pytest.approx([2 * cap for cap in caps[1:9]], abs=1e-6)
    assert all(r <= 2 * c + 1e-6 for r, c in zip(reported[1:], caps[1:]))


def test_a_dead_switchboard_stops_its_drives():
    electric = plant()
    electric.set_bus_tie("tie_12", False)
    electric.set_bus_tie("tie_23", False)
    electric.lose_set("g5")
    electric.lose_set("g6")
    dead = electric.advance(THRUST, 0.1)
    assert dead == ["swbd_3"] and electric.reported["swbd_3"] == 0.0
    low, high = electric.thrust_caps()
    assert high[4:] == pytest.approx([0.0, 0.0]) and low[4:] == pytest.approx([0.0, 0.0])
    assert np.isinf(high[:4]).all() and np.isinf(low[:4]).all()


def short(name: str, tmp_path):
    """The benchmark's events in 60 s: the ties at 10 s, g5 at 30 s, thruster 6 at 32 s, in a
    drawworks pulse (from 0 s)."""
    text = (SCENARIOS / name).read_text().replace("../", str(ROOT / "config") + "/")
    for old, new in (("duration: 320.0", "duration: 60.0"), ("time: 200.0", "time: 10.0"),
                     ("time: 250.0", "time: 30.0"), ("time: 252.0", "time: 32.0"), ("start: 100.0", "start: 0.0")):
        text = text.replace(old, new)
    path = tmp_path / name
    path.write_text(text)
    loop = ClosedLoop(load_scenario(path), tmp_path / "out", in_process_link, log=lambda line: None)
    return loop, loop.run()


@pytest.mark.slow
def test_with_the_load_reduction_no_set_trips(tmp_path):
    loop, result = short("drilling_rig_power.yaml", tmp_path)
    record = loop.electric.record
    assert [why for _, _, why in record.trips] == ["lost (scenario event)"]
    assert result.metrics["generator_sets_tripped"] == 0.0 and result.metrics["time_under_frequency"] == 0.0
    frequency = np.array(record.frequency)
    assert frequency.min() > 0.95 and result.report["power_plant"]["switchboards"]["swbd_3"][
        "lowest_frequency"] == pytest.approx(frequency[:, 2].min())
    assert result.metrics["time_over_available"] == 0.0


@pytest.mark.slow
def test_without_it_the_last_set_of_the_board_trips_and_the_board_goes_dead(tmp_path):
    loop, result = short("drilling_rig_power_no_reduction.yaml", tmp_path)
    trips = [(time, name) for time, name, why in loop.electric.record.trips if why == RELAY]
    assert [name for _, name in trips] == ["g6"] and 30.0 < trips[0][0] < 32.0
    assert result.metrics["generator_sets_tripped"] == 1.0 and result.metrics["frequency_dip"] == 1.0
    assert loop.electric.dead == {"swbd_3"} and math.isinf(result.metrics["consequence_alarm_time"])
    thrust = np.array(result.trace.thrust)
    assert np.abs(thrust[-10:, 4:]).max() == 0.0                            # the allocator knows
