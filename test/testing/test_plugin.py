"""The pytest plugin: the allocator_harness fixture as a user's test meets it (the README's
example run by pytest from the installed entry point, its teardown), each of the harness's
calls against figures derived by hand, and the DDS defaults."""

import os
import re
import subprocess
import sys

import pytest
from conftest import DATA, ROOT

from allocator_pkg.testing import plugin

EXAMPLE = ROOT / "config" / "example1_rov.yaml"

TEARDOWN = '''
made = []


def test_a_harness_is_made(allocator_harness):
    made.append(allocator_harness({path!r}, node="lifecycle"))
    assert made[0].node.context.ok()


def test_its_context_is_shut_down_after_the_test():
    assert not made[0].node.context.ok()
'''


def readme_example() -> str:
    text = (ROOT / "README.md").read_text()
    section = text[text.index("## Testing your vehicle"):]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_the_readme_example_passes_under_pytest_with_the_installed_plugin(tmp_path):
    code = readme_example()
    assert len(code.splitlines()) == 10
    (tmp_path / "test_readme_example.py").write_text(code)
    (tmp_path / "test_teardown.py").write_text(TEARDOWN.format(path=str(EXAMPLE)))
    env = {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
           "ROS_DOMAIN_ID": os.environ.get("ROS_DOMAIN_ID", plugin.own_domain(os.getpid()))}
    result = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(tmp_path)],
                            cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "3 passed" in result.stdout


def test_dds_defaults_to_loopback_and_a_domain_of_its_own_unless_set(monkeypatch):
    monkeypatch.delenv("ROS_AUTOMATIC_DISCOVERY_RANGE", raising=False)
    monkeypatch.delenv("ROS_DOMAIN_ID", raising=False)
    plugin.pytest_configure(None)
    assert os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] == "LOCALHOST"
    assert os.environ["ROS_DOMAIN_ID"] == plugin.own_domain(os.getpid())
    monkeypatch.setenv("ROS_DOMAIN_ID", "7")
    plugin.pytest_configure(None)
    assert os.environ["ROS_DOMAIN_ID"] == "7"
    assert {int(plugin.own_domain(pid)) for pid in range(1000)} == set(range(1, 101))


def test_heave_capability_by_hand_and_with_a_vertical_thruster_failed(allocator_harness):
    """Four vertical thrusters of 40 N up and 30 N down, symmetric about the centre: 160 N and
    120 N of heave. With t5 failed, holding roll and pitch at zero leaves t6 = t7 and t8 = 0
    (sum of y F = 0, sum of x F = 0 over t6, t7, t8): 80 N."""
    bench = allocator_harness(DATA / "eight_thrusters.yaml")
    scale, wrench = bench.capability([0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    assert scale == pytest.approx(160.0, rel=1e-6)
    assert wrench == pytest.approx([0.0, 0.0, 160.0, 0.0, 0.0, 0.0], abs=1e-6)
    assert bench.capability([0.0, 0.0, -2.0, 0.0, 0.0, 0.0])[0] == pytest.approx(60.0, rel=1e-6)
    assert bench.set_fault("t5", plugin_mode("failed")) == (True, "t5: FAILED from the next sample")
    assert bench.capability([0.0, 0.0, 1.0, 0.0, 0.0, 0.0])[0] == pytest.approx(80.0, rel=1e-6)
    with pytest.raises(ValueError, match="no component in the controlled DOFs"):
        bench.capability([0.0] * 6)


def plugin_mode(name):
    from allocator_pkg import FaultMode
    return FaultMode[name.upper()]


def test_faults_by_name_or_mode_and_parameters_as_a_whole(allocator_harness):
    rov = allocator_harness(EXAMPLE, parameters={"wrench_timeout": 0.0})
    assert rov.set_fault("main_stbd", "degraded", efficiency=0.5) == (True, "main_stbd: DEGRADED from the next "
                                                                            "sample")
    assert rov.set_fault("azimuth_fwd", "STUCK", angle=0.4)[0]
    success, message = rov.set_fault("bow", "failed")
    assert not success and "bow" in message
    with pytest.raises(ValueError, match="unknown fault mode 'broken'; modes: nominal, degraded, failed, stuck"):
        rov.set_fault("main_port", "broken")
    rov.step(0.1)
    assert list(rov.commands[-1].mode) == [3, 0, 0, 1]
    assert rov.commands[-1].azimuth[0] == pytest.approx(0.4)
    assert rov.clear_faults() == "cleared faults of azimuth_fwd, main_stbd"
    assert rov.set_parameters({"dofs": ["surge", "yaw"], "weights.slack": [1.0e6, 1.0e6]}) == (True, "")
    successful, reason = rov.set_parameters({"dofs": ["surge", "yaw"], "weights.minimax": 2.0,
                                             "actuators.main_port.thrust_max": -1.0})
    assert not successful and "thrust_max" in reason
    assert rov.node.allocator.vehicle.dofs == ("surge", "yaw")


@pytest.mark.parametrize("node", ["plain", "lifecycle"])
def test_wrenches_as_arrays_and_messages_on_both_nodes(allocator_harness, node):
    from geometry_msgs.msg import Wrench, WrenchStamped

    from allocator_pkg.ros.conversions import array_to_wrench
    rov = allocator_harness(EXAMPLE, parameters={"wrench_type": "wrench_stamped", "wrench_timeout": 0.0},
                            node=node)
    rov.send_wrench([50.0, 0.0, 0.0, 0.0, 0.0, 5.0])
    rov.step(0.04)
    assert rov.status[-1].requested.force.x == 50.0 and rov.status[-1].requested.torque.z == 5.0
    rov.send_wrench(array_to_wrench([60.0, 1.0, 0.0, 0.0, 0.0, 0.0]))
    rov.step(0.02)
    assert rov.status[-1].requested.force.x == 60.0
    stamped = WrenchStamped(wrench=Wrench(force=array_to_wrench([70.0, 0, 0, 0, 0, 0]).force))
    stamped.header.frame_id = "base_link"
    rov.send_wrench(stamped)
    rov.step(0.02)
    assert rov.status[-1].requested.force.x == 70.0
    stamped.header.frame_id = "odom"
    rov.send_wrench(stamped)
    rov.step(0.02)
    assert rov.status[-1].requested.force.x == 70.0                  # the wrong frame is rejected
    assert rov.node.runtime.counters.rejected_frames == 1
    assert len(rov.commands) == len(rov.status) == rov.node.samples


def test_an_unknown_node_kind_is_named(allocator_harness):
    with pytest.raises(ValueError, match="node must be one of plain, lifecycle, not 'managed'"):
        allocator_harness(EXAMPLE, node="managed")


def test_a_relative_params_file_is_found_next_to_the_test_then_in_the_current_directory(tmp_path, monkeypatch):
    tests = tmp_path / "tests"
    (tests / "config").mkdir(parents=True)
    beside = tests / "config" / "rov.yaml"
    beside.write_text(EXAMPLE.read_text())
    monkeypatch.chdir(ROOT)
    assert plugin.params_path("config/rov.yaml", tests) == beside
    assert plugin.params_path("config/example1_rov.yaml", tests) == EXAMPLE
    assert plugin.params_path(str(EXAMPLE), tests) == EXAMPLE
    with pytest.raises(FileNotFoundError, match=re.escape(f"no such params file: config/none.yaml (looked for "
                                                          f"{tests}/config/none.yaml and {ROOT}/config/none.yaml)")):
        plugin.params_path("config/none.yaml", tests)


def test_the_readme_example_runs_from_another_directory_with_its_vehicle_beside_it(tmp_path):
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "example1_rov.yaml").write_text(EXAMPLE.read_text())
    (tmp_path / "test_readme_example.py").write_text(readme_example())
    env = {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
           "ROS_DOMAIN_ID": os.environ.get("ROS_DOMAIN_ID", plugin.own_domain(os.getpid()))}
    result = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                             str(tmp_path / "test_readme_example.py")],
                            cwd="/", env=env, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "1 passed" in result.stdout


def test_a_params_file_not_found_names_each_place_it_looked_at_once(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FileNotFoundError) as raised:
        plugin.params_path("none.yaml", tmp_path)
    assert str(raised.value) == f"no such params file: none.yaml (looked for {tmp_path}/none.yaml)"


def test_two_harnesses_of_different_vehicles_run_side_by_side_each_in_a_namespace_of_its_own(allocator_harness):
    """Same domain, same node name: each harness's probe takes only its own node's commands and
    status, and each node only its own clock."""
    rov = allocator_harness(EXAMPLE)
    bench = allocator_harness(DATA / "eight_thrusters.yaml")
    assert rov.node.get_namespace().startswith("/run_") and bench.node.get_namespace().startswith("/run_")
    assert rov.node.get_namespace() != bench.node.get_namespace()
    rov.step(0.2)
    bench.step(0.5)
    assert rov.actuators == ["azimuth_fwd", "azimuth_aft", "main_port", "main_stbd"]
    assert bench.actuators == [f"t{i}" for i in range(1, 9)]
    assert {tuple(message.name) for message in rov.commands} == {tuple(rov.actuators)}
    assert {tuple(message.name) for message in bench.commands} == {tuple(bench.actuators)}
    assert len(rov.commands) == rov.node.samples and len(bench.commands) == bench.node.samples
    assert rov.node.get_clock().now().nanoseconds == rov.time_ns


def test_the_harness_stops_at_a_foreign_node_in_its_namespace_and_names_it(allocator_harness):
    import rclpy

    from allocator_msgs.msg import ThrusterCommands
    from allocator_pkg.testing.harness import ForeignNodeError
    rov = allocator_harness(EXAMPLE)
    namespace = rov.node.get_namespace()
    intruder = rclpy.create_node("bluerov2_allocator", namespace=namespace, context=rov.node.context)
    try:
        commands = intruder.create_publisher(ThrusterCommands, "thruster_commands", 10)
        rov.spin_until(lambda: commands.get_subscription_count() > 0)
        commands.publish(ThrusterCommands(name=[f"thruster_{i}" for i in range(1, 9)]))
        with pytest.raises(ForeignNodeError) as raised:
            rov.spin_for(2.0)
        assert str(raised.value) == (
            "thruster commands of actuators thruster_1, thruster_2, thruster_3, thruster_4, thruster_5, thruster_6, "
            "thruster_7, thruster_8 (this vehicle's: azimuth_fwd, azimuth_aft, main_port, main_stbd): not from "
            f"{namespace}/thrust_allocator of this harness; other nodes publishing: {namespace}/bluerov2_allocator "
            f"on {namespace}/thruster_commands")
    finally:
        intruder.destroy_node()
