"""The ros2_control output: thrust and azimuth arrays in the controller's joint order, and the
configurations refused with the key named."""

import pytest
from conftest import DATA, ROOT, vehicle_from

from allocator_pkg import ConfigError, read_parameters
from allocator_pkg.configuration.parameters import parse_parameters

EXAMPLE = ROOT / "config" / "example1_rov.yaml"
JOINTS = ["main_stbd", "azimuth_aft", "main_port", "azimuth_fwd"]


def listen(harness, topic):
    """The Float64MultiArray messages the probe receives on ``topic``, once it is connected."""
    from std_msgs.msg import Float64MultiArray
    received = []
    subscription = harness.probe.create_subscription(Float64MultiArray, topic, received.append, 100)
    harness.spin_until(lambda: subscription.get_publisher_count() > 0)
    return received


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0, ros2_control__thrust_topic="/thruster_controller/commands",
                    ros2_control__angle_topic="/azimuth_controller/commands", ros2_control__actuators=JOINTS)
def test_every_sample_publishes_the_thrust_and_the_angles_in_the_joint_order(harness):
    thrust = listen(harness, "/thruster_controller/commands")
    angles = listen(harness, "/azimuth_controller/commands")
    harness.send_wrench([100.0, 20.0, 0.0, 0.0, 0.0, 10.0])
    harness.tick(5)
    harness.spin_until(lambda: len(thrust) >= 5 and len(angles) >= 5)
    last = harness.commands[-1]
    by_name = dict(zip(last.name, zip(last.thrust, last.azimuth)))
    assert list(thrust[-1].data) == [by_name[name][0] for name in JOINTS]
    assert list(angles[-1].data) == [by_name["azimuth_aft"][1], by_name["azimuth_fwd"][1]]
    assert any(value != 0.0 for value in thrust[-1].data) and any(value != 0.0 for value in angles[-1].data)


@pytest.mark.params(EXAMPLE, ros2_control__thrust_topic="thruster_controller/commands")
def test_without_a_list_the_thrust_is_in_the_configuration_order(harness):
    thrust = listen(harness, "thruster_controller/commands")
    harness.tick(2)
    harness.spin_until(lambda: len(thrust) >= 2)
    assert list(thrust[-1].data) == list(harness.commands[-1].thrust)
    assert harness.node.runtime.settings.ros2_control_actuators == ("azimuth_fwd", "azimuth_aft", "main_port",
                                                                    "main_stbd")


def problems(path, **overrides):
    with pytest.raises(ConfigError) as caught:
        vehicle_from(path, **overrides)
    return caught.value.problems


def test_an_unknown_or_twice_listed_actuator_is_refused_with_the_key_named():
    found = problems(EXAMPLE, ros2_control__actuators=["main_port", "main_stbd", "bow", "main_port"])
    assert ("ros2_control.actuators", "'bow' is not in actuators.names (azimuth_fwd, azimuth_aft, main_port, "
                                      "main_stbd)") in found
    assert ("ros2_control.actuators", "'main_port' is listed 2 times; each actuator at most once") in found


def test_an_angle_topic_without_a_rotatable_thruster_is_refused():
    found = problems(DATA / "eight_thrusters.yaml", ros2_control__angle_topic="/angles")
    assert [key for key, _ in found] == ["ros2_control.angle_topic"]
    assert "no azimuth angle to publish" in found[0][1]
    found = problems(EXAMPLE, ros2_control__angle_topic="/angles", ros2_control__actuators=["main_port"])
    assert [key for key, _ in found] == ["ros2_control.angle_topic"]


def test_a_subset_is_taken_in_its_order():
    parameters = read_parameters(EXAMPLE)
    parameters.update({"ros2_control.actuators": ["main_stbd", "main_port"], "ros2_control.thrust_topic": "/t"})
    _, settings = parse_parameters(parameters)
    assert settings.ros2_control_actuators == ("main_stbd", "main_port")
    assert settings.ros2_control_thrust_topic == "/t" and settings.ros2_control_angle_topic == ""


def test_the_topics_follow_a_parameter_change_and_a_refused_one_changes_nothing(harness):
    from rclpy.parameter import Parameter
    result = harness.node.set_parameters([Parameter("ros2_control.actuators", value=["main_port", "bow"])])[0]
    assert not result.successful and "ros2_control.actuators: 'bow' is not in actuators.names" in result.reason
    assert harness.node.runtime.settings.ros2_control_thrust_topic == ""
    result = harness.node.set_parameters([Parameter("ros2_control.thrust_topic", value="/thrust"),
                                          Parameter("ros2_control.actuators", value=["main_stbd"])])[0]
    assert result.successful
    thrust = listen(harness, "/thrust")
    harness.tick(2)
    harness.spin_until(lambda: len(thrust) >= 1)
    assert list(thrust[-1].data) == [harness.commands[-1].thrust[3]]
