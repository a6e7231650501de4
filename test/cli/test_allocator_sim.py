"""allocator-sim closed loop with the real allocator_node process, on the shipped
scenarios (shortened with --duration-scale but the set-point change): the loop holds each
within its stated bounds for qp, by the verdict allocator-sim gives, also through its failure;
the run starts in equilibrium with the thrusters loaded; the same seed gives the same
metrics; the metrics agree with what the MCAP holds; every recorded command is within the
limits in force; the command line prints the verdict and its exit status follows it."""

import math
import re
import subprocess
import time
from dataclasses import replace

import numpy as np
import pytest
from conftest import ALARM_METRICS, ALARM_TOLERANCE, ROOT
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory

from allocator_msgs.msg import ActuatorFault
from allocator_pkg.cli.allocator_sim import main, run
from allocator_pkg.effectiveness.faults import thrust_limits
from allocator_pkg.ros.process import child_process, executable, node_command
from allocator_pkg.ros.recording_metrics import metrics_from_recording
from allocator_pkg.simulation.run_report import read_report, report_checks
from allocator_pkg.simulation.scenario import Event, load_scenario
from allocator_pkg.simulation.verdict import broken, verdict_lines
from allocator_pkg.vehicle.angles import wrap

pytestmark = pytest.mark.slow

SCENARIOS = {"dp_station_keeping": 0.1, "dp_azimuth_failure": 0.1, "rov_thruster_failure": 0.15,
             "rov_battery_sag": 0.15, "dp_stuck_azimuth": 0.1, "dp_setpoint_change": 1.0, "dp_calm_bias": 0.2,
             "dp_switchboard_trip": 0.5, "dp_power_limited": 0.5, "dp_consequence_alarm": 0.5}
"""The shipped scenarios, each with the scale of its duration here (the set-point change at
full length: its windows' bounds are for the vessel's own pace; the power scenarios at half:
their weather ramps and the alarm's lead need the time)."""
RESULTS = {}


def scenario(name):
    return load_scenario(ROOT / "config" / "scenarios" / f"{name}.yaml").scaled(SCENARIOS[name])


def finished_run(name, tmp_path_factory):
    """(scenario, result, output folder) of a shipped scenario, run once per session."""
    if name not in RESULTS:
        out = tmp_path_factory.mktemp(name)
        RESULTS[name] = (scenario(name), run(scenario(name), out, log=lambda _: None), out)
    return RESULTS[name]


@pytest.fixture(params=sorted(SCENARIOS))
def finished(request, tmp_path_factory):
    return finished_run(request.param, tmp_path_factory)


def test_the_loop_holds_the_scenario_within_its_bounds(finished):
    case, result, out = finished
    report = read_report(out / "metrics.json")
    assert report["metrics"] == pytest.approx(result.metrics)
    assert report["units"]["energy"] == "J" and set(report["units"]) == set(report["metrics"])
    checks = report_checks(case, report)
    assert checks and not broken(checks), verdict_lines(checks)
    assert report["metrics"]["realtime_factor"] > 0.0
    faulted = np.array(result.trace.faulted)
    if any(e.kind == "fault" for e in case.events):
        assert faulted.any()                                # the failure happened inside the run
        fault = report["windows"]["fault"]
        assert fault["metrics"]["position_error_max"] == pytest.approx(result.trace.position_errors()[faulted].max())
        assert fault["metrics"]["position_error_max"] <= case.bounds["position_error_max"]


def test_the_run_starts_in_equilibrium_with_the_thrusters_loaded(finished):
    case, result, _ = finished
    a = result.trace.arrays()
    first = a["time"] < 5.0 * case.duration / 100.0 + 2.0           # the first seconds, before any event
    assert a["power"][0] > 0.0
    assert a["power"][first].max() <= 1.5 * a["power"][0]        # no spike while the thrusters load
    assert result.trace.position_errors()[first].max() <= 0.25 * case.bounds["position_error_max"]


def test_the_metrics_agree_with_the_recording(finished):
    case, result, out = finished
    recomputed = metrics_from_recording(out / "run.mcap", result.vehicle, case.horizontal)
    for key, value in recomputed.items():
        assert value == pytest.approx(result.metrics[key], rel=1e-9, abs=1e-9), key


def test_every_recorded_command_is_within_the_limits_in_force(finished):
    case, result, out = finished
    vehicle = result.vehicle
    period = 1.0 / vehicle.rate_hz
    topics = {"/thruster_commands": [], "/allocation_status": [], "/clock": [], "/odometry": [], "/setpoint": [],
              "/wrench_command": []}
    with open(out / "run.mcap", "rb") as stream:
        for _, channel, _, message in make_reader(stream, decoder_factories=[DecoderFactory()]).iter_decoded_messages():
            if channel.topic in topics:
                topics[channel.topic].append(message)
    steps = len(result.trace.time)
    assert all(len(messages) == steps for messages in topics.values()), {k: len(v) for k, v in topics.items()}
    previous = None
    for commands, status in zip(topics["/thruster_commands"], topics["/allocation_status"]):
        voltage = status.voltage if math.isfinite(status.voltage) else None
        low, high = thrust_limits(vehicle, voltage)
        thrust, angle = np.array(commands.thrust), np.array(commands.azimuth)
        assert np.all(thrust >= low - 1e-6) and np.all(thrust <= high + 1e-6)
        mode = np.array(list(commands.mode))          # uint8[] reads back as bytes
        failed = mode == ActuatorFault.FAILED
        assert np.all(thrust[failed] == 0.0)
        available = list(status.source_available)
        for i, actuator in enumerate(vehicle.actuators):
            steady = previous is not None and mode[i] == previous[2][i] == ActuatorFault.NOMINAL \
                and available == previous[3]                  # less power cuts the thrust at once too
            if steady and actuator.thrust_rate_max > 0.0:     # a failure stops a thruster at once
                assert abs(thrust[i] - previous[0][i]) <= actuator.thrust_rate_max * period * (1 + 1e-9) + 1e-6
            if actuator.rotatable:
                for start, end in actuator.rotation.forbidden_sectors:
                    if abs(thrust[i]) > 1e-6:
                        assert not (start + 1e-6 < wrap(angle[i]) < end - 1e-6), (actuator.name, angle[i])
                if previous is not None:
                    assert abs(wrap(angle[i] - previous[1][i])) <= actuator.rotation.rate_max * period + 1e-9
                    if mode[i] == previous[2][i] == ActuatorFault.STUCK:
                        assert angle[i] == previous[1][i]
        previous = (thrust, angle, mode, available)
    if case.voltage is not None and any(e.kind == "battery_ramp" for e in case.events):
        voltages = [s.voltage for s in topics["/allocation_status"]]
        assert voltages[0] == pytest.approx(16.0) and voltages[-1] < 13.0    # the limits followed the sag


def test_the_same_seed_gives_the_same_metrics(tmp_path_factory, tmp_path):
    case, result, _ = finished_run("dp_azimuth_failure", tmp_path_factory)   # a fault, azimuths
    again = run(case, tmp_path, log=lambda _: None)
    for key, value in result.metrics.items():
        if key in ALARM_METRICS:                              # the node's analysis thread: within a period
            assert again.metrics[key] == pytest.approx(value, abs=ALARM_TOLERANCE), key
        elif key != "realtime_factor":
            assert again.metrics[key] == value, key
    assert np.array_equal(np.array(again.trace.position), np.array(result.trace.position))


def test_the_set_point_step_is_measured(tmp_path_factory):
    _, result, out = finished_run("dp_setpoint_change", tmp_path_factory)
    report = read_report(out / "metrics.json")
    (step,) = report["steps"]
    assert (step["channel"], step["time"], step["size"]) == ("position", 60.0, 10.0)
    assert 0.0 < step["rise_time"] < 60.0 and step["overshoot"] >= 0.0
    assert step["settling_time"] is None or step["settling_time"] > step["rise_time"]
    assert set(report["windows"]) == {"settled", "moved", "turned"}
    position, heading = result.trace.setpoint[-1], result.trace.setpoint_heading[-1]
    assert position == [10.0, 0.0, 0.0] and heading == pytest.approx(np.radians(15.0))


def test_thrust_bias_at_least_halves_the_azimuth_travel_in_calm_weather(tmp_path_factory, tmp_path):
    case, biased, _ = finished_run("dp_calm_bias", tmp_path_factory)
    assert case.parameters["bias.enabled"] is True
    plain = run(replace(case, parameters={**case.parameters, "bias.enabled": False}), tmp_path, log=lambda _: None)
    assert biased.metrics["azimuth_travel"] <= 0.5 * plain.metrics["azimuth_travel"]
    assert biased.metrics["energy"] > plain.metrics["energy"]                   # what holding the angles costs
    for metric in ("position_error_max", "heading_error_max"):
        assert biased.metrics[metric] <= 1.1 * plain.metrics[metric], metric    # and it holds station as well


def test_the_bias_switches_off_and_on_while_the_node_runs(tmp_path):
    """bias.enabled as a node parameter: off at 20 s, on again at 40 s; the azimuths leave
    their opposed angles and come back, the wrench met all along."""
    events = (Event(time=20.0, kind="parameter", name="bias.enabled", value=False),
              Event(time=40.0, kind="parameter", name="bias.enabled", value=True))
    result = run(replace(scenario("dp_calm_bias"), events=events), tmp_path, log=lambda _: None)
    a = result.trace.arrays()
    stbd, port = np.degrees(a["azimuth"][:, 0]), np.degrees(a["azimuth"][:, 1])
    for when in (a["time"] < 20.0, a["time"] > 58.0):
        assert np.all(np.abs(stbd[when] + 82.5) < 7.5) and np.all(np.abs(port[when] - 82.5) < 7.5)
    off = (a["time"] > 35.0) & (a["time"] < 40.0)
    assert np.all(np.abs(stbd[off]) < 45.0) and np.all(np.abs(port[off]) < 45.0)
    assert not a["saturated"].any()


def bounded_copy(tmp_path, bound: float):
    """dp_station_keeping with its position bound set to ``bound``."""
    text = (ROOT / "config" / "scenarios" / "dp_station_keeping.yaml").read_text().replace("../", f"{ROOT}/config/")
    path = tmp_path / f"bound_{bound:g}.yaml"
    path.write_text(text.replace("bounds: {position_error_max: 3.0", f"bounds: {{position_error_max: {bound}"))
    return path


def test_the_command_line_gives_the_verdict_and_fails_a_broken_bound(tmp_path, capsys):
    path = bounded_copy(tmp_path, 1e-4)
    assert main([str(path), "--out", str(tmp_path / "run"), "--duration-scale", "0.02"]) == 1
    text = capsys.readouterr().out
    assert "FAIL  run" in text and "verdict: FAIL, 1 of 2 bounds broken" in text
    assert "sim: position_error_rms [m]" in text and "sim: thrust_reversals [count]" in text
    assert main([str(path), "--out", str(tmp_path / "data"), "--duration-scale", "0.02", "--no-verdict"]) == 0
    assert "verdict" not in capsys.readouterr().out
    assert main([str(bounded_copy(tmp_path, 3.0)), "--out", str(tmp_path / "held"), "--duration-scale", "0.02"]) == 0
    assert "verdict: PASS, 2 bounds held" in capsys.readouterr().out


def test_compare_gives_a_verdict_per_method(tmp_path, capsys):
    path = bounded_copy(tmp_path, 1e-4)
    assert main(["compare", str(path), "--methods", "qp", "pseudoinverse", "--out", str(tmp_path / "cmp"),
                 "--duration-scale", "0.02"]) == 1
    text = capsys.readouterr().out
    assert "sim: qp: FAIL, broke run position_error_max" in text and "sim: pseudoinverse: FAIL" in text
    assert "| thrust reversals [count] |" in text


def test_compare_leaves_out_a_method_the_scenario_parameters_ask_too_much_of(tmp_path, capsys):
    path = ROOT / "config" / "scenarios" / "dp_calm_bias.yaml"
    assert main(["compare", str(path), "--methods", "qp", "lp", "--out", str(tmp_path / "cmp"),
                 "--duration-scale", "0.02", "--no-baseline"]) == 0
    text = capsys.readouterr().out
    assert "sim: lp left out: bias.enabled: method 'lp' does not implement thrust bias" in text
    assert "sim: qp: PASS" in text and not (tmp_path / "cmp" / "lp").exists()


def test_a_bad_scenario_is_refused_with_its_key(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    text = (ROOT / "config" / "scenarios" / "dp_station_keeping.yaml").read_text().replace("../", f"{ROOT}/config/")
    bad.write_text(text.replace("thruster_time_constant: 2.0", "thruster_time_constant: -1.0"))
    assert main([str(bad), "--out", str(tmp_path / "out")]) == 2          # refused, not a broken bound
    assert "thruster_time_constant" in capsys.readouterr().err


def test_the_command_line_runs_the_allocator_in_process(tmp_path, capsys):
    path = bounded_copy(tmp_path, 1e-4)
    out = tmp_path / "in_process"
    assert main([str(path), "--out", str(out), "--duration-scale", "0.02", "--in-process"]) == 1
    assert "verdict: FAIL, 1 of 2 bounds broken" in capsys.readouterr().out
    assert {p.name for p in out.iterdir()} == {"metrics.json", "footprint.png", "timeline.png"}   # no node, no MCAP
    assert main(["compare", str(bounded_copy(tmp_path, 3.0)), "--methods", "qp", "lp", "--out", str(tmp_path / "cmp"),
                 "--duration-scale", "0.02", "--no-baseline", "--in-process"]) == 0
    assert (tmp_path / "cmp" / "compare.md").exists() and (tmp_path / "cmp" / "lp" / "metrics.json").exists()


def test_two_simulations_of_different_vehicles_beside_a_make_run_node_give_the_metrics_of_each_alone(
        tmp_path_factory, tmp_path):
    """One domain: the node of `make run` (config/default.yaml, no namespace) and, at the same
    time, allocator-sim of a DP vessel (four thrusters) and of an ROV (four others), each in a
    namespace of its own: every metric as the run alone gives it."""
    names = ("dp_azimuth_failure", "rov_thruster_failure")
    alone = {name: finished_run(name, tmp_path_factory)[1].metrics for name in names}
    sim = str(executable("allocator-sim"))
    with child_process(node_command(ROOT / "config" / "default.yaml")) as make_run:
        runs = {name: subprocess.Popen([sim, str(ROOT / "config" / "scenarios" / f"{name}.yaml"), "--duration-scale",
                                        str(SCENARIOS[name]), "--out", str(tmp_path / name), "--no-verdict"],
                                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
                for name in names}
        outputs = {name: process.communicate(timeout=600)[0] for name, process in runs.items()}
        assert make_run.poll() is None, make_run.output()
    for name in names:
        assert runs[name].returncode == 0, outputs[name]
        together = read_report(tmp_path / name / "metrics.json")["metrics"]
        for key, value in alone[name].items():
            if key in ALARM_METRICS:
                assert together[key] == pytest.approx(value, abs=ALARM_TOLERANCE), (name, key)
            elif key != "realtime_factor":
                assert together[key] == value, (name, key)


def test_the_link_stops_at_a_foreign_node_in_its_namespace_and_names_it(tmp_path):
    """A node of another vehicle (eight thrusters) in the run's namespace: the link names it,
    when it takes the wrench before the run, and when its commands come."""
    import rclpy
    from geometry_msgs.msg import Wrench
    from rosgraph_msgs.msg import Clock

    from allocator_msgs.msg import ThrusterCommands
    from allocator_pkg.ros.process import namespace_arguments, run_namespace
    from allocator_pkg.ros.sim_link import NodeLink
    from allocator_pkg.simulation.run_setup import SimulationError

    namespace = run_namespace()
    foreign = rclpy.Context()
    rclpy.init(context=foreign, args=["--ros-args", *namespace_arguments(namespace)])
    link = NodeLink(tmp_path, tmp_path / "node.log", namespace, ["azimuth_fwd", "azimuth_aft", "main_port",
                                                                 "main_stbd"])
    try:
        intruder = rclpy.create_node("bluerov2_allocator", context=foreign)
        intruder.create_subscription(Wrench, "wrench_command", lambda _: None, 10)
        intruder.create_subscription(Clock, "/clock", lambda _: None, 10)
        commands = intruder.create_publisher(ThrusterCommands, "thruster_commands", 10)
        with pytest.raises(SimulationError) as raised:
            link.wait_for_node(lambda: True)
        assert f"{namespace}/bluerov2_allocator on {namespace}/wrench_command" in str(raised.value)
        assert f"other nodes than this run's {namespace}/thrust_allocator on its topics: " in str(raised.value)
        deadline = time.monotonic() + 10.0
        while commands.get_subscription_count() == 0 and time.monotonic() < deadline:
            link.executor.spin_once(timeout_sec=0.05)
        commands.publish(ThrusterCommands(name=[f"thruster_{i}" for i in range(1, 9)]))
        with pytest.raises(SimulationError, match=re.escape(
                "thruster commands of thruster_1, thruster_2, thruster_3, thruster_4, thruster_5, thruster_6, "
                "thruster_7, thruster_8 (the vehicle's actuators: azimuth_fwd, azimuth_aft, main_port, main_stbd)")):
            while time.monotonic() < deadline:
                link.executor.spin_once(timeout_sec=0.05)
    finally:
        link.close()
        rclpy.try_shutdown(context=foreign)
