"""Bad input everywhere: each gets a clear error and leaves the running state untouched."""

import math
import threading
import time

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg import FaultMode, vehicle_from_parameters

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


def parameter(name, value):
    from rclpy.parameter import Parameter
    return Parameter(name, value=value)


BAD_PARAMETERS = [
    ("rate_hz", "fast", "rate_hz: expected a number"),
    ("rate_hz", -5.0, "Parameter rate_hz out of range"),
    ("rate_hz", math.nan, "Parameter rate_hz out of range"),
    ("method", "magic", "method: 'magic' is not one of"),
    ("dofs", ["surge", "surge"], "dofs: lists a DOF twice"),
    ("weights.slack", [1.0], "weights.slack: needs one weight per controlled DOF"),
    ("actuators.main_port.direction", [0.0, 0.0, 0.0], "actuators.main_port.direction: must not be the zero vector"),
    ("actuators.main_port.thrust_min", 10.0, "Parameter actuators.main_port.thrust_min out of range"),
    ("actuators.main_port.thrust_max", math.inf, "Parameter actuators.main_port.thrust_max out of range"),
    ("actuators.main_port.thrust_max", 0.0, "actuators.main_port.thrust_max: must be > 0"),
    ("actuators.main_port.command_min", 100.0, "actuators.main_port.command_min"),
    ("actuators.azimuth_fwd.azimuth_min", 2.0, "azimuth_initial: 0 rad is outside the feasible sector [2, 3.14159]"),
    ("actuators.azimuth_fwd.azimuth_min", 4.0, "actuators.azimuth_fwd.azimuth_min: must be below azimuth_max"),
    ("actuators.azimuth_fwd.forbidden_sectors", [1.0], "actuators.azimuth_fwd.forbidden_sectors: needs [start, end]"),
    ("actuators.azimuth_fwd.forbidden_sectors", [-0.5, 0.5], "azimuth_initial: 0 rad is inside a forbidden sector"),
    ("solver.max_iter", 0, "Parameter solver.max_iter out of range"),
    ("per_actuator_topics", "yes", "per_actuator_topics: expected true or false"),
    ("priorities", [0, 1], "priorities: needs one level per controlled DOF in `dofs` order (3: surge, sway, yaw)"),
    ("priorities", [0, 1, -2], "priorities: must be >= 0, got -2"),
    ("actuators.main_port.table_voltage", [12.0, 16.0], "actuators.main_port.table_voltage: only used with"),
    ("actuators.main_port.command_deadband", -1.0, "Parameter actuators.main_port.command_deadband out of range"),
    ("nominal_voltage", -3.0, "Parameter nominal_voltage out of range"),
]


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
@pytest.mark.parametrize(("name", "value", "reason"), BAD_PARAMETERS)
def test_bad_runtime_parameter_alone_and_mixed_with_good_ones(harness, name, value, reason):
    node = harness.node
    before = node.allocator.vehicle
    setups = node.allocator.stats.solver_setups
    result = node.set_parameters([parameter(name, value)])[0]
    assert not result.successful and reason in result.reason
    mixed = node.set_parameters_atomically([parameter("weights.minimax", 3.0), parameter(name, value)])
    assert not mixed.successful and reason in mixed.reason
    assert node.get_parameter("weights.minimax").value == 0.0
    assert node.allocator.vehicle == before
    assert node.allocator.stats.solver_setups == setups
    harness.send_wrench([50.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(2)
    assert harness.status[-1].solver_status == "solved"


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_read_only_and_undeclared_parameters(harness):
    node = harness.node
    for name, value in (("actuators.names", ["x"]), ("actuators.main_port.type", "azimuth")):
        result = node.set_parameters([parameter(name, value)])[0]
        assert not result.successful and "read-only" in result.reason
    from rclpy.exceptions import ParameterNotDeclaredException
    with pytest.raises(ParameterNotDeclaredException):
        node.set_parameters([parameter("actuators.main_port.thrust_maximum", 1.0)])


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_huge_wrench_saturates_within_limits(harness):
    harness.send_wrench([1e30, -1e30, 0.0, 0.0, 0.0, 1e30])
    harness.tick(3)
    commands, status = harness.commands[-1], harness.status[-1]
    assert status.saturated
    assert all(math.isfinite(t) for t in commands.thrust)
    assert max(commands.thrust[2:]) <= 300.0 and min(commands.thrust[2:]) >= -200.0
    assert all(0.0 <= t <= 150.0 for t in commands.thrust[:2])


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0, **{"actuators.azimuth_fwd.azimuth_min": -1.0,
                                                    "actuators.azimuth_fwd.azimuth_max": 1.0})
def test_stuck_angle_outside_the_feasible_sector_is_refused(harness):
    from allocator_msgs.msg import ActuatorFault
    from allocator_msgs.srv import SetActuatorFault
    request = SetActuatorFault.Request(fault=ActuatorFault(actuator="azimuth_fwd", mode=FaultMode.STUCK, azimuth=2.0))
    response = harness.call(harness.fault_client, request)
    assert not response.success and "outside the feasible sector [-1, 1]" in response.message
    assert harness.node.allocator.faults == {}


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
@pytest.mark.parametrize(("name", "value"), [("solver.max_iter", 1), ("solver.time_limit", 1e-9)])
def test_solver_trouble_publishes_the_fallback_and_recovers(harness, name, value):
    harness.send_wrench([250.0, 60.0, 0.0, 0.0, 0.0, 40.0])
    harness.tick(5)
    assert harness.node.set_parameters([parameter(name, value)])[0].successful
    harness.send_wrench([260.0, 80.0, 0.0, 0.0, 0.0, -40.0])
    harness.tick(2)
    status, commands = harness.status[-1], harness.commands[-1]
    assert status.solver_status.startswith("fallback: pseudoinverse")
    assert all(math.isfinite(t) for t in commands.thrust)
    assert max(commands.thrust[2:]) <= 300.0
    assert harness.node.set_parameters([parameter(name, 4000 if name == "solver.max_iter" else 0.0)])[0].successful
    harness.tick(2)
    assert harness.status[-1].solver_status == "solved"


@pytest.mark.parametrize("executor_type", ["SingleThreadedExecutor", "MultiThreadedExecutor"])
def test_parameter_changes_from_other_threads_race_the_timer_and_the_services(ros_context, executor_type):
    """Two threads change parameters (each change valid only as a whole) while the executor
    runs the timer and a third thread sets and clears faults through the services: every
    published sample belongs to one whole configuration, and the final configuration is the
    one the parameters describe. On a MultiThreadedExecutor the callbacks also run on
    threads of its pool."""
    import rclpy
    from rclpy import executors
    from std_srvs.srv import Trigger

    from allocator_msgs.msg import ActuatorFault, AllocationStatus, ThrusterCommands
    from allocator_msgs.srv import SetActuatorFault
    from allocator_pkg.ros.conversions import array_to_wrench
    from allocator_pkg.ros.node import AllocatorNode
    from allocator_pkg.ros.ros_parameters import allocator_parameters

    node = AllocatorNode(context=ros_context, cli_args=["--ros-args", "--params-file", str(EXAMPLE)],
                         parameter_overrides=[parameter("rate_hz", 200.0), parameter("wrench_timeout", 0.0)])
    client = rclpy.create_node("racer", context=ros_context)
    samples = []
    client.create_subscription(ThrusterCommands, "thruster_commands", samples.append, 100)
    client.create_subscription(AllocationStatus, "allocation_status", samples.append, 100)
    wrench = client.create_publisher(type(array_to_wrench(np.zeros(6))), "wrench_command", 10)
    step = iter(range(10**9))
    # rclpy 7.1.6's MultiThreadedExecutor stalls for seconds under steady subscription traffic
    # (README, "Threads"); there the wrench comes once a second so that the race gets run.
    wrench_period = 0.01 if executor_type == "SingleThreadedExecutor" else 1.0
    client.create_timer(wrench_period, lambda: wrench.publish(array_to_wrench(
        [200.0 * math.sin(next(step) / 10), 50.0, 0.0, 0.0, 0.0, 30.0])))
    set_fault = client.create_client(SetActuatorFault, "thrust_allocator/set_actuator_fault")
    clear = client.create_client(Trigger, "thrust_allocator/clear_faults")
    executor = getattr(executors, executor_type)(context=ros_context)
    executor.add_node(node)
    probe = executors.SingleThreadedExecutor(context=ros_context)
    probe.add_node(client)
    spinners = [threading.Thread(target=e.spin, daemon=True) for e in (executor, probe)]
    for spinner in spinners:
        spinner.start()
    assert set_fault.wait_for_service(timeout_sec=10.0) and clear.wait_for_service(timeout_sec=10.0)

    three = [parameter("dofs", ["surge", "sway", "yaw"]), parameter("weights.slack", [1e6, 2e6, 3e6]),
             parameter("actuators.main_port.thrust_max", 300.0)]
    two = [parameter("dofs", ["surge", "yaw"]), parameter("weights.slack", [1e6, 3e6]),
           parameter("actuators.main_port.thrust_max", 150.0)]
    stop = time.monotonic() + 3.0
    outcomes: dict[str, list] = {"three": [], "two": [], "fault": []}

    def change(name, parameters):
        while time.monotonic() < stop:
            outcomes[name].append(node.set_parameters_atomically(parameters).successful)

    def faults():
        k = 0
        while time.monotonic() < stop:
            fault = ActuatorFault(actuator="main_stbd", mode=FaultMode.DEGRADED, efficiency=0.25 + 0.25 * (k % 3))
            outcomes["fault"].append(set_fault.call(SetActuatorFault.Request(fault=fault), timeout_sec=5.0).success)
            outcomes["fault"].append(clear.call(Trigger.Request(), timeout_sec=5.0).success)
            k += 1

    racers = [threading.Thread(target=change, args=("three", three)),
              threading.Thread(target=change, args=("two", two)), threading.Thread(target=faults)]
    for racer in racers:
        racer.start()
    for racer in racers:
        racer.join(timeout=20.0)
    executor.shutdown()
    probe.shutdown()
    for spinner in spinners:
        spinner.join(timeout=5.0)

    assert all(len(v) > 10 and all(v) for v in outcomes.values()), {k: len(v) for k, v in outcomes.items()}
    commands = [m for m in samples if isinstance(m, ThrusterCommands)]
    statuses = [m for m in samples if isinstance(m, AllocationStatus)]
    assert len(commands) > 100 and len(statuses) > 100
    for message in commands:
        assert list(message.name) == ["azimuth_fwd", "azimuth_aft", "main_port", "main_stbd"]
        assert all(math.isfinite(t) for t in message.thrust)
        assert -200.0 <= message.thrust[2] <= 300.0
        assert len(message.thrust) == len(message.azimuth) == len(message.command) == len(message.mode) == 4
    for message in statuses:
        status = message.solver_status
        assert status in ("solved", "solved inaccurate") or status.startswith("fallback") or "iterate used (" in status
    assert node.allocator.vehicle == vehicle_from_parameters(allocator_parameters(node))
    assert node.allocator.vehicle.dofs in (("surge", "sway", "yaw"), ("surge", "yaw"))
    client.destroy_node()
    node.destroy_node()
