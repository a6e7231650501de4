"""allocator_node and allocator-ctl as separate processes, over real DDS on loopback."""

import math
import os
import signal
import subprocess
import sys
import time

import pytest
from conftest import ROOT

EXAMPLE = ROOT / "config" / "example1_rov.yaml"
BIN = os.path.dirname(sys.executable)

pytestmark = pytest.mark.slow


def start_node(params_file, *extra):
    return subprocess.Popen([os.path.join(BIN, "allocator_node"), "--ros-args", "--params-file", str(params_file),
                             *extra], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def ctl(*arguments, timeout=30):
    return subprocess.run([os.path.join(BIN, "allocator-ctl"), *arguments], capture_output=True, text=True,
                          timeout=timeout)


@pytest.fixture
def node_process():
    process = start_node(EXAMPLE)
    yield process
    if process.poll() is None:
        process.kill()
        process.wait()


class Listener:
    def __init__(self, context):
        import rclpy
        from rclpy.qos import QoSProfile, ReliabilityPolicy

        from allocator_msgs.msg import ThrusterCommands
        from allocator_pkg.ctl import Controller
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
    from allocator_pkg.conversions import array_to_wrench
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
    assert "stopped: published zero thrust" in node_process.stdout.read()


def test_node_process_stops_cleanly_on_sigint(ros_context, node_process):
    """Ctrl-C: one zero-thrust command, exit code 0 (SIGINT during a solve: test_sparse_rows)."""
    listener = Listener(ros_context)
    listener.spin_until(lambda: len(listener.commands) > 3)
    count = len(listener.commands)
    node_process.send_signal(signal.SIGINT)
    listener.spin_until(lambda: node_process.poll() is not None and len(listener.commands) > count, timeout=20.0)
    assert node_process.wait(timeout=10) == 0
    assert all(t == 0.0 for t in listener.commands[-1].thrust)
    assert "stopped: published zero thrust" in node_process.stdout.read()


def test_invalid_configuration_exits_with_a_clear_message(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(EXAMPLE.read_text().replace("thrust_max: 300.0", "thrust_max: -300.0", 1))
    process = start_node(bad)
    output, _ = process.communicate(timeout=30)
    assert process.returncode == 1
    assert "invalid configuration" in output
    assert "actuators.main_port.thrust_max: must be > 0" in output
    assert "Traceback" not in output


def test_allocator_ctl_commands(node_process, tmp_path):
    result = ctl("fault", "main_port", "degraded", "0.5")
    assert result.returncode == 0, result.stderr
    assert "main_port: DEGRADED" in result.stdout
    result = ctl("fault", "main_port", "degraded")
    assert result.returncode == 2 and "needs a value" in result.stderr
    result = ctl("fault", "main_port", "stuck", "0.3")
    assert result.returncode == 1 and "these can be stuck" in result.stdout
    assert "cleared faults of main_port" in ctl("clear").stdout
    assert ctl("params", "set", "rate_hz=20", "weights.minimax=0.5").stdout.strip() == "applied"
    rejected = ctl("params", "set", "rate_hz=-1")
    assert rejected.returncode == 1 and "rate_hz" in rejected.stdout
    values = ctl("params", "get", "rate_hz", "weights.minimax").stdout
    assert "rate_hz: 20" in values and "weights.minimax: 0.5" in values
    table = tmp_path / "samples.csv"
    wrench = subprocess.Popen([os.path.join(BIN, "allocator-ctl"), "wrench", "80", "0", "0", "0", "0", "5",
                               "--rate", "20", "--duration", "6"], stdout=subprocess.DEVNULL)
    echo = ctl("echo", "--duration", "4", "--csv", str(table))
    wrench.wait(timeout=30)
    assert echo.returncode == 0
    assert "main_stbd" in echo.stdout and "sat" in echo.stdout
    rows = table.read_text().splitlines()
    assert rows[0].startswith("stamp,azimuth_fwd.thrust")
    assert len(rows) > 10
    thrust = [float(row.split(",")[9]) for row in rows[1:]]            # main_port.thrust
    assert max(thrust) > 10.0 and all(math.isfinite(t) for t in thrust)
