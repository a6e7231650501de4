"""Start allocator_node (node ``thrust_allocator``) with a vehicle params file.

    ros2 launch allocator_pkg allocator.launch.py
    ros2 launch allocator_pkg allocator.launch.py config:=/path/to/vehicle.yaml namespace:=rov1

``config`` defaults to the package's config/default.yaml; topics and services are relative,
so a namespace moves all of them (remap further with the usual launch remappings).
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription

PACKAGE = "allocator_pkg"
DEFAULT_CONFIG = os.path.join("config", "default.yaml")


def generate_launch_description():
    default_config = os.path.join(get_package_share_directory(PACKAGE), DEFAULT_CONFIG)
    return LaunchDescription([
        DeclareLaunchArgument("config", default_value=default_config,
                              description="Vehicle params file (ROS 2 params YAML)"),
        DeclareLaunchArgument("namespace", default_value="", description="Namespace of the node"),
        DeclareLaunchArgument("use_sim_time", default_value="false", description="Use /clock time"),
        Node(
            package=PACKAGE,
            executable="allocator_node",
            name="thrust_allocator",
            namespace=LaunchConfiguration("namespace"),
            parameters=[LaunchConfiguration("config"), {"use_sim_time": LaunchConfiguration("use_sim_time")}],
            output="screen",
            emulate_tty=True,
        ),
    ])
