"""The node in one SingleThreadedExecutor with a probe node, on simulated time."""

import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from diagnostic_msgs.msg import DiagnosticStatus

from allocator_pkg import Allocator, FaultMode

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_wrench_in_commands_out_equal_the_core_answer(harness):
    core = Allocator(vehicle_from(EXAMPLE))
    for _ in range(harness.node.samples):                     # before the wrench: allocating zero
        core.allocate(np.zeros(6))
    harness.send_wrench([100.0, 20.0, 0.0, 0.0, 0.0, 10.0])
    harness.tick(5)
    last = harness.commands[-1]
    for _ in range(5):
        expected = core.allocate([100.0, 20.0, 0.0, 0.0, 0.0, 10.0])
    assert list(last.name) == ["azimuth_fwd", "azimuth_aft", "main_port", "main_stbd"]
    assert np.array(last.thrust) == pytest.approx(expected.thrust)
    assert np.array(last.azimuth) == pytest.approx(expected.azimuth)
    assert np.array(last.command) == pytest.approx(expected.command)
    assert list(last.mode) == [0, 0, 0, 0]
    status = harness.status[-1]
    assert status.requested.force.x == 100.0
    assert status.achieved.force.x == pytest.approx(expected.achieved[0])
    assert status.method == "qp" and status.solver_status == "solved"
    assert last.header.stamp.sec * 10**9 + last.header.stamp.nanosec == harness.time_ns


def test_each_sample_publishes_one_message_of_each_kind(harness):
    before = harness.node.samples
    harness.tick(7)
    harness.spin_for(0.2)
    assert harness.node.samples - before == 7
    assert len(harness.commands) == len(harness.status) == harness.node.samples


def test_timer_period_follows_rate_hz(harness):
    from rclpy.parameter import Parameter
    assert harness.node.period == pytest.approx(1 / 50)
    result = harness.node.set_parameters([Parameter("rate_hz", value=20.0)])[0]
    assert result.successful
    assert harness.node.period == pytest.approx(1 / 20)
    assert harness.node.allocator.dt == pytest.approx(1 / 20)
    before = harness.node.samples
    harness.tick(3, period=0.05)
    assert harness.node.samples - before == 3


def fault_request(actuator, mode, efficiency=0.0, azimuth=0.0):
    from allocator_msgs.msg import ActuatorFault
    from allocator_msgs.srv import SetActuatorFault
    return SetActuatorFault.Request(fault=ActuatorFault(actuator=actuator, mode=mode, efficiency=efficiency,
                                                        azimuth=azimuth))


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_fault_service_modes(harness):
    harness.send_wrench([150.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    response = harness.call(harness.fault_client, fault_request("main_port", FaultMode.FAILED))
    assert response.success, response.message
    harness.tick(40)
    commands = harness.commands[-1]
    assert commands.thrust[2] == 0.0 and commands.mode[2] == FaultMode.FAILED
    assert harness.status[-1].achieved.force.x == pytest.approx(150.0, rel=1e-3)   # the others compensate
    assert harness.call(harness.fault_client, fault_request("main_stbd", FaultMode.DEGRADED, efficiency=0.5)).success
    assert harness.call(harness.fault_client, fault_request("azimuth_fwd", FaultMode.STUCK, azimuth=0.4)).success
    harness.tick(2)
    assert list(harness.commands[-1].mode) == [FaultMode.STUCK, 0, FaultMode.FAILED, FaultMode.DEGRADED]
    assert harness.commands[-1].azimuth[0] == pytest.approx(0.4)
    assert harness.call(harness.fault_client, fault_request("main_port", FaultMode.NOMINAL)).success
    from std_srvs.srv import Trigger
    cleared = harness.call(harness.clear_client, Trigger.Request())
    assert cleared.success and "azimuth_fwd" in cleared.message
    assert harness.call(harness.clear_client, Trigger.Request()).message == "no faults were set"
    harness.tick(1)
    assert list(harness.commands[-1].mode) == [0, 0, 0, 0]


@pytest.mark.parametrize(("request_args", "expected"), [
    (("ghost", FaultMode.FAILED), "unknown actuator 'ghost'; actuators: azimuth_fwd, azimuth_aft, main_port"),
    (("main_port", FaultMode.DEGRADED, 0.0), "efficiency in (0, 1]"),
    (("main_port", FaultMode.DEGRADED, -1.0), "efficiency in (0, 1]"),
    (("main_port", FaultMode.DEGRADED, 2.0), "efficiency in (0, 1]"),
    (("main_port", FaultMode.DEGRADED, math.nan), "efficiency in (0, 1]"),
    (("main_port", FaultMode.STUCK, 0.0, 0.3), "these can be stuck: azimuth_fwd, azimuth_aft"),
    (("main_port", 9), "unknown mode 9; modes: NOMINAL=0, DEGRADED=1, FAILED=2, STUCK=3"),
])
def test_fault_service_errors_change_nothing(harness, request_args, expected):
    response = harness.call(harness.fault_client, fault_request(*request_args))
    assert not response.success
    assert expected in response.message
    assert harness.node.allocator.faults == {}


def test_parameter_changes_are_checked_as_a_whole(harness):
    from rcl_interfaces.srv import SetParameters, SetParametersAtomically
    from rclpy.parameter import Parameter

    def request(kind, **values):
        return kind.Request(parameters=[Parameter(name.replace("__", "."), value=value).to_parameter_msg()
                                        for name, value in values.items()])

    ok = harness.call(harness.parameters_client, request(SetParameters, actuators__main_port__thrust_max=250.0))
    assert ok.results[0].successful
    assert harness.node.allocator.vehicle.actuator("main_port").thrust_max == 250.0
    bad = harness.call(harness.parameters_client, request(SetParameters, actuators__main_port__thrust_min=10.0))
    assert not bad.results[0].successful
    assert "actuators.main_port.thrust_min" in bad.results[0].reason
    assert harness.node.get_parameter("actuators.main_port.thrust_min").value == -200.0
    # Valid only together: one set_parameters request takes them as a whole (rclpy alone would
    # apply them one by one and refuse the first); a bad value in it refuses all of them.
    alone = harness.call(harness.parameters_client, request(SetParameters, dofs=["surge", "yaw"]))
    assert not alone.results[0].successful and "weights.slack" in alone.results[0].reason
    spoilt = harness.call(harness.parameters_client, request(SetParameters, weights__minimax=2.0, method="magic"))
    assert [r.successful for r in spoilt.results] == [False, False] and "method" in spoilt.results[0].reason
    assert harness.node.get_parameter("weights.minimax").value == 0.0
    together = harness.call(harness.parameters_client,
                            request(SetParameters, dofs=["surge", "yaw"], weights__slack=[1e6, 2e6]))
    assert [r.successful for r in together.results] == [True, True]
    assert harness.node.allocator.dofs == ("surge", "yaw")
    mixed = request(SetParametersAtomically, rate_hz=10.0, method="magic")
    result = harness.call(harness.atomic_parameters_client, mixed).result
    assert not result.successful and "method" in result.reason
    assert harness.node.get_parameter("rate_hz").value == 50.0
    assert harness.node.period == pytest.approx(1 / 50)
    read_only = harness.call(harness.parameters_client, request(SetParameters, actuators__names=["a"]))
    assert not read_only.results[0].successful
    assert "read-only" in read_only.results[0].reason
    setups = harness.node.allocator.stats.solver_setups
    harness.call(harness.parameters_client, request(SetParameters, weights__minimax=5.0))
    assert harness.node.allocator.stats.solver_setups == setups      # values only


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_a_change_to_a_method_that_cannot_serve_the_vehicle_is_refused_whole(harness):
    """explicit needs actuators of fixed direction; example1_rov has azimuths. The change is
    refused with the other values in it, and the running configuration keeps allocating."""
    from rclpy.parameter import Parameter
    before = harness.node.allocator.vehicle
    result = harness.node.set_parameters_atomically([Parameter("weights.minimax", value=3.0),
                                                     Parameter("method", value="explicit")])
    assert not result.successful
    assert "method" in result.reason and "'explicit' cannot serve this vehicle" in result.reason
    assert harness.node.get_parameter("method").value == "qp"
    assert harness.node.get_parameter("weights.minimax").value == 0.0
    assert harness.node.allocator.vehicle == before and harness.node.allocator.method == "qp"
    harness.send_wrench([50.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(2)
    assert harness.status[-1].method == "qp" and harness.status[-1].solver_status == "solved"


def test_a_params_file_whose_method_cannot_serve_the_vehicle_is_refused_naming_method(ros_context):
    from rclpy.parameter import Parameter

    from allocator_pkg.ros.node import AllocatorNode
    from allocator_pkg.ros.node_base import NodeConfigError
    with pytest.raises(NodeConfigError) as error:
        AllocatorNode(context=ros_context, cli_args=["--ros-args", "--params-file", str(EXAMPLE)],
                      parameter_overrides=[Parameter("method", value="explicit")])
    assert [name for name, _ in error.value.problems] == ["method"]
    assert "'explicit' cannot serve this vehicle" in error.value.report()


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_faults_survive_reconfiguration(harness):
    from rclpy.parameter import Parameter
    assert harness.call(harness.fault_client, fault_request("main_port", FaultMode.FAILED)).success
    assert harness.node.set_parameters([Parameter("method", value="pseudoinverse")])[0].successful
    harness.tick(1)
    assert harness.commands[-1].mode[2] == FaultMode.FAILED
    assert harness.status[-1].method == "pseudoinverse"


@pytest.mark.params(EXAMPLE, wrench_timeout=0.1)
def test_watchdog_commands_zero_thrust_on_stale_input(harness):
    harness.send_wrench([100.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(3)
    assert harness.commands[-1].thrust[2] > 0.0
    assert harness.status[-1].solver_status == "solved"
    harness.tick(6)                                   # 0.12 s without a new wrench
    assert all(t == 0.0 for t in harness.commands[-1].thrust)
    assert harness.status[-1].solver_status.startswith("stale")
    harness.send_wrench([100.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(1)
    assert harness.status[-1].solver_status == "solved"


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_non_finite_wrench_is_rejected_and_the_last_valid_one_kept(harness):
    harness.send_wrench([80.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.send_wrench([math.nan, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.send_wrench([0.0, math.inf, 0.0, 0.0, 0.0, 0.0])
    harness.tick(2)
    assert harness.status[-1].requested.force.x == 80.0
    assert harness.diagnostics_after_a_second()["rejected wrenches"] == "2"


def test_diagnostics_levels(harness):
    from diagnostic_msgs.msg import DiagnosticStatus
    one_second = round(1.0 / harness.node.period)

    def latest_level():
        count = len(harness.diagnostics)
        harness.tick(one_second)
        harness.spin_until(lambda: len(harness.diagnostics) > count)
        return harness.diagnostics[-1].status[0]

    assert latest_level().level == DiagnosticStatus.ERROR        # no wrench yet: stale
    harness.send_wrench([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    for _ in range(one_second):
        harness.send_wrench([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
        harness.tick(1)
    status = latest_level()
    harness.send_wrench([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    status = latest_level() if status.level != DiagnosticStatus.OK else status
    assert status.level == DiagnosticStatus.OK and status.message == "allocating"
    assert harness.call(harness.fault_client, fault_request("main_port", FaultMode.DEGRADED, efficiency=0.5)).success
    for _ in range(one_second):
        harness.send_wrench([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
        harness.tick(1)
    harness.spin_until(lambda: harness.diagnostics[-1].status[0].level == DiagnosticStatus.WARN, timeout=3.0)
    values = {kv.key: kv.value for kv in harness.diagnostics[-1].status[0].values}
    assert values["mode main_port"] == "DEGRADED"
    assert "main_port DEGRADED" in harness.diagnostics[-1].status[0].message


@pytest.mark.params(ROOT / "config" / "infante_auv.yaml")
def test_odometry_sets_the_speed_of_control_surfaces(harness):
    from nav_msgs.msg import Odometry
    odometry = harness.probe.create_publisher(Odometry, "odometry", 10)
    harness.spin_until(lambda: odometry.get_subscription_count() > 0)
    message = Odometry()
    message.twist.twist.linear.x = 2.0
    odometry.publish(message)
    harness.spin_until(lambda: harness.node.allocator.speed == 2.0)
    message.twist.twist.linear.x = math.nan
    odometry.publish(message)
    harness.spin_for(0.2)
    assert harness.node.allocator.speed == 2.0


@pytest.mark.params(EXAMPLE, wrench_timeout=0.1)
def test_watchdog_logs_once_per_transition(harness):
    from rcl_interfaces.msg import Log
    logs = []
    harness.probe.create_subscription(Log, "/rosout", logs.append, 100)
    harness.spin_until(lambda: harness.node.count_subscribers("/rosout") > 0 or True)
    harness.send_wrench([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(2)
    harness.tick(20)                                     # stale for 18 samples
    harness.send_wrench([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(2)
    harness.spin_for(0.3)
    texts = [log.msg for log in logs if log.name == harness.node.get_logger().name]      # this run's node
    assert sum("no valid wrench" in text for text in texts) == 1
    assert sum("wrench input resumed" in text for text in texts) >= 1


@pytest.mark.params(ROOT / "config" / "infante_auv.yaml")
def test_diagnostics_name_unavailable_control_surfaces(harness):
    assert harness.diagnostics_after_a_second()["unavailable"].startswith("fin_bow_port")


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_a_best_effort_controller_connects_by_default(harness):
    """wrench_command is a best-effort subscription: a sensor-data (best-effort) publisher feeds it
    as well as the probe's reliable one does."""
    from geometry_msgs.msg import Wrench
    from rclpy.qos import QoSProfile, ReliabilityPolicy
    publisher = harness.probe.create_publisher(Wrench, "wrench_command",
                                               QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT))
    message = Wrench()
    message.force.x = 42.0
    received = harness.node.wrenches_received

    def delivered():
        publisher.publish(message)
        return harness.node.wrenches_received > received

    harness.spin_until(delivered)
    harness.tick(1)
    assert harness.status[-1].requested.force.x == 42.0


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_the_shutdown_command_is_zero_thrust_and_acknowledged(harness):
    harness.send_wrench([150.0, 20.0, 0.0, 0.0, 0.0, 10.0])
    harness.tick(3)
    angles = list(harness.commands[-1].azimuth)
    count = len(harness.commands)
    assert harness.node.publish_stop(timeout=5.0)
    harness.spin_until(lambda: len(harness.commands) > count)
    assert list(harness.commands[-1].thrust) == [0.0] * 4 and list(harness.commands[-1].azimuth) == angles


@pytest.mark.params(ROOT / "config" / "otter_usv.yaml")
def test_an_under_actuated_vehicle_says_so_in_diagnostics(harness):
    values = harness.diagnostics_after_a_second()
    assert values["actuation"].startswith("under-actuated: the actuators give 2 independent directions")
    assert "sway is left to the vehicle's dynamics" in values["actuation"]


@pytest.mark.params(ROOT / "config" / "dp_vessel.yaml", wrench_timeout=0.0)
def test_after_faults_the_status_and_diagnostics_name_the_reach_lost(harness):
    """dp_vessel: a force (fx, fy) at (x, y) gives yaw x fy - y fx; azimuth_stbd at (-41.5, 7) m
    alone gives (1, 0, -7) and (0, 1, -41.5), which hold no unit wrench."""
    harness.tick(1)
    assert list(harness.status[-1].lost_reach) == []
    assert harness.diagnostics_after_a_second()["lost to faults"] == "none"
    assert harness.set_group_fault("switchboard_b")[0]                 # azimuth_port, tunnel_aft
    assert harness.set_fault("tunnel_fwd", "failed")[0]
    harness.tick(1)
    lost = ("after the faults the working actuators reach 2 independent directions of the 3 controlled DOFs "
            "(surge, sway, yaw), 3 with every actuator; surge, sway, yaw only together with other DOFs; some "
            "combinations will be saturated")
    assert list(harness.status[-1].lost_reach) == [lost]
    values = harness.diagnostics_after_a_second()
    assert values["lost to faults"] == lost
    status = harness.diagnostics[-1].status[0]
    assert lost in status.message and status.level != DiagnosticStatus.OK
    assert harness.set_fault("azimuth_stbd", "stuck", angle=0.0)[0]
    harness.tick(1)
    assert harness.status[-1].lost_reach[0] == ("after the faults no working actuator produces sway; "
                                                "requests in it will always be saturated")
    harness.clear_faults()
    harness.tick(1)
    assert list(harness.status[-1].lost_reach) == []
    assert harness.diagnostics_after_a_second()["lost to faults"] == "none"


BLUEROV = ROOT / "config" / "bluerov2_heavy.yaml"


@pytest.mark.params(BLUEROV, wrench_timeout=0.0, frame="flu")
def test_get_capability_answers_along_a_direction_in_the_nodes_frame(harness):
    from allocator_msgs.srv import GetCapability
    from allocator_pkg.ros.conversions import array_to_wrench, wrench_to_array
    client = harness.probe.create_client(GetCapability, "thrust_allocator/get_capability")
    up = harness.call(client, GetCapability.Request(direction=array_to_wrench([0.0, 0.0, 1.0, 0.0, 0.0, 0.0])))
    assert up.success and up.scale == pytest.approx(4 * 39.9, rel=1e-6)          # FLU up: the verticals reversed
    assert wrench_to_array(up.achieved) == pytest.approx([0.0, 0.0, 4 * 39.9, 0.0, 0.0, 0.0], abs=1e-6)
    harness.call(harness.fault_client, _fault_request("thruster_5", 2))
    down = harness.call(client, GetCapability.Request(direction=array_to_wrench([0.0, 0.0, -1.0, 0.0, 0.0, 0.0])))
    assert down.scale == pytest.approx(2 * 51.5, rel=1e-6)                       # a diagonal pair left
    zero = harness.call(client, GetCapability.Request(direction=array_to_wrench([0.0] * 6)))
    assert not zero.success and "no component in the controlled DOFs" in zero.message
    bad = harness.call(client, GetCapability.Request(direction=array_to_wrench([math.nan, 0, 0, 0, 0, 0])))
    assert not bad.success and "finite" in bad.message


@pytest.mark.params(ROOT / "config" / "dp_vessel.yaml", wrench_timeout=0.0)
def test_get_capability_after_a_group_fault_lifts_the_sector_that_protected_the_lost_azimuth(harness):
    """dp_vessel, switchboard B lost (azimuth_port, tunnel_aft): azimuth_stbd's sector about 90 deg
    kept its race off azimuth_port and lifts, so pure sway to starboard is azimuth_stbd abeam with
    tunnel_fwd balancing its yaw moment (41.5 F_a = 37 F_fwd, F_fwd at 300 kN): 567.5 kN."""
    assert harness.set_group_fault("switchboard_b")[0]
    scale, achieved = harness.capability([0.0, 1.0, 0.0, 0.0, 0.0, 0.0])
    assert scale == pytest.approx(300e3 * (1.0 + 37.0 / 41.5), rel=1e-3)
    assert achieved[[0, 1, 5]] == pytest.approx([0.0, scale, 0.0], abs=1.0)


def _fault_request(actuator, mode):
    from allocator_msgs.msg import ActuatorFault
    from allocator_msgs.srv import SetActuatorFault
    return SetActuatorFault.Request(fault=ActuatorFault(actuator=actuator, mode=mode))


def test_every_service_of_an_unconfigured_node_answers_not_configured(ros_context):
    from std_srvs.srv import Trigger

    from allocator_msgs.srv import GetCapability, HoldActuator, SetActuatorFault
    from allocator_pkg.ros.lifecycle_node import AllocatorLifecycleNode
    node = AllocatorLifecycleNode(context=ros_context, cli_args=["--ros-args", "--params-file", str(EXAMPLE)])
    try:
        for callback, kind in ((node._on_set_fault, SetActuatorFault), (node._on_clear_faults, Trigger),
                               (node._on_get_capability, GetCapability), (node._on_hold_actuator, HoldActuator)):
            response = callback(kind.Request(), kind.Response())
            assert (response.success, response.message) == \
                (False, "not configured: the allocator has no configuration yet"), kind
    finally:
        node.destroy_node()
