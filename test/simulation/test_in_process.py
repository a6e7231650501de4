"""allocator_pkg.simulation.in_process: the allocator library in the closed loop judges the
allocator the node runs. On shipped scenarios with a fault, its clearing, a parameter change,
a battery sag, a redundancy group's loss and a change of available power (shortened), the
in-process run and the node-in-the-loop run give the same metrics, window metrics, commanded
thrusts and angles and power per source to 1e-9, and consequence alarm times within one
analysis period and a few samples (the node analyses on a thread of its own); the link reads the wrench
and writes the unallocated wrench in the node's frame, takes the battery's voltage as float32,
and refuses the faults and parameters the node refuses, leaving the allocator as it was."""

from dataclasses import replace

import numpy as np
import pytest
from conftest import ALARM_METRICS, ALARM_TOLERANCE, ROOT

from allocator_pkg.allocation.allocator import Allocator
from allocator_pkg.cli.allocator_sim import run
from allocator_pkg.configuration.parameters import vehicle_from_parameters
from allocator_pkg.configuration.params_file import read_parameters
from allocator_pkg.effectiveness.faults import FaultMode
from allocator_pkg.simulation.in_process import InProcessLink, node_parameters
from allocator_pkg.simulation.plant import Pose
from allocator_pkg.simulation.run_report import read_report
from allocator_pkg.simulation.run_setup import SimulationError
from allocator_pkg.simulation.scenario import load_scenario
from allocator_pkg.vehicle.frames import wrench_between

SCENARIOS = {"dp_stuck_azimuth": 0.1, "dp_azimuth_failure": 0.1, "rov_battery_sag": 0.15,
             "dp_switchboard_trip": 0.1}
"""Shipped scenarios with the scale of their duration: a STUCK fault and a parameter change
(30 s), a failure and its clearing (30 s), a battery ramp on the 6-DOF vehicle (15 s), a
switchboard's group fault and the other's available power cut (30 s)."""
TOLERANCE = 1e-9


def assert_same_metrics(node: dict, own: dict, where) -> None:
    """Equal to TOLERANCE, the alarm times (ALARM_METRICS) to ALARM_TOLERANCE."""
    assert node.keys() == own.keys()
    for key, value in node.items():
        tolerance = ALARM_TOLERANCE if key in ALARM_METRICS else TOLERANCE
        assert own[key] == pytest.approx(value, rel=TOLERANCE, abs=tolerance), (where, key)


def scenario(name, scale=1.0):
    return load_scenario(ROOT / "config" / "scenarios" / f"{name}.yaml").scaled(scale)


def at_rest() -> Pose:
    return Pose(np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3))


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(SCENARIOS))
def test_the_in_process_run_gives_the_node_runs_metrics_and_commands(name, tmp_path):
    case = scenario(name, SCENARIOS[name])
    node = run(case, tmp_path / "node", log=lambda _: None)
    own = run(case, tmp_path / "in_process", log=lambda _: None, in_process=True)
    reports = [read_report(tmp_path / folder / "metrics.json") for folder in ("node", "in_process")]
    for report in reports:
        assert report["metrics"].pop("realtime_factor") > 0.0
    assert_same_metrics(reports[0]["metrics"], reports[1]["metrics"], "run")
    for window, figures in reports[0]["windows"].items():
        assert_same_metrics(figures["metrics"], reports[1]["windows"][window]["metrics"], window)
    assert reports[0]["sources"].keys() == reports[1]["sources"].keys()
    for source, figures in reports[0]["sources"].items():
        assert reports[1]["sources"][source] == pytest.approx(figures, rel=TOLERANCE, abs=TOLERANCE), source
    for field in ("thrust", "azimuth", "power", "voltage", "saturated", "position"):
        np.testing.assert_allclose(own.trace.arrays()[field], node.trace.arrays()[field], rtol=TOLERANCE,
                                   atol=TOLERANCE, equal_nan=True, err_msg=field)
    for field in ("source_power", "source_available"):
        np.testing.assert_allclose(own.trace.power_arrays()[field], node.trace.power_arrays()[field],
                                   rtol=TOLERANCE, atol=TOLERANCE, err_msg=field)
    assert len(own.trace.time) == len(node.trace.time) == round(case.duration * own.vehicle.rate_hz)
    assert not (tmp_path / "in_process" / "run.mcap").exists()


def test_the_node_parameters_are_the_vehicle_file_with_the_scenarios_over_it():
    case = replace(scenario("dp_stuck_azimuth"), parameters={"weights.minimax": 3.0}, method="lp")
    given = node_parameters(case)
    assert given == {**read_parameters(case.vehicle), "trigger": "input", "method": "lp", "weights.minimax": 3.0}
    link = InProcessLink(case)
    assert link.allocator.vehicle == vehicle_from_parameters(given)
    assert link.allocator.method == "lp"


def test_the_wrench_and_the_unallocated_wrench_are_in_the_nodes_frame():
    case = scenario("dp_station_keeping")
    frd, flu = InProcessLink(case), InProcessLink(replace(case, parameters={"frame": "flu"}))
    wrench = np.array([5.0e6, -3.0e6, 0.0, 0.0, 0.0, 4.0e7])            # beyond what the thrusters give
    for link in (frd, flu):
        link.begin(0, 100_000_000, None, np.zeros(6))
    body = frd.step(0, at_rest(), None, wrench, np.zeros(3), 0.0)
    other = flu.step(0, at_rest(), None, wrench_between(wrench, "flu"), np.zeros(3), 0.0)
    assert body.saturated and np.any(np.abs(body.unallocated) > 1.0)
    np.testing.assert_array_equal(other.thrust, body.thrust)
    np.testing.assert_array_equal(other.unallocated, wrench_between(body.unallocated, "flu"))
    reference = Allocator(frd.allocator.vehicle)
    reference.stop()
    reference.allocate(np.zeros(6))
    np.testing.assert_array_equal(reference.allocate(wrench).thrust, body.thrust)


def test_the_battery_voltage_arrives_as_float32_and_a_refused_one_keeps_the_last():
    link = InProcessLink(scenario("rov_battery_sag"))
    link.begin(0, 20_000_000, 16.0, np.zeros(6))
    answer = link.step(0, at_rest(), 14.1, np.zeros(6), np.zeros(3), 0.0)
    assert answer.voltage == float(np.float32(14.1)) != 14.1
    answer = link.step(0, at_rest(), 1000.0, np.zeros(6), np.zeros(3), 0.0)     # outside the T200 tables
    assert answer.voltage == float(np.float32(14.1)) and link.rejected_voltages == 1


def test_a_fault_carries_its_efficiency_or_angle_and_a_refused_one_changes_nothing():
    link = InProcessLink(scenario("dp_stuck_azimuth"))
    assert link.set_fault("azimuth_port", "degraded", 0.5) == "azimuth_port: DEGRADED from the next sample"
    link.set_fault("azimuth_stbd", "stuck", 0.3)
    faults = link.allocator.faults
    assert faults["azimuth_port"].mode == FaultMode.DEGRADED and faults["azimuth_port"].efficiency == 0.5
    assert faults["azimuth_stbd"].mode == FaultMode.STUCK and faults["azimuth_stbd"].angle == 0.3
    with pytest.raises(SimulationError, match="refused"):
        link.set_fault("tunnel_fwd", "degraded", 1.5)
    with pytest.raises(SimulationError, match="refused"):
        link.set_fault("no_such_thruster", "failed", 0.0)
    assert link.allocator.faults == faults
    assert link.clear_faults() == "cleared faults of azimuth_port, azimuth_stbd"
    assert link.allocator.faults == {} and link.clear_faults() == "no faults were set"


def test_a_parameter_is_applied_as_the_node_applies_it():
    case = scenario("dp_stuck_azimuth")
    link = InProcessLink(case)
    name = "actuators.azimuth_port.thrust_rate_max"
    assert link.set_parameter(name, 50000) == f"{name} = 50000"        # an integer for a float key
    expected = vehicle_from_parameters({**node_parameters(case), name: 50000.0})
    assert link.allocator.vehicle == expected
    assert link.parameters[name] == 50000.0 and isinstance(link.parameters[name], float)
    link.set_parameter("weights.minimax", 2.0)                       # the earlier change stays
    assert link.allocator.vehicle == vehicle_from_parameters({**node_parameters(case), name: 50000.0,
                                                              "weights.minimax": 2.0})


@pytest.mark.parametrize(("name", "value", "reason"), [
    ("frame", "flu", "read-only"),
    ("no_such_parameter", 1.0, "not declared"),
    ("actuators.azimuth_port.thrust_rate_max", -1.0, "thrust_rate_max"),
    ("dofs", ["surge", "sway", "yaw", "heave"], "dofs"),
])
def test_a_parameter_the_node_refuses_is_refused_and_changes_nothing(name, value, reason):
    link = InProcessLink(scenario("dp_stuck_azimuth"))
    vehicle, parameters = link.allocator.vehicle, dict(link.parameters)
    with pytest.raises(SimulationError, match=reason):
        link.set_parameter(name, value)
    assert link.allocator.vehicle is vehicle and link.parameters == parameters


@pytest.mark.parametrize("name", ["dp_station_keeping", "rov_thruster_failure"])
def test_the_live_line_keeps_within_the_tables_width_with_every_actuator(name):
    from allocator_pkg.simulation.live_text import WIDTH

    case = scenario(name)
    link = InProcessLink(case)
    link.begin(0, 100_000_000, None, np.zeros(6))
    link.step(0, at_rest(), None, np.array([5.0e6, -3.0e6, 0.0, 0.0, 0.0, 4.0e7]), np.zeros(3), 0.0)
    lines = link.live_line().splitlines()
    assert max(len(line) for line in lines) <= WIDTH
    text = "\n".join(lines)
    assert all(f"{actuator} " in text for actuator in link.allocator.names) and "sat YES" in text
