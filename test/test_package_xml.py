"""package.xml declares every ROS package the code imports (rcl_interfaces included),
and the pip rosdep keys of the solvers are defined in the repository's own rosdep.yaml."""

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


def test_every_solver_the_code_imports_has_a_pip_rosdep_key_defined_here():
    depends = {element.text for element in ElementTree.parse(ROOT / "package.xml").getroot().iter("exec_depend")}
    rules = yaml.safe_load((ROOT / "rosdep.yaml").read_text())
    pip_keys = {key for key in depends if key.endswith("-pip")}
    solvers = imported_modules() & {"osqp", "daqp", "highspy", "quadprog"}
    assert {"osqp", "daqp", "highspy"} <= solvers
    assert pip_keys == {f"python3-{name}-pip" for name in solvers if name != "quadprog"} == set(rules)
    for name in solvers - {"quadprog"}:
        assert rules[f"python3-{name}-pip"]["ubuntu"]["pip"]["packages"] == [name]
