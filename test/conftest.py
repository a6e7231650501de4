"""Shared fixtures. DDS stays on this machine: discovery on loopback and a domain of our
own unless the caller chose them (set before any rclpy import starts a participant)."""

import os
from pathlib import Path

os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
os.environ.setdefault("ROS_DOMAIN_ID", "42")

import numpy as np
import pytest
from hypothesis import settings

from allocator_pkg import Vehicle, read_parameters, vehicle_from_parameters
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix

# Property tests: `make test` runs the same examples every time (a red CI means a change broke
# something); HYPOTHESIS_PROFILE=explore draws many fresh ones to look for new failures.
settings.register_profile("ci", derandomize=True, max_examples=60)
settings.register_profile("explore", max_examples=1000)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

ROOT = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"


def matrices(vehicle: Vehicle) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """T (controlled rows, every angle zero), the actuator weights and the configured thrust
    ranges of a vehicle of fixed directions, from the configuration alone."""
    t = configuration_matrix(vehicle.actuators, [0.0] * len(vehicle.actuators))[list(vehicle.dof_indices)]
    w = np.array([a.weight for a in vehicle.actuators])
    low = np.array([a.thrust_min for a in vehicle.actuators])
    high = np.array([a.thrust_max for a in vehicle.actuators])
    return t, w, low, high


def vehicle_from(path, **overrides) -> Vehicle:
    """A vehicle from a params file with some parameters replaced (dots in names as '__')."""
    parameters = read_parameters(path)
    parameters.update({key.replace("__", "."): value for key, value in overrides.items()})
    return vehicle_from_parameters(parameters)


@pytest.fixture
def eight_thrusters():
    return DATA / "eight_thrusters.yaml"


class Harness:
    """The node under test and a probe node in one SingleThreadedExecutor, in a context of
    their own. Time is simulated: the probe publishes /clock, so timers fire when the test
    steps the clock, and every timing is deterministic."""

    def __init__(self, context, params_file, parameters=()):
        import rclpy
        from diagnostic_msgs.msg import DiagnosticArray
        from rcl_interfaces.srv import SetParameters, SetParametersAtomically
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.parameter import Parameter
        from rosgraph_msgs.msg import Clock
        from std_srvs.srv import Trigger

        from allocator_msgs.msg import AllocationStatus, ThrusterCommands
        from allocator_msgs.srv import SetActuatorFault
        from allocator_pkg.ros.node import AllocatorNode
        from allocator_pkg.ros.wrench_input import message_type

        self.time_ns = 1_000_000_000
        overrides = [Parameter("use_sim_time", value=True), *parameters]
        self.node = AllocatorNode(context=context, cli_args=["--ros-args", "--params-file", str(params_file)],
                                  parameter_overrides=overrides)
        self.probe = rclpy.create_node("probe", context=context)
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)
        self.executor.add_node(self.probe)
        self.commands, self.status, self.diagnostics = [], [], []
        self.probe.create_subscription(ThrusterCommands, "thruster_commands", self.commands.append, 100)
        self.probe.create_subscription(AllocationStatus, "allocation_status", self.status.append, 100)
        self.probe.create_subscription(DiagnosticArray, "/diagnostics", self.diagnostics.append, 100)
        self._wrench_type = message_type(self.node.runtime.settings)
        self.wrench = self.probe.create_publisher(self._wrench_type, "wrench_command", 10)
        self.clock = self.probe.create_publisher(Clock, "/clock", 10)
        self.fault = self.probe.create_client(SetActuatorFault, "thrust_allocator/set_actuator_fault")
        self.clear = self.probe.create_client(Trigger, "thrust_allocator/clear_faults")
        self.set_parameters = self.probe.create_client(SetParameters, "thrust_allocator/set_parameters")
        self.set_atomically = self.probe.create_client(SetParametersAtomically,
                                                       "thrust_allocator/set_parameters_atomically")
        self._clock_type = Clock
        self.spin_until(lambda: self.wrench.get_subscription_count() > 0 and self.clock.get_subscription_count() > 0)
        self.tick(0)
        # The jump from time 0 to the first /clock makes the timer fire once.
        self.spin_until(lambda: self.node.samples >= 1 and len(self.commands) >= 1 and len(self.status) >= 1)

    def spin_until(self, predicate, timeout=10.0):
        import time
        deadline = time.monotonic() + timeout
        while not predicate():
            if time.monotonic() > deadline:
                raise TimeoutError("condition not reached")
            self.executor.spin_once(timeout_sec=0.01)

    def spin_for(self, seconds):
        import time
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.01)

    def tick(self, periods=1, period=None):
        """Advance simulated time by whole allocation periods; wait for each sample's output."""
        from builtin_interfaces.msg import Time
        period = period if period is not None else self.node.period
        for _ in range(periods):
            expected = self.node.samples + 1
            self.time_ns += round(period * 1e9)
            self._publish_clock(Time(sec=self.time_ns // 10**9, nanosec=self.time_ns % 10**9))
            self.spin_until(lambda expected=expected: self.node.samples >= expected
                            and len(self.commands) >= expected and len(self.status) >= expected)
        if periods == 0:
            self._publish_clock(Time(sec=self.time_ns // 10**9, nanosec=self.time_ns % 10**9))
            self.spin_until(lambda: self.node.get_clock().now().nanoseconds >= self.time_ns)

    def advance(self, seconds):
        """Advance simulated time without waiting for samples (the input trigger samples on input)."""
        from builtin_interfaces.msg import Time
        self.time_ns += round(seconds * 1e9)
        self._publish_clock(Time(sec=self.time_ns // 10**9, nanosec=self.time_ns % 10**9))
        self.spin_until(lambda: self.node.get_clock().now().nanoseconds >= self.time_ns)
        self.spin_for(0.05)

    def diagnostics_after_a_second(self):
        """Step the clock one second and return the key-values of the diagnostics that follow."""
        count = len(self.diagnostics)
        self.tick(round(1.0 / self.node.period))
        self.spin_until(lambda: len(self.diagnostics) > count)
        return {kv.key: kv.value for kv in self.diagnostics[-1].status[0].values}

    def sent(self, publisher, message):
        """Publish a message to the node and spin until it has taken it."""
        received = self.node.wrenches_received
        publisher.publish(message)
        self.spin_until(lambda: self.node.wrenches_received > received)

    def _publish_clock(self, stamp):
        self.clock.publish(self._clock_type(clock=stamp))

    def send_wrench(self, values, frame_id=None):
        """A Wrench, or a WrenchStamped in ``frame_id`` (default: the node's base_frame)."""
        from allocator_pkg.ros.conversions import array_to_wrench
        message = self._wrench_type()
        if hasattr(message, "header"):
            message.header.frame_id = self.node.runtime.settings.base_frame if frame_id is None else frame_id
            message.wrench = array_to_wrench(values)
        else:
            message = array_to_wrench(values)
        self.sent(self.wrench, message)

    def call(self, client, request):
        self.spin_until(client.service_is_ready)
        future = client.call_async(request)
        self.spin_until(future.done)
        return future.result()

    def close(self):
        self.executor.shutdown()
        self.node.destroy_node()
        self.probe.destroy_node()


@pytest.fixture
def ros_context():
    """A fresh rclpy context per test, shut down afterwards."""
    import rclpy
    context = rclpy.Context()
    rclpy.init(context=context)
    yield context
    rclpy.try_shutdown(context=context)


@pytest.fixture
def harness(ros_context, request):
    """Harness on the params file a test names with @pytest.mark.params(path, **overrides)."""
    from rclpy.parameter import Parameter
    marker = request.node.get_closest_marker("params")
    path = marker.args[0] if marker else ROOT / "config" / "example1_rov.yaml"
    values = marker.kwargs if marker else {}
    overrides = [Parameter(name.replace("__", "."), value=value) for name, value in values.items()]
    h = Harness(ros_context, path, overrides)
    yield h
    h.close()
