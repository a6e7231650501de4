"""package.xml declares every ROS package the code imports (rcl_interfaces included),
and the pip rosdep keys of what it imports from PyPI are defined in the repository's own rosdep.yaml."""

import ast
import xml.etree.ElementTree as ElementTree

import yaml
from conftest import ROOT

ROS_PACKAGES = {"rclpy", "rcl_interfaces", "lifecycle_msgs", "geometry_msgs", "std_msgs", "std_srvs", "nav_msgs",
                "diagnostic_msgs", "visualization_msgs", "builtin_interfaces", "rosgraph_msgs", "allocator_msgs",
                "sensor_msgs"}


def imported_modules() -> set[str]:
    found = set()
    for path in (ROOT / "allocator_pkg").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                found.update(alias.name.split(".")[0] for alias in node.names)
            elif isinstance(node, ast.ImportFrom) and not node.level:
                found.add(node.module.split(".")[0])
    return found


def test_every_imported_ros_package_is_an_exec_depend():
    depends = {element.text for element in ElementTree.parse(ROOT / "package.xml").getroot().iter("exec_depend")}
    imported = imported_modules() & ROS_PACKAGES
    assert {"rclpy", "rcl_interfaces", "visualization_msgs"} <= imported
    assert imported <= depends, f"not declared: {sorted(imported - depends)}"
    assert "lifecycle_msgs" in depends                      # rclpy.lifecycle's services


PIP_PACKAGES = {"osqp": "osqp", "daqp": "daqp", "highspy": "highspy", "mcap": "mcap", "mcap_ros2": "mcap-ros2-support"}
"""Imported module -> PyPI package of what the code needs from pip (no rosdistro key exists)."""


def test_every_pip_package_the_code_imports_has_a_rosdep_key_defined_here():
    depends = {element.text for element in ElementTree.parse(ROOT / "package.xml").getroot().iter("exec_depend")}
    rules = yaml.safe_load((ROOT / "rosdep.yaml").read_text())
    pip_keys = {key for key in depends if key.endswith("-pip")}
    imported = imported_modules() & set(PIP_PACKAGES)
    assert {"osqp", "daqp", "highspy", "mcap", "mcap_ros2"} <= imported
    assert pip_keys == {f"python3-{PIP_PACKAGES[name]}-pip" for name in imported} == set(rules)
    for name in imported:
        for platform in ("debian", "fedora", "osx", "rhel", "ubuntu"):
            assert rules[f"python3-{PIP_PACKAGES[name]}-pip"][platform]["pip"]["packages"] == [PIP_PACKAGES[name]]
