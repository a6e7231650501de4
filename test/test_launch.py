"""The launch file (for real ROS installs; no launch wheels exist here): it compiles, and the
files it names are in the package."""

import ast
import py_compile

from conftest import ROOT

LAUNCH = ROOT / "launch" / "allocator.launch.py"


def test_launch_file_compiles():
    py_compile.compile(str(LAUNCH), doraise=True)


def test_launch_file_names_existing_files_and_the_real_executables():
    tree = ast.parse(LAUNCH.read_text())
    constants = {node.targets[0].id: node.value for node in tree.body
                 if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name)}
    config = constants["DEFAULT_CONFIG"]
    parts = [arg.value for arg in config.args]
    assert (ROOT.joinpath(*parts)).is_file()
    strings = {node.value for node in ast.walk(tree) if isinstance(node, ast.Constant)}
    assert {"allocator_pkg", "allocator_node", "allocator_lifecycle_node", "thrust_allocator"} <= strings
    setup = (ROOT / "setup.py").read_text()
    assert "allocator_node = allocator_pkg.ros.node:main" in setup
    assert "allocator_lifecycle_node = allocator_pkg.ros.lifecycle_node:main" in setup


def test_launch_arguments_namespace_frame_remaps_and_log_level():
    tree = ast.parse(LAUNCH.read_text())
    arguments = next(ast.literal_eval(node.value) for node in tree.body
                     if isinstance(node, ast.Assign) and node.targets[0].id == "ARGUMENTS")
    names = {name: default for name, default, _ in arguments}
    assert {"config", "namespace", "name", "frame", "log_level", "wrench_topic", "commands_topic",
            "status_topic", "lifecycle"} <= set(names)
    # the remaps default to the node's own topic names, so that leaving them out changes nothing
    assert (names["wrench_topic"], names["commands_topic"], names["status_topic"]) == (
        "wrench_command", "thruster_commands", "allocation_status")
    strings = {node.value for node in ast.walk(tree) if isinstance(node, ast.Constant)}
    assert {"--log-level", "wrench_command", "thruster_commands", "allocation_status"} <= strings
