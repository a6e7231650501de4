"""allocator_lifecycle_node as a separate process, driven through the lifecycle_msgs services:
configure checks the vehicle, activate starts commands, deactivate commands zero thrust and
stops, cleanup frees everything, shutdown from any state ends the process cleanly."""

import signal
import time

import pytest
from conftest import ROOT

from allocator_pkg.ros.process import child_process, namespace_arguments, node_command

EXAMPLE = ROOT / "config" / "example1_rov.yaml"

pytestmark = pytest.mark.slow


def start(*extra):
    return child_process(node_command(EXAMPLE, *extra, parameters=["wrench_timeout:=0.0"],
                                      node="allocator_lifecycle_node"))


class Manager:
    """A lifecycle manager and a listener of the node's commands, in this process."""

    def __init__(self, context, namespace):
        import rclpy
        from lifecycle_msgs.srv import ChangeState, GetState
        from rcl_interfaces.srv import SetParameters
        from rclpy.executors import SingleThreadedExecutor

        from allocator_msgs.msg import ThrusterCommands
        from allocator_msgs.srv import SetActuatorFault
        from allocator_pkg.ros.node_client import Controller
        self.node = rclpy.create_node("manager", context=context)
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)
        target = f"{namespace}/thrust_allocator"
        self.change = self.node.create_client(ChangeState, f"{target}/change_state")
        self.get = self.node.create_client(GetState, f"{target}/get_state")
        self.fault = self.node.create_client(SetActuatorFault, f"{target}/set_actuator_fault")
        self.parameters = self.node.create_client(SetParameters, f"{target}/set_parameters")
        self.controller = Controller(self.node, namespace=namespace)
        self.commands = []
        self.node.create_subscription(ThrusterCommands, f"{namespace}/thruster_commands", self.commands.append, 100)

    def spin_until(self, predicate, timeout=20.0):
        deadline = time.monotonic() + timeout
        while not predicate():
            assert time.monotonic() < deadline, "timed out"
            self.executor.spin_once(timeout_sec=0.05)

    def spin_for(self, seconds):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.05)

    def call(self, client, request):
        self.spin_until(client.service_is_ready)
        future = client.call_async(request)
        self.spin_until(future.done)
        return future.result()

    def transition(self, transition_id):
        from lifecycle_msgs.msg import Transition
        from lifecycle_msgs.srv import ChangeState
        return self.call(self.change, ChangeState.Request(transition=Transition(id=transition_id))).success

    def state(self):
        """The node's state. A query may be asked again: right after the node starts, the
        service can be visible before the way back to us is matched, and its first reply can
        be lost (seen once in `make test`; the test then waited 20 s for it)."""
        from lifecycle_msgs.srv import GetState
        self.spin_until(self.get.service_is_ready)
        for _ in range(4):
            future = self.get.call_async(GetState.Request())
            deadline = time.monotonic() + 5.0
            while not future.done() and time.monotonic() < deadline:
                self.executor.spin_once(timeout_sec=0.05)
            if future.done():
                return future.result().current_state.label
            self.get.remove_pending_request(future)
        raise AssertionError("get_state never answered")


def test_configure_activate_deactivate_cleanup_and_shutdown_when_active(ros_context, namespace):
    from lifecycle_msgs.msg import Transition
    from rcl_interfaces.srv import SetParameters
    from rclpy.parameter import Parameter

    from allocator_msgs.msg import ActuatorFault
    from allocator_msgs.srv import SetActuatorFault
    from allocator_pkg.ros.conversions import array_to_wrench
    with start(*namespace_arguments(f"{namespace}/managed")) as process:
        manager = Manager(ros_context, f"{namespace}/managed")
        assert manager.state() == "unconfigured"
        refused = manager.call(manager.fault, SetActuatorFault.Request(fault=ActuatorFault(actuator="main_port",
                                                                                            mode=2)))
        assert not refused.success and "not configured" in refused.message
        assert manager.transition(Transition.TRANSITION_CONFIGURE) and manager.state() == "inactive"
        manager.spin_for(0.5)
        assert manager.commands == []                                  # configured, not commanding
        assert manager.transition(Transition.TRANSITION_ACTIVATE) and manager.state() == "active"
        wrench = array_to_wrench([120.0, 0.0, 0.0, 0.0, 0.0, 0.0])

        def driven():
            manager.controller.wrench.publish(wrench)
            return manager.commands and manager.commands[-1].thrust[2] > 10.0

        manager.spin_until(driven)
        assert manager.transition(Transition.TRANSITION_DEACTIVATE) and manager.state() == "inactive"
        manager.spin_for(0.3)
        count = len(manager.commands)
        assert all(t == 0.0 for t in manager.commands[-1].thrust)     # zero thrust, then nothing
        manager.controller.wrench.publish(wrench)
        manager.spin_for(0.5)
        assert len(manager.commands) == count
        assert manager.transition(Transition.TRANSITION_CLEANUP) and manager.state() == "unconfigured"
        # unconfigured: a change is taken as it is, and checked by the next configure
        bad = SetParameters.Request(parameters=[Parameter("method", value="magic")
                                                .to_parameter_msg()])
        assert manager.call(manager.parameters, bad).results[0].successful
        assert not manager.transition(Transition.TRANSITION_CONFIGURE) and manager.state() == "unconfigured"
        good = SetParameters.Request(parameters=[Parameter("method", value="pseudoinverse")
                                                 .to_parameter_msg()])
        assert manager.call(manager.parameters, good).results[0].successful
        assert manager.transition(Transition.TRANSITION_CONFIGURE)
        assert manager.transition(Transition.TRANSITION_ACTIVATE)
        manager.spin_until(driven)
        count = len(manager.commands)
        assert manager.transition(Transition.TRANSITION_ACTIVE_SHUTDOWN)
        manager.spin_until(lambda: len(manager.commands) > count and all(t == 0.0 for t in manager.commands[-1].thrust))
        assert process.wait(timeout=10) == 0
    output = process.output()
    assert f"{namespace}/managed/thrust_allocator: invalid configuration:\n  method: 'magic' is not one of" in output
    assert "Traceback" not in output


@pytest.mark.parametrize("transitions", [[], ["configure"]], ids=["unconfigured", "inactive"])
def test_shutdown_from_any_state_ends_the_process(ros_context, namespace, transitions):
    from lifecycle_msgs.msg import Transition
    with start(*namespace_arguments(f"{namespace}/ending")) as process:
        manager = Manager(ros_context, f"{namespace}/ending")
        for _ in transitions:
            assert manager.transition(Transition.TRANSITION_CONFIGURE)
        assert manager.transition(Transition.TRANSITION_INACTIVE_SHUTDOWN if transitions
                                  else Transition.TRANSITION_UNCONFIGURED_SHUTDOWN)
        assert process.wait(timeout=10) == 0
    assert "Traceback" not in process.output() and manager.commands == []


def test_sigint_while_active_commands_zero_thrust(ros_context, namespace):
    from lifecycle_msgs.msg import Transition
    with start(*namespace_arguments(f"{namespace}/signalled")) as process:
        manager = Manager(ros_context, f"{namespace}/signalled")
        assert manager.transition(Transition.TRANSITION_CONFIGURE)
        assert manager.transition(Transition.TRANSITION_ACTIVATE)
        manager.spin_until(lambda: len(manager.commands) > 3)
        count = len(manager.commands)
        process.send_signal(signal.SIGINT)
        manager.spin_until(lambda: process.poll() is not None and len(manager.commands) > count)
        assert process.wait(timeout=10) == 0
        assert all(t == 0.0 for t in manager.commands[-1].thrust)
    assert "stopped: published zero thrust" in process.output()
