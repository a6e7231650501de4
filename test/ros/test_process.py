"""allocator_node and allocator-ctl as separate processes, over real DDS on loopback, each test's
nodes in the test's own namespace (the ``namespace`` fixture, which ``ros_context`` shares)."""

import contextlib
import math
import signal
import subprocess
import time

import pytest
from conftest import ROOT

from allocator_pkg.ros.process import child_process, executable, namespace_arguments, node_command

EXAMPLE = ROOT / "config" / "example1_rov.yaml"

pytestmark = pytest.mark.slow


def ctl(namespace, *arguments, timeout=30):
    """allocator-ctl ``arguments`` to the allocator in ``namespace``."""
    return subprocess.run([str(executable("allocator-ctl")), "--namespace", namespace, *arguments],
                          capture_output=True, text=True, timeout=timeout)


@pytest.fixture
def node_process(namespace):
    with child_process(node_command(EXAMPLE, *namespace_arguments(namespace))) as process:
        yield process


class Listener:
    def __init__(self, context):
        import rclpy
        from rclpy.qos import QoSProfile, ReliabilityPolicy

        from allocator_msgs.msg import ThrusterCommands
        from allocator_pkg.ros.node_client import Controller
        self.node = rclpy.create_node("listener", context=context)
        self.controller = Controller(self.node)
        self.commands = []
        self.node.create_subscription(ThrusterCommands, "thruster_commands", self.commands.append,
                                      QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE))
        from rclpy.executors import SingleThreadedExecutor
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)

    def spin_until(self, predicate, timeout=20.0):
        deadline = time.monotonic() + timeout
        while not predicate():
            assert time.monotonic() < deadline, "timed out"
            self.executor.spin_once(timeout_sec=0.05)


def test_node_process_runs_takes_faults_and_stops_cleanly_on_sigterm(ros_context, node_process):
    listener = Listener(ros_context)
    listener.spin_until(lambda: len(listener.commands) > 3)
    assert list(listener.commands[-1].name) == ["azimuth_fwd", "azimuth_aft", "main_port", "main_stbd"]
    from allocator_pkg.ros.conversions import array_to_wrench
    wrench = array_to_wrench([120.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    listener.spin_until(lambda: listener.controller.wrench.get_subscription_count() > 0)

    def driven():
        listener.controller.wrench.publish(wrench)
        return listener.commands[-1].thrust[2] > 10.0

    listener.spin_until(driven)
    response = listener.controller.set_fault("main_port", "failed")
    assert response.success, response.message

    def compensated():
        listener.controller.wrench.publish(wrench)
        return listener.commands[-1].mode[2] == 2 and sum(listener.commands[-1].thrust) > 60.0

    listener.spin_until(compensated)
    assert listener.commands[-1].thrust[2] == 0.0
    count = len(listener.commands)
    node_process.send_signal(signal.SIGTERM)
    listener.spin_until(lambda: node_process.poll() is not None and len(listener.commands) > count, timeout=20.0)
    listener.spin_until(lambda: all(t == 0.0 for t in listener.commands[-1].thrust), timeout=5.0)
    assert node_process.wait(timeout=10) == 0
    assert "stopped: published zero thrust" in node_process.output()


def test_node_process_stops_cleanly_on_sigint(ros_context, node_process):
    """Ctrl-C: one zero-thrust command, exit code 0 (SIGINT during a solve: test_sparse_rows)."""
    listener = Listener(ros_context)
    listener.spin_until(lambda: len(listener.commands) > 3)
    count = len(listener.commands)
    node_process.send_signal(signal.SIGINT)
    listener.spin_until(lambda: node_process.poll() is not None and len(listener.commands) > count, timeout=20.0)
    assert node_process.wait(timeout=10) == 0
    assert all(t == 0.0 for t in listener.commands[-1].thrust)
    assert "stopped: published zero thrust" in node_process.output()


def test_invalid_configuration_exits_with_a_clear_message(tmp_path, namespace):
    bad = tmp_path / "bad.yaml"
    bad.write_text(EXAMPLE.read_text().replace("thrust_max: 300.0", "thrust_max: -300.0", 1))
    with child_process(node_command(bad, *namespace_arguments(f"{namespace}/rov1"))) as process:
        process.wait(timeout=30)
    output = process.output()
    assert process.returncode == 1
    assert f"{namespace}/rov1/thrust_allocator: invalid configuration" in output
    assert "actuators.main_port.thrust_max: must be > 0" in output
    assert f"parameters found for {namespace}/rov1/thrust_allocator: actuators.azimuth_aft.{{" in output
    assert "actuators.names, dofs, method, rate_hz, weights.minimax" in output
    assert "Traceback" not in output


def test_a_section_that_does_not_apply_is_named_with_the_node_full_name(tmp_path, namespace):
    """A file keyed 'thrust_allocator:' does not apply to <namespace>/rov1/thrust_allocator."""
    keyed_by_name = tmp_path / "keyed_by_name.yaml"
    keyed_by_name.write_text(EXAMPLE.read_text().replace("/**:", "thrust_allocator:", 1))
    with child_process(node_command(keyed_by_name, *namespace_arguments(f"{namespace}/rov1"))) as process:
        process.wait(timeout=30)
    output = process.output()
    assert process.returncode == 1
    assert (f"{namespace}/rov1/thrust_allocator: invalid configuration:\n  actuators.names: required key is "
            "missing") in output
    assert (f"no allocator parameters found for {namespace}/rov1/thrust_allocator: a params file section applies "
            "only to the nodes its key matches; key it '/**:' (any node) or '/**/thrust_allocator:'") in output


def test_every_shipped_file_runs_namespaced_and_renamed(ros_context, namespace):
    from allocator_msgs.msg import ThrusterCommands
    from allocator_pkg import read_parameters
    files = sorted((ROOT / "config").glob("*.yaml"))
    with contextlib.ExitStack() as stack:
        processes = {path: stack.enter_context(child_process(node_command(
            path, "-r", f"__ns:={namespace}/{path.stem}", "-r", "__node:=alloc")))
                     for path in files}
        listener = Listener(ros_context)
        received = {path: [] for path in files}
        for path in files:
            listener.node.create_subscription(ThrusterCommands, f"{namespace}/{path.stem}/thruster_commands",
                                              received[path].append, 10)
        listener.spin_until(lambda: all(received.values()), timeout=60.0)
    outputs = {path: process.output() for path, process in processes.items()}
    logger = namespace.strip("/")
    for path in files:
        assert list(received[path][-1].name) == read_parameters(path)["actuators.names"], path
        assert (f"[{logger}.{path.stem}.alloc]: wrench from {namespace}/{path.stem}/wrench_command "
                "(geometry_msgs/msg/Wrench") in outputs[path]
        assert (f"publishing {namespace}/{path.stem}/thruster_commands, {namespace}/{path.stem}/allocation_status, "
                f"{namespace}/{path.stem}/alloc/thrust_markers, /diagnostics") in outputs[path]


def test_wrench_command_is_best_effort_and_qos_overrides_change_it(ros_context, namespace):
    """The default takes reliable and best-effort controllers; the standard qos_overrides parameters work."""
    from geometry_msgs.msg import Wrench
    from rclpy.qos import QoSProfile, ReliabilityPolicy
    with child_process(node_command(EXAMPLE, "-r", f"__ns:={namespace}/qa")), \
            child_process(node_command(EXAMPLE, "-r", f"__ns:={namespace}/qb", parameters=[
                f"qos_overrides.{namespace}/qb/wrench_command.subscription.reliability:=reliable"])) as overridden:
        listener = Listener(ros_context)
        node = listener.node

        def subscription(topic):
            found = node.get_subscriptions_info_by_topic(topic)
            return found[0].qos_profile if found else None

        listener.spin_until(lambda: subscription(f"{namespace}/qa/wrench_command")
                            and subscription(f"{namespace}/qb/wrench_command"))
        assert subscription(f"{namespace}/qa/wrench_command").reliability == ReliabilityPolicy.BEST_EFFORT
        assert subscription(f"{namespace}/qb/wrench_command").reliability == ReliabilityPolicy.RELIABLE
        sensor_data = node.create_publisher(Wrench, f"{namespace}/qa/wrench_command",
                                            QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT))
        listener.spin_until(lambda: sensor_data.get_subscription_count() == 1)
    assert "Traceback" not in overridden.output()


def test_a_publisher_of_the_other_wrench_type_is_reported_once(ros_context, namespace):
    from diagnostic_msgs.msg import DiagnosticArray
    from geometry_msgs.msg import WrenchStamped
    with child_process(node_command(EXAMPLE, *namespace_arguments(f"{namespace}/typed"))) as process:
        listener = Listener(ros_context)
        import rclpy
        controller = rclpy.create_node("controller", namespace=f"{namespace}/typed", context=ros_context,
                                       use_global_arguments=False)        # not in the context's namespace
        listener.executor.add_node(controller)
        controller.create_publisher(WrenchStamped, "wrench_command", 10)
        reports = []

        def reported(message):
            reports.extend(kv.value for status in message.status for kv in status.values
                           if status.name == f"{namespace}/typed/thrust_allocator: thrust allocation"
                           and kv.key == "wrong-type publishers")

        listener.node.create_subscription(DiagnosticArray, f"{namespace}/typed/diagnostics", reported, 10)
        listener.spin_until(lambda: reports.count(f"{namespace}/typed/controller (geometry_msgs/msg/WrenchStamped)")
                            >= 3,
                            timeout=30.0)
    assert process.output().count(f"a publisher of another type on {namespace}/typed/wrench_command never connects: "
                                  f"{namespace}/typed/controller (geometry_msgs/msg/WrenchStamped); this node takes "
                                  "geometry_msgs/msg/Wrench (wrench_type: wrench)") == 1


def test_the_input_trigger_answers_a_wrench_without_waiting_for_the_timer(ros_context, namespace):
    """At 0.2 Hz a timer would wait up to 5 s; the input trigger allocates the wrench on arrival.
    The bound is loose on purpose (a shared machine): bench/node.py measures the latency."""
    from allocator_msgs.msg import AllocationStatus
    from allocator_pkg.ros.conversions import array_to_wrench
    with child_process(node_command(EXAMPLE, "-r", f"__ns:={namespace}/fast",
                                    parameters=["trigger:=input", "rate_hz:=0.2", "wrench_timeout:=0.0"])):
        listener = Listener(ros_context)
        answers = []
        listener.node.create_subscription(AllocationStatus, f"{namespace}/fast/allocation_status", answers.append,
                                          10)
        publisher = listener.node.create_publisher(type(array_to_wrench([0.0] * 6)),
                                                   f"{namespace}/fast/wrench_command", 10)
        listener.spin_until(lambda: publisher.get_subscription_count() > 0
                            and listener.node.count_publishers(f"{namespace}/fast/allocation_status") > 0)
        deadline = time.monotonic() + 1.0                 # both ways matched: no sample comes before a wrench
        listener.spin_until(lambda: time.monotonic() > deadline)
        sent = time.time()
        publisher.publish(array_to_wrench([33.0, 0.0, 0.0, 0.0, 0.0, 0.0]))
        listener.spin_until(lambda: answers and answers[-1].requested.force.x == 33.0, timeout=10.0)
        answered = answers[-1].header.stamp.sec + answers[-1].header.stamp.nanosec * 1e-9
        assert answered - sent < 2.0


def test_the_geometry_comes_from_the_robot_description_topic(ros_context, tmp_path, namespace):
    """robot_state_publisher's way: a transient-local robot_description, here from this process."""
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
    from std_msgs.msg import String
    from test_urdf import BLUEROV, urdf_of, without_geometry

    from allocator_msgs.msg import ThrusterCommands
    from allocator_pkg import read_parameters
    from allocator_pkg.configuration.params_file import write_parameters
    params = write_parameters(tmp_path / "bluerov2.yaml", without_geometry(BLUEROV, frame="flu"))
    listener = Listener(ros_context)
    latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    description = listener.node.create_publisher(String, f"{namespace}/urdf/robot_description", latched)
    description.publish(String(data=urdf_of(read_parameters(BLUEROV), "flu")))
    with child_process(node_command(params, "-r", f"__ns:={namespace}/urdf")) as process:
        commands = []
        listener.node.create_subscription(ThrusterCommands, f"{namespace}/urdf/thruster_commands", commands.append,
                                          10)
        listener.spin_until(lambda: commands, timeout=30.0)
    output = process.output()
    assert list(commands[-1].name) == [f"thruster_{i}" for i in range(1, 9)]
    assert f"waiting for {namespace}/urdf/robot_description" in output
    assert f"over 8 actuators (geometry from {namespace}/urdf/robot_description)" in output


def test_allocator_ctl_commands(node_process, tmp_path, namespace):
    result = ctl(namespace, "fault", "main_port", "degraded", "0.5")
    assert result.returncode == 0, result.stderr
    assert "main_port: DEGRADED" in result.stdout
    assert result.stderr.strip() == f"allocator-ctl: reached {namespace}/thrust_allocator"
    result = ctl(namespace, "fault", "main_port", "degraded")
    assert result.returncode == 2 and "needs a value" in result.stderr
    result = ctl(namespace, "fault", "main_port", "stuck", "0.3")
    assert result.returncode == 1 and "these can be stuck" in result.stdout
    assert "cleared faults of main_port" in ctl(namespace, "clear").stdout
    result = ctl(namespace, "group", "bus")
    assert result.returncode == 1 and result.stdout.strip() == "unknown redundancy group 'bus'; groups: none"
    result = ctl(namespace, "tie", "bt_ab", "open")
    assert result.returncode == 1 and result.stdout.strip() == "unknown bus tie 'bt_ab'; bus ties: none"
    assert ctl(namespace, "params", "set", "rate_hz=20", "weights.minimax=0.5").stdout.strip() == "applied"
    rejected = ctl(namespace, "params", "set", "rate_hz=-1")
    assert rejected.returncode == 1 and "rate_hz" in rejected.stdout
    values = ctl(namespace, "params", "get", "rate_hz", "weights.minimax").stdout
    assert "rate_hz: 20" in values and "weights.minimax: 0.5" in values
    table = tmp_path / "samples.csv"
    wrench = subprocess.Popen([str(executable("allocator-ctl")), "--namespace", namespace, "wrench", "80", "0", "0",
                               "0", "0", "5", "--rate", "20", "--duration", "6"], stdout=subprocess.DEVNULL)
    recording = tmp_path / "samples.mcap"
    echo = ctl(namespace, "echo", "--duration", "4", "--csv", str(table), "--mcap", str(recording))
    wrench.wait(timeout=30)
    assert echo.returncode == 0, echo.stderr
    assert f"allocator-ctl: echoing {namespace}/thrust_allocator" in echo.stderr
    assert "main_stbd" in echo.stdout and "sat" in echo.stdout
    rows = table.read_text().splitlines()
    assert rows[0].startswith("stamp,azimuth_fwd.thrust")
    assert len(rows) > 10
    thrust = [float(row.split(",")[9]) for row in rows[1:]]            # main_port.thrust
    assert max(thrust) > 10.0 and all(math.isfinite(t) for t in thrust)
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    with open(recording, "rb") as stream:
        topics = {}
        for _, channel, _, message in make_reader(stream, decoder_factories=[DecoderFactory()]).iter_decoded_messages():
            topics.setdefault(channel.topic, []).append(message)
    wrench_topic, commands = f"{namespace}/wrench_command", f"{namespace}/thruster_commands"
    assert {wrench_topic, commands, f"{namespace}/allocation_status"} == set(topics)
    assert topics[wrench_topic][-1].force.x == 80.0 and topics[wrench_topic][-1].torque.z == 5.0
    assert len(topics[commands]) == len(rows) - 1


def test_allocator_ctl_fails_a_redundancy_group_and_clears_it(namespace):
    with child_process(node_command(ROOT / "config" / "dp_vessel.yaml", *namespace_arguments(namespace))):
        result = ctl(namespace, "group", "switchboard_a")
        assert result.returncode == 0, result.stderr
        assert result.stdout.strip() == ("switchboard_a: azimuth_stbd, tunnel_fwd FAILED and swbd_a at 0 kW from the "
                                         "next sample")
        assert ctl(namespace, "clear").stdout.strip() == ("cleared faults of azimuth_stbd, tunnel_fwd (redundancy "
                                                          "groups switchboard_a)")


def test_the_readme_allocator_ctl_lines_run_against_a_node_as_written(namespace):
    """Every allocator-ctl line of the README that ends by itself (the wrench line with its
    --duration, fault, clear, capability, params set), split as a shell splits it, against
    the node of config/default.yaml; then params get and unknown names."""
    import re
    import shlex

    readme = (ROOT / "README.md").read_text()
    lines = [line.split("#")[0].strip() for line in re.findall(r"^\.venv/bin/allocator-ctl .*$", readme, re.M)]
    runnable = [line for line in lines if line.split()[1] != "echo"]
    assert {line.split()[1] for line in runnable} == {"wrench", "fault", "clear", "capability", "params"}
    with child_process(node_command(ROOT / "config" / "default.yaml", *namespace_arguments(namespace))):
        for line in runnable:
            arguments = shlex.split(line)[1:]
            result = ctl(namespace, *arguments)
            assert result.returncode == 0, f"{line}: {result.stdout}{result.stderr}"
        values = ctl(namespace, "params", "get", "dofs", "weights.slack").stdout
        assert "dofs: ['surge', 'yaw']" in values and "weights.slack: [1000000.0, 1000000.0]" in values
        unknown = ctl(namespace, "params", "set", "weights.minmax=1.0")
        assert unknown.returncode == 1
        assert (f"'weights.minmax' is not a parameter of {namespace}/thrust_allocator; did you mean "
                "weights.minimax?" in unknown.stderr)


def test_wrench_and_echo_say_what_to_check_when_no_node_answers(namespace):
    check = ("is the node running, with the same ROS_DOMAIN_ID and ROS_AUTOMATIC_DISCOVERY_RANGE, and --namespace "
             "and --node its namespace and name?")
    wrench = ctl(namespace, "--timeout", "1", "wrench", "10", "0", "0", "0", "0", "0", "--duration", "1")
    assert wrench.returncode == 1
    assert wrench.stderr.strip() == f"allocator-ctl: no node takes {namespace}/wrench_command ({check})"
    echo = ctl(namespace, "--timeout", "1", "echo", "--duration", "1")
    assert echo.returncode == 1 and echo.stdout == ""
    assert echo.stderr.strip() == f"allocator-ctl: no node publishes {namespace}/allocation_status ({check})"


def test_a_one_shot_command_ends_its_executor_before_its_node_and_says_which_node_it_reached(node_process,
                                                                                                  namespace):
    """The executor the service call made is shut down before the node and the context end: none
    is left with its signal guard for the garbage collector to destroy after them, at exit, where
    the guard's handle may be gone already ("Exception ignored ... InvalidHandle")."""
    import sys
    script = ("import gc, sys\n"
              "from rclpy.executors import Executor\n"
              "from allocator_pkg.cli import allocator_ctl as ctl\n"
              "code = ctl.main(sys.argv[1:])\n"
              "left = [o for o in gc.get_objects() if isinstance(o, Executor) and o._sigint_gc is not None]\n"
              "print(f'executors left: {len(left)}')\n"
              "sys.exit(code)\n")
    result = subprocess.run([sys.executable, "-c", script, "--namespace", namespace, "clear"], capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["no faults were set", "executors left: 0"]
    assert result.stderr.strip() == f"allocator-ctl: reached {namespace}/thrust_allocator"


def test_echo_names_the_node_it_echoes_and_ends_cleanly_on_sigterm(node_process, namespace):
    echo = subprocess.Popen([str(executable("allocator-ctl")), "--namespace", namespace, "echo", "--rate", "20"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        first = echo.stdout.readline()
        echo.send_signal(signal.SIGTERM)
        rest, errors = echo.communicate(timeout=30)
    finally:
        echo.kill()
        echo.wait()
    assert first.startswith("azimuth_fwd")
    assert echo.returncode == 0, errors
    assert errors.strip() == f"allocator-ctl: echoing {namespace}/thrust_allocator ({namespace}/allocation_status)"
    assert "Traceback" not in rest + errors


def test_a_command_warns_when_several_nodes_have_the_allocator_name(namespace):
    with child_process(node_command(EXAMPLE, *namespace_arguments(namespace))), \
            child_process(node_command(EXAMPLE, *namespace_arguments(namespace))):
        deadline = time.monotonic() + 30.0
        while "warning" not in (result := ctl(namespace, "clear")).stderr and time.monotonic() < deadline:
            pass
    assert result.returncode == 0, result.stderr
    assert (f"allocator-ctl: warning: 2 nodes are named {namespace}/thrust_allocator in this domain; any of them "
            "may have answered (give each run a namespace of its own)") in result.stderr
