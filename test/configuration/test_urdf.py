"""Geometry from a URDF: the BlueROV2 Heavy's URDF, built here from config/bluerov2_heavy.yaml
with scipy's rotations (not the parser's), gives the same configuration matrix as the params
file, in FLU (REP-103) and FRD; and every malformed description is named."""

import math

import numpy as np
import pytest
from conftest import ROOT
from scipy.spatial.transform import Rotation

from allocator_pkg import ConfigError, read_parameters, vehicle_from_parameters
from allocator_pkg.configuration.params_file import write_parameters
from allocator_pkg.configuration.urdf import geometry_parameters
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix

BLUEROV = ROOT / "config" / "bluerov2_heavy.yaml"
EXAMPLE = ROOT / "config" / "example1_rov.yaml"
FLU = np.array([1.0, -1.0, -1.0])
HULL = (np.array([0.02, -0.01, 0.05]), np.array([0.1, -0.2, 0.7]))      # a rotated mount between them


def matrix(xyz, rpy):
    result = np.eye(4)
    result[:3, :3] = Rotation.from_euler("xyz", rpy).as_matrix()         # URDF rpy: fixed axes x, y, z
    result[:3, 3] = xyz
    return result


def origin(transform):
    xyz = " ".join(f"{v:.15g}" for v in transform[:3, 3])
    rpy = " ".join(f"{v:.15g}" for v in Rotation.from_matrix(transform[:3, :3]).as_euler("xyz"))
    return f'<origin xyz="{xyz}" rpy="{rpy}"/>'


def joint(name, kind, parent, child, transform, axis="1 0 0"):
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'{origin(transform)}<axis xyz="{axis}"/></joint>')


def urdf_of(parameters, frame, kinds=None, axis_of=None):
    """base_footprint -> base_link -> hull (fixed, rotated) -> one link per actuator on a
    continuous joint (``kinds`` may change that) whose x axis is its thrust direction."""
    sign = FLU if frame == "flu" else np.ones(3)
    hull = matrix(*HULL)
    parts = ['<robot name="test">', '<link name="base_footprint"/>', '<link name="base_link"/>', '<link name="hull"/>',
             joint("footprint", "fixed", "base_footprint", "base_link", matrix([0, 0, 0.3], [0, 0, 0])),
             joint("hull_mount", "fixed", "base_link", "hull", hull)]
    for name in parameters["actuators.names"]:
        position = np.array(parameters[f"actuators.{name}.position"]) * sign
        direction = np.array(parameters.get(f"actuators.{name}.direction", [1.0, 0.0, 0.0])) * sign
        direction /= np.linalg.norm(direction)
        yaw, pitch = math.atan2(direction[1], direction[0]), math.asin(-direction[2])
        target = matrix(position, [0.0, pitch, yaw])                    # its x axis along the direction
        axis = (axis_of or {}).get(name, "1 0 0")
        parts += [f'<link name="{name}"/>',
                  joint(f"{name}_joint", (kinds or {}).get(name, "continuous"), "hull", name,
                        np.linalg.inv(hull) @ target, axis)]
    return "\n".join([*parts, "</robot>"])


def without_geometry(path, **extra):
    parameters = {name: value for name, value in read_parameters(path).items()
                  if not name.endswith((".position", ".direction"))}
    return {**parameters, "geometry_source": "robot_description", **extra}


@pytest.mark.parametrize("frame", ["flu", "frd"])
def test_the_bluerov2_urdf_gives_the_params_files_configuration_matrix(frame):
    full = read_parameters(BLUEROV)
    parameters = without_geometry(BLUEROV, frame=frame)
    geometry = geometry_parameters(urdf_of(full, frame), parameters)
    from_urdf = vehicle_from_parameters({**parameters, **geometry})
    from_file = vehicle_from_parameters(full)
    zeros = np.zeros(len(from_file.actuators))
    assert configuration_matrix(from_urdf.actuators, zeros) == pytest.approx(
        configuration_matrix(from_file.actuators, zeros), abs=1e-9)
    assert geometry["actuators.thruster_5.direction"] == pytest.approx([0.0, 0.0, 1.0], abs=1e-12)


def test_a_flu_urdf_read_as_frd_flips_the_geometry():
    full = read_parameters(BLUEROV)
    geometry = geometry_parameters(urdf_of(full, "flu"), without_geometry(BLUEROV, frame="frd"))
    assert geometry["actuators.thruster_1.position"] == pytest.approx(
        np.array(full["actuators.thruster_1.position"]) * FLU)


def test_azimuth_thrusters_take_the_position_and_must_turn_about_z():
    full = read_parameters(EXAMPLE)
    parameters = without_geometry(EXAMPLE, frame="flu")
    azimuths = {"azimuth_fwd": "revolute", "azimuth_aft": "revolute"}
    # the link's x axis is +x (direction defaults to it); turning about the body z is the link's z
    geometry = geometry_parameters(urdf_of(full, "flu", azimuths, {"azimuth_fwd": "0 0 1", "azimuth_aft": "0 0 1"}),
                                   parameters)
    vehicle = vehicle_from_parameters({**parameters, **geometry})
    assert vehicle.actuator("azimuth_fwd").position == pytest.approx(full["actuators.azimuth_fwd.position"])
    assert "actuators.azimuth_fwd.direction" not in geometry
    with pytest.raises(ConfigError, match=r"actuators\.azimuth_aft\.link: the axis of joint 'azimuth_aft_joint'"):
        geometry_parameters(urdf_of(full, "flu", azimuths, {"azimuth_fwd": "0 0 1"}), parameters)


def test_problems_are_named_per_actuator():
    full = read_parameters(BLUEROV)
    parameters = without_geometry(BLUEROV, frame="flu")
    text = urdf_of(full, "flu", {"thruster_2": "fixed"})
    broken = {**parameters, "actuators.thruster_1.link": "ghost", "actuators.thruster_3.position": [0.0, 0.0, 0.0],
              "actuators.thruster_4.link": "base_footprint"}
    with pytest.raises(ConfigError) as error:
        geometry_parameters(text, broken)
    problems = dict(error.value.problems)
    assert problems["actuators.thruster_1.link"] == "no joint has link 'ghost' as its child"
    assert "revolute or continuous joint" in problems["actuators.thruster_2.link"]
    assert "comes from the robot description" in problems["actuators.thruster_3.position"]
    assert problems["actuators.thruster_4.link"] == "no joint has link 'base_footprint' as its child"
    moving = text.replace('name="hull_mount" type="fixed"', 'name="hull_mount" type="revolute"')
    with pytest.raises(ConfigError, match="joint 'hull_mount' between 'base_link' and 'thruster_1' is revolute"):
        geometry_parameters(moving, parameters)
    with pytest.raises(ConfigError, match="is not below base_frame 'hull_x'"):
        geometry_parameters(text, {**parameters, "base_frame": "hull_x"})
    with pytest.raises(ConfigError, match="robot_description: not valid XML"):
        geometry_parameters("<robot>", parameters)


def test_the_node_reads_a_urdf_file_and_keeps_its_geometry(tmp_path, ros_context):
    """A node with geometry_source robot_description and robot_description_file: the geometry is
    the URDF's, and a runtime change of a position is refused."""
    from rclpy.parameter import Parameter

    from allocator_pkg.ros.node import AllocatorNode
    full = read_parameters(BLUEROV)
    description = tmp_path / "bluerov2.urdf"
    description.write_text(urdf_of(full, "flu"))
    params = write_parameters(tmp_path / "bluerov2.yaml", without_geometry(
        BLUEROV, frame="flu", robot_description_file=str(description)))
    node = AllocatorNode(context=ros_context, cli_args=["--ros-args", "--params-file", str(params)])
    try:
        position = node.allocator.vehicle.actuator("thruster_1").position
        assert position == pytest.approx(full["actuators.thruster_1.position"])
        result = node.set_parameters([Parameter("actuators.thruster_1.position", value=[0.0, 0.0, 0.0])])[0]
        assert not result.successful and "comes from the robot description" in result.reason
    finally:
        node.release()
        node.destroy_node()
