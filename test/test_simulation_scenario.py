"""allocator_pkg.simulation.scenario: the shipped scenario files load, scaling shortens
durations and events together, and bad input is refused naming its key."""

import math

import pytest
from conftest import ROOT

from allocator_pkg.simulation.scenario import ScenarioError, load_scenario

SCENARIOS = sorted((ROOT / "config" / "scenarios").glob("*.yaml"))


def test_four_scenarios_ship():
    assert {path.stem for path in SCENARIOS} >= {"dp_station_keeping", "dp_azimuth_failure",
                                                  "rov_thruster_failure", "rov_battery_sag"}


@pytest.mark.parametrize("path", SCENARIOS, ids=lambda p: p.stem)
def test_every_shipped_scenario_loads_with_bounds(path):
    scenario = load_scenario(path)
    assert scenario.vehicle.is_file() and scenario.bounds and scenario.duration > 0
    assert (scenario.particulars is not None) == scenario.horizontal


def test_scaling_shortens_the_run_and_its_events_together():
    scenario = load_scenario(ROOT / "config" / "scenarios" / "dp_azimuth_failure.yaml")
    short = scenario.scaled(0.1)
    assert short.duration == pytest.approx(30.0)
    assert [e.time for e in short.events] == pytest.approx([10.0, 22.0])
    assert [e.kind for e in short.events] == ["fault", "clear_faults"]
    sag = load_scenario(ROOT / "config" / "scenarios" / "rov_battery_sag.yaml").scaled(0.5)
    assert (sag.events[0].time, sag.events[0].duration, sag.events[0].value) == (10.0, 30.0, 12.0)
    assert sag.voltage == 16.0 and sag.setpoint_heading == 0.0 and math.isclose(sag.setpoint_position[2], 5.0)
    with pytest.raises(ScenarioError, match="duration scale"):
        scenario.scaled(0.0)


@pytest.mark.parametrize(("old", "new", "key"), [
    ("model: dp_vessel", "model: submarine", "model"),
    ("method: qp", "method: [qp]", "method"),
    ("duration: 300.0", "duration: -5", "duration"),
    ("kp: [38.0e+3, 51.0e+3, 3.4e+7]", "kp: [38.0e+3, 51.0e+3]", "controller"),
    ("speed: 12.0", "speed: fast", "environment.wind.speed"),
    ("{time: 100.0, fault: {actuator: azimuth_port, mode: failed}}",
     "{time: 100.0, fault: {actuator: azimuth_port, mode: exploded}}", r"events\[0\]\.fault\.mode"),
    ("{time: 220.0, clear_faults: true}", "{time: 220.0}", r"events\[1\]"),
    ("bounds: {position_error_max: 4.0", "bounds: {position_error_mean: 4.0", "bounds.position_error_mean"),
    ("particulars: ../particulars/dp_vessel.yaml", "particulars: ../particulars/nowhere.yaml", "particulars"),
])
def test_bad_input_names_its_key(tmp_path, old, new, key):
    text = (ROOT / "config" / "scenarios" / "dp_azimuth_failure.yaml").read_text().replace("../", f"{ROOT}/config/")
    old, new = old.replace("../", f"{ROOT}/config/"), new.replace("../", f"{ROOT}/config/")
    assert old in text
    path = tmp_path / "bad.yaml"
    path.write_text(text.replace(old, new))
    with pytest.raises(ScenarioError, match=key):
        load_scenario(path)
