"""allocator_pkg.simulation.scenario: the shipped scenario files load, scaling shortens
durations and events together, and bad input is refused naming its key."""

import math

import pytest
from conftest import ROOT

from allocator_pkg.simulation.scenario import ScenarioError, load_scenario

SCENARIOS = sorted((ROOT / "config" / "scenarios").glob("*.yaml"))


def test_the_scenarios_ship():
    assert {path.stem for path in SCENARIOS} >= {"dp_station_keeping", "dp_azimuth_failure", "dp_setpoint_change",
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


def _bad(tmp_path, old: str, new: str, base: str = "dp_azimuth_failure.yaml"):
    text = (ROOT / "config" / "scenarios" / base).read_text().replace("../", f"{ROOT}/config/")
    old, new = old.replace("../", f"{ROOT}/config/"), new.replace("../", f"{ROOT}/config/")
    assert old in text
    path = tmp_path / "bad.yaml"
    path.write_text(text.replace(old, new, 1))
    return path


@pytest.mark.parametrize("old, new, message", [
    ("environment:", "enviroment:", "enviroment: unknown key; did you mean environment"),
    ("direction: 20.0", "dir: 20.0", r"environment\.current\.dir: unknown key; did you mean direction"),
    ("speed_sigma: 0.05", "speed_sigm: 0.05", r"environment\.current\.speed_sigm: unknown key; did you mean "
                                              "speed_sigma"),
    ("{time: 220.0, clear_faults: true}", "{time: 220.0, clear_faults: true, note: x}",
     r"events\[1\]\.note: unknown key"),
    ("bounds: {", "bounds: {depth_eror_max: 1.0, ", r"bounds\.depth_eror_max: unknown key; did you mean "
                                                   "depth_error_max"),
])
def test_unknown_keys_are_refused_at_any_depth_with_the_nearest_known_one(tmp_path, old, new, message):
    with pytest.raises(ScenarioError, match=message):
        load_scenario(_bad(tmp_path, old, new))


def test_a_vehicle_file_for_another_hull_is_refused(tmp_path):
    with pytest.raises(ScenarioError, match=r"vehicle: .*bluerov2_heavy.yaml controls heave, roll, pitch, which the "
                                            "dp_vessel model"):
        load_scenario(_bad(tmp_path, "vehicle: ../dp_vessel.yaml", "vehicle: ../bluerov2_heavy.yaml"))
    with pytest.raises(ScenarioError, match=r"vehicle: .*dp_vessel.yaml does not control heave"):
        load_scenario(_bad(tmp_path, "vehicle: ../bluerov2_heavy.yaml", "vehicle: ../dp_vessel.yaml",
                           base="rov_thruster_failure.yaml"))


@pytest.mark.parametrize("old, new, message", [
    ("method: qp", "method: qpp", "method: 'qpp' is not a method; did you mean qp"),
    ("method: qp", "method: explicit", "explicit.*cannot serve this vehicle.*azimuth_stbd, azimuth_port rotate"),
    ("actuator: azimuth_port", "actuator: azimuth_left", r"events\[0\]\.fault\.actuator: 'azimuth_left' is not "
                                                         "an actuator of the vehicle"),
    ("{actuator: azimuth_port, mode: failed}", "{actuator: azimuth_port, mode: degraded}",
     r"events\[0\]\.fault\.value: required for degraded"),
    ("{actuator: azimuth_port, mode: failed}", "{actuator: azimuth_port, mode: degraded, value: 1.5}",
     r"events\[0\]\.fault\.value: DEGRADED needs an efficiency in \(0, 1\]"),
    ("{actuator: azimuth_port, mode: failed}", "{actuator: tunnel_fwd, mode: stuck}",
     r"events\[0\]\.fault\.value: STUCK applies to rotatable thrusters"),
    ("{time: 220.0, clear_faults: true}", "{time: 220.0, parameter: {name: weights.minmax, value: 1.0}}",
     r"events\[1\]\.parameter\.name: 'weights\.minmax' is not a parameter"),
    ("{time: 220.0, clear_faults: true}", "{time: 220.0, parameter: {name: frame, value: flu}}",
     r"events\[1\]\.parameter\.name: 'frame' is read-only"),
    ("{time: 220.0, clear_faults: true}", "{time: 220.0, parameter: {name: weights.minimax, value: -1.0}}",
     r"events\[1\]\.parameter: the allocator refuses it: parameters\.weights\.minimax: must be >= 0"),
    ("seed: 2", "seed: 2\nparameters: {rate_hz: 0.0}", r"parameters\.rate_hz: must be > 0"),
])
def test_the_method_the_parameters_and_every_event_are_checked_at_load(tmp_path, old, new, message):
    with pytest.raises(ScenarioError, match=message):
        load_scenario(_bad(tmp_path, old, new))


def test_another_method_is_checked_against_the_vehicle():
    scenario = load_scenario(ROOT / "config" / "scenarios" / "dp_azimuth_failure.yaml")
    assert scenario.with_method("nonlinear").method == "nonlinear"
    with pytest.raises(ScenarioError, match=r"explicit.*cannot serve"):
        scenario.with_method("explicit")


def test_set_point_events_windows_and_bounds_load():
    scenario = load_scenario(ROOT / "config" / "scenarios" / "dp_setpoint_change.yaml")
    step, ramp = scenario.events
    assert (step.kind, step.time, step.value.position, step.value.speed) == ("setpoint", 60.0, (10.0, 0.0, 0.0), None)
    assert ramp.value.heading == pytest.approx(math.radians(15.0))
    assert ramp.value.heading_rate == pytest.approx(math.radians(0.2))
    assert [w.name for w in scenario.windows] == ["settled", "moved", "turned"]
    assert scenario.windows[0].bounds == {"position_error_max": 3.0, "heading_error_max": 2.0}
    assert [(s.channel, s.time) for s in scenario.schedule().steps(scenario.duration)] == [("position", 60.0)]
    short = scenario.scaled(0.5)
    assert (short.windows[1].start, short.windows[1].end) == (120.0, 150.0)
    assert short.events[1].value.heading_rate == pytest.approx(math.radians(0.4))      # the ramp takes half as long


def test_the_automatic_windows_follow_the_faults():
    scenario = load_scenario(ROOT / "config" / "scenarios" / "dp_azimuth_failure.yaml")
    assert [(w.name, w.start, w.end) for w in scenario.all_windows()] == [("fault", 100.0, 220.0),
                                                                          ("after_fault", 220.0, 300.0)]


@pytest.mark.parametrize("old, new, message", [
    ("{time: 300.0, setpoint: {heading: 15.0, heading_rate: 0.2}}", "{time: 300.0, setpoint: {heading_rate: 0.2}}",
     r"events\[1\]\.setpoint: a mapping with a position, a heading or both"),
    ("{time: 300.0, setpoint: {heading: 15.0, heading_rate: 0.2}}",
     "{time: 300.0, setpoint: {heading: 15.0, speed: 0.2}}",
     r"events\[1\]\.setpoint\.speed: a ramp of the position, which the event does not change"),
    ("heading_rate: 0.2", "heading_rate: 0.0", r"events\[1\]\.setpoint\.heading_rate: a number > 0"),
    ("heading_rate: 0.2", "heading_rte: 0.2", r"events\[1\]\.setpoint\.heading_rte: unknown key; did you mean "
                                              "heading_rate"),
    ("{position: [10.0, 0.0, 0.0]}", "{position: [10.0, 0.0]}", r"events\[0\]\.setpoint\.position: a list of 3"),
    ("start: 240.0, end: 300.0", "start: 300.0, end: 240.0", r"windows\[1\]: start < end <= duration"),
    ("start: 420.0, end: 480.0", "start: 420.0, end: 500.0", r"windows\[2\]: start < end <= duration \(480 s\)"),
    ("name: moved", "name: settled", r"windows\[1\]\.name: 'settled' names another window too"),
    ("name: moved", "name: after_fault", r"windows\[1\]\.name: 'after_fault' is the name of an automatic window"),
    ("name: moved, start", "nme: moved, start", r"windows\[1\]\.nme: unknown key; did you mean name"),
    ("bounds: {position_error_max: 11.0", "bounds: {realtime_factor: 11.0",
     r"bounds\.realtime_factor: unknown key"),
    ("bounds: {position_error_max: 2.0, heading_error_max: 1.0}", "bounds: {energy: -1.0}",
     r"windows\[1\]\.bounds\.energy: at least 0"),
])
def test_set_point_events_windows_and_bounds_are_checked_at_load(tmp_path, old, new, message):
    with pytest.raises(ScenarioError, match=message):
        load_scenario(_bad(tmp_path, old, new, base="dp_setpoint_change.yaml"))


def test_any_metric_but_the_real_time_factor_can_be_bounded(tmp_path):
    scenario = load_scenario(_bad(tmp_path, "bounds: {position_error_max: 4.0", "bounds: {energy: 2.0e+8, "
                                  "thrust_reversals: 3, saturated_fraction: 0.05, position_error_rms: 1.0"))
    assert scenario.bounds == {"energy": 2e8, "thrust_reversals": 3.0, "saturated_fraction": 0.05,
                               "position_error_rms": 1.0, "heading_error_max": 3.0}


def test_group_faults_power_and_weather_ramps_load():
    trip = load_scenario(ROOT / "config" / "scenarios" / "dp_switchboard_trip.yaml")
    assert [(e.time, e.kind, e.name) for e in trip.events] == [(100.0, "group_fault", "switchboard_b"),
                                                              (160.0, "power", "swbd_a")]
    assert trip.events[1].value == 450.0
    assert [(w.name, w.start, w.end) for w in trip.all_windows()] == [("fault", 100.0, 300.0)]
    alarm = load_scenario(ROOT / "config" / "scenarios" / "dp_consequence_alarm.yaml").scaled(0.5)
    ramp = next(e for e in alarm.events if e.kind == "weather_ramp")
    assert (ramp.time, ramp.duration, ramp.value) == (10.0, 75.0, 1.9)
    assert alarm.position_limit == 8.0 and trip.position_limit == 5.0


@pytest.mark.parametrize("old, new, message", [
    ("{time: 100.0, group_fault: {group: switchboard_b}}", "{time: 100.0, group_fault: {group: switchboard_c}}",
     r"events\[0\]\.group_fault\.group: 'switchboard_c' is not a redundancy group of the vehicle "
     r"\(switchboard_a, switchboard_b\)"),
    ("{time: 100.0, group_fault: {group: switchboard_b}}", "{time: 100.0, group_fault: {name: switchboard_b}}",
     r"events\[0\]\.group_fault\.name: unknown key"),
    ("{time: 100.0, group_fault: {group: switchboard_b}}", "{time: 100.0, group_fault: switchboard_b}",
     r"events\[0\]\.group_fault: a mapping"),
    ("{source: swbd_a, available: 450.0}", "{source: swbd_c, available: 450.0}",
     r"events\[1\]\.power\.source: 'swbd_c' is not a power source of the vehicle \(swbd_a, swbd_b\)"),
    ("{source: swbd_a, available: 450.0}", "{source: swbd_a, available: -1.0}",
     r"events\[1\]\.power\.available: at least 0"),
    ("{source: swbd_a, available: 450.0}", "{source: swbd_a}", r"events\[1\]\.power\.available: required"),
    ("{time: 160.0, power: {source: swbd_a, available: 450.0}}",
     "{time: 160.0, weather_ramp: {to: -2.0, duration: 10.0}}", r"events\[1\]\.weather_ramp\.to: at least 0"),
    ("{time: 160.0, power: {source: swbd_a, available: 450.0}}",
     "{time: 160.0, weather_ramp: {to: 2.0, duration: 10.0, hs: 4.0}}", r"events\[1\]\.weather_ramp\.hs: unknown"),
    ("seed: 3", "seed: 3\nposition_limit: 0.0", "position_limit: at least"),
    ("bounds: {position_error_max: 5.0", "bounds: {alarm_lead_time: 4.0", "bounds.alarm_lead_time: unknown key"),
])
def test_group_faults_power_and_weather_ramps_are_checked_at_load(tmp_path, old, new, message):
    with pytest.raises(ScenarioError, match=message):
        load_scenario(_bad(tmp_path, old, new, base="dp_switchboard_trip.yaml"))


def test_a_vehicle_without_groups_or_sources_refuses_their_events(tmp_path):
    with pytest.raises(ScenarioError, match=r"group_fault\.group: 'a' is not a redundancy group of the vehicle "
                                            r"\(it has none\)"):
        load_scenario(_bad(tmp_path, "events:\n", "events:\n  - {time: 1.0, group_fault: {group: a}}\n",
                           base="rov_thruster_failure.yaml"))


@pytest.mark.parametrize("base, old, new, message", [
    ("dp_azimuth_failure.yaml", "{time: 220.0, clear_faults: true}", "{time: 220.0, battery_ramp: {to: 12.0, "
     "duration: 10.0}}", r"events\[1\]\.battery_ramp\.to: the vehicle has no thrust tables measured at several"),
    ("dp_azimuth_failure.yaml", "seed: 2", "seed: 2\nbattery: {voltage: 16.0}",
     r"battery\.voltage: the vehicle has no thrust tables"),
    ("rov_battery_sag.yaml", "battery: {voltage: 16.0}", "battery: {voltage: 80.0}",
     r"battery\.voltage: 80 V is outside the vehicle's thrust tables \(10 to 20 V\)"),
    ("rov_battery_sag.yaml", "battery_ramp: {to: 12.0", "battery_ramp: {to: 5.0",
     r"events\[0\]\.battery_ramp\.to: 5 V is outside the vehicle's thrust tables"),
    ("rov_battery_sag.yaml", "battery: {voltage: 16.0}\n", "",
     r"events\[0\]\.battery_ramp: needs battery\.voltage"),
    ("dp_azimuth_failure.yaml", "{time: 220.0, clear_faults: true}", "{time: 300.0, clear_faults: true}",
     r"events\[1\]\.time: 300 s is not within the run \(0 to 300 s\)"),
    ("dp_azimuth_failure.yaml", "{actuator: azimuth_port, mode: failed}",
     "{actuator: azimuth_port, mode: stuck, value: 200.0}", r"events\[0\]\.fault\.value: the stuck angle in degrees"),
    ("dp_azimuth_failure.yaml", "{actuator: azimuth_port, mode: failed}",
     "{actuator: azimuth_port, mode: failed, value: 0.5}", r"events\[0\]\.fault\.value: .* failed takes no value"),
    ("dp_azimuth_failure.yaml", "wind: {speed: 12.0", "wind: {speed: 300.0",
     r"environment\.wind\.speed: at most 70 m/s, not 300"),
    ("dp_azimuth_failure.yaml", "current: {speed: 0.5", "current: {speed: 50.0",
     r"environment\.current\.speed: at most 10 m/s, not 50"),
    ("dp_azimuth_failure.yaml", "{time: 220.0, clear_faults: true}",
     "{time: 220.0, weather_ramp: {to: 8.0, duration: 10.0}}",
     r"environment\.wind\.speed: at most 70 m/s, not 96 \(8 times 12 with the weather ramps\)"),
    ("dp_azimuth_failure.yaml", "vehicle: ../dp_vessel.yaml", "vehicle: ../example1_rov.yaml",
     r"vehicle: its actuators \(azimuth_fwd, azimuth_aft, main_port, main_stbd\) are not the thrusters of the "
     r"dp_vessel's particulars"),
    ("dp_azimuth_failure.yaml", "particulars: ../particulars/dp_vessel.yaml",
     "particulars: ../particulars/otter_usv.yaml", r"particulars: .*otter_usv\.yaml is a hull of .* not the "
                                                   r"dp_vessel model's 83 x 18 x 5 m"),
    ("rov_thruster_failure.yaml", "environment:\n", "environment:\n  wind: {speed: 5.0, direction: 0.0}\n",
     r"environment\.wind: the bluerov2_heavy model is submerged"),
    ("rov_thruster_failure.yaml", "setpoint: {position: [0.0, 0.0, 5.0]", "setpoint: {position: [0.0, 0.0, -5.0]",
     r"setpoint\.position: down -5 m is above the surface"),
    ("rov_thruster_failure.yaml", "{time: 40.0, fault: {actuator: thruster_1, mode: failed}}",
     "{time: 40.0, setpoint: {position: [0.0, 0.0, -1.0]}}",
     r"events\[0\]\.setpoint\.position: down -1 m is above the surface"),
    ("dp_azimuth_failure.yaml", "setpoint: {position: [0.0, 0.0, 0.0]", "setpoint: {position: [0.0, 0.0, 3.0]",
     r"setpoint\.position: down 3 m; the dp_vessel model floats at the surface"),
])
def test_a_file_that_would_run_other_than_it_says_is_refused(tmp_path, base, old, new, message):
    with pytest.raises(ScenarioError, match=message):
        load_scenario(_bad(tmp_path, old, new, base=base))


def test_a_stuck_angle_is_in_degrees_like_every_angle_of_the_file(tmp_path):
    scenario = load_scenario(_bad(tmp_path, "{actuator: azimuth_port, mode: failed}",
                                  "{actuator: azimuth_port, mode: stuck, value: 30.0}"))
    assert scenario.events[0].value == pytest.approx(math.pi / 6.0)
    where = load_scenario(_bad(tmp_path, "{actuator: azimuth_port, mode: failed}",
                               "{actuator: azimuth_port, mode: stuck}"))
    assert where.events[0].value is None                        # stuck at the angle it has then


def test_a_method_held_to_bounds_of_its_own():
    scenario = load_scenario(ROOT / "config" / "scenarios" / "rov_battery_sag.yaml")
    assert scenario.run_bounds() == {"position_error_max": 0.5, "heading_error_max": 5.0, "depth_error_max": 0.3}
    own = scenario.with_method("pseudoinverse")
    assert own.run_bounds() == {"position_error_max": 0.5, "heading_error_max": 50.0, "depth_error_max": 0.3}
    assert "clipping" in own.method_bounds["pseudoinverse"].note


def test_a_method_holds_its_own_bounds_over_a_window(tmp_path):
    path = _bad(tmp_path, "bounds: {position_error_max: 11.0, heading_error_max: 5.0}",
                "bounds: {position_error_max: 11.0, heading_error_max: 5.0}\nmethods:\n  lp:\n"
                "    windows: {moved: {position_error_max: 2.5}}\n", base="dp_setpoint_change.yaml")
    scenario = load_scenario(path)
    assert scenario.window_bounds()["moved"] == {"position_error_max": 2.0, "heading_error_max": 1.0}
    assert scenario.with_method("lp").window_bounds()["moved"] == {"position_error_max": 2.5, "heading_error_max": 1.0}
    assert scenario.with_method("lp").run_bounds() == scenario.run_bounds()


@pytest.mark.parametrize("methods, message", [
    ("  qpp: {bounds: {heading_error_max: 50.0}}", r"methods\.qpp: method: 'qpp' is not a method; did you mean qp"),
    ("  svd_filter: {bounds: {heading_error_max: 50.0}}", r"methods\.svd_filter: .*cannot serve this vehicle"),
    ("  lp: {bounds: {heading_eror_max: 50.0}}", r"methods\.lp\.bounds\.heading_eror_max: unknown key; did you mean "
                                                 "heading_error_max"),
    ("  lp: {bound: {heading_error_max: 50.0}}", r"methods\.lp\.bound: unknown key; did you mean bounds"),
    ("  lp: {bounds: {heading_error_max: -1.0}}", r"methods\.lp\.bounds\.heading_error_max: at least 0"),
    ("  lp: {windows: {settled: {heading_error_max: 1.0}}}", r"methods\.lp\.windows\.settled: not a window of the "
                                                             r"file \(it has none\)"),
    ("  lp: {note: [a]}", r"methods\.lp\.note: a text"),
    ("  lp: {}", r"methods\.lp: a mapping of bounds, windows and a note"),
])
def test_what_a_scenario_expects_of_a_method_is_checked_at_load(tmp_path, methods, message):
    old = "bounds: {position_error_max: 0.5, heading_error_max: 5.0, depth_error_max: 0.3}\n"
    text = (ROOT / "config" / "scenarios" / "rov_battery_sag.yaml").read_text().replace("../", f"{ROOT}/config/")
    start = text.index(old) + len(old)
    path = tmp_path / "bad.yaml"
    path.write_text(text[:start] + "methods:\n" + methods + "\n")
    with pytest.raises(ScenarioError, match=message):
        load_scenario(path)


TIE_PARAMETERS = ("seed: 3", "seed: 3\nparameters: {power.bus_ties: [bt_ab], power.bus_tie.bt_ab.sources: "
                  "[swbd_a, swbd_b], power.bus_tie.bt_ab.closed: false}")


def tie_scenario(tmp_path, event: str):
    """dp_switchboard_trip with a bus tie between its switchboards and ``event`` for its group fault."""
    path = _bad(tmp_path, *TIE_PARAMETERS, base="dp_switchboard_trip.yaml")
    path.write_text(path.read_text().replace("{time: 100.0, group_fault: {group: switchboard_b}}", event))
    return path


def test_a_bus_tie_event_loads_with_its_state(tmp_path):
    case = load_scenario(tie_scenario(tmp_path, "{time: 50.0, bus_tie: {name: bt_ab, closed: true}}"))
    event = case.events[0]
    assert (event.time, event.kind, event.name, event.value) == (50.0, "bus_tie", "bt_ab", True)


@pytest.mark.parametrize("event, message", [
    ("{time: 50.0, bus_tie: {name: bt_xy, closed: true}}",
     r"events\[0\]\.bus_tie\.name: 'bt_xy' is not a bus tie of the vehicle \(bt_ab\)"),
    ("{time: 50.0, bus_tie: {name: bt_ab, closed: 1}}", r"events\[0\]\.bus_tie: name .* and closed \(true or false\)"),
    ("{time: 50.0, bus_tie: {name: bt_ab}}", r"events\[0\]\.bus_tie: name .* and closed \(true or false\), not"),
    ("{time: 50.0, bus_tie: {name: bt_ab, closed: true, delay: 2.0}}", r"events\[0\]\.bus_tie\.delay: unknown key"),
])
def test_a_bus_tie_event_is_checked_at_load(tmp_path, event, message):
    with pytest.raises(ScenarioError, match=message):
        load_scenario(tie_scenario(tmp_path, event))
