"""Start the thrust allocator (node ``thrust_allocator``) with a vehicle params file.

    ros2 launch allocator_pkg allocator.launch.py
    ros2 launch allocator_pkg allocator.launch.py config:=/path/to/vehicle.yaml namespace:=rov1 frame:=flu
    ros2 launch allocator_pkg allocator.launch.py wrench_topic:=/controller/wrench log_level:=debug
    ros2 launch allocator_pkg allocator.launch.py lifecycle:=true    # allocator_lifecycle_node, unconfigured

``config`` defaults to the package's config/default.yaml. The shipped files are keyed ``/**:``,
so they apply under any ``namespace`` and node ``name``; topics and services are relative, so
a namespace moves all of them. ``wrench_topic``, ``commands_topic`` and ``status_topic`` remap
the three main topics (relative names resolve in the namespace). ``frame`` is the body frame
convention of the wrenches (frd or flu; the params file's value when empty).
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import LaunchConfiguration, PythonExpression
from launch_ros.actions import LifecycleNode, Node

from launch import LaunchDescription

PACKAGE = "allocator_pkg"
DEFAULT_CONFIG = os.path.join("config", "default.yaml")
ARGUMENTS = (
    ("config", None, "Vehicle params file (ROS 2 params YAML)"),
    ("namespace", "", "Namespace of the node"),
    ("name", "thrust_allocator", "Name of the node"),
    ("frame", "", "Body frame convention of the wrenches: frd or flu (empty: the params file's)"),
    ("wrench_topic", "wrench_command", "Remap of wrench_command"),
    ("commands_topic", "thruster_commands", "Remap of thruster_commands"),
    ("status_topic", "allocation_status", "Remap of allocation_status"),
    ("log_level", "info", "Log level: debug, info, warn, error or fatal"),
    ("use_sim_time", "false", "Use /clock time"),
    ("lifecycle", "false", "Start allocator_lifecycle_node (managed, unconfigured) instead of allocator_node"),
)


def generate_launch_description():
    default_config = os.path.join(get_package_share_directory(PACKAGE), DEFAULT_CONFIG)
    declared = [DeclareLaunchArgument(name, default_value=default if default is not None else default_config,
                                      description=description) for name, default, description in ARGUMENTS]
    frame = LaunchConfiguration("frame")
    overrides = PythonExpression(["{'frame': '", frame, "'} if '", frame, "' else {}"])
    common = dict(
        package=PACKAGE,
        name=LaunchConfiguration("name"),
        namespace=LaunchConfiguration("namespace"),
        parameters=[LaunchConfiguration("config"), {"use_sim_time": LaunchConfiguration("use_sim_time")}, overrides],
        remappings=[("wrench_command", LaunchConfiguration("wrench_topic")),
                    ("thruster_commands", LaunchConfiguration("commands_topic")),
                    ("allocation_status", LaunchConfiguration("status_topic"))],
        ros_arguments=["--log-level", LaunchConfiguration("log_level")],
        output="screen",
        emulate_tty=True,
    )
    lifecycle = LaunchConfiguration("lifecycle")
    return LaunchDescription([
        *declared,
        Node(executable="allocator_node", condition=UnlessCondition(lifecycle), **common),
        LifecycleNode(executable="allocator_lifecycle_node", condition=IfCondition(lifecycle), **common),
    ])
