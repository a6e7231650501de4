"""The launch file (for real ROS installs; no launch wheels exist here): it compiles, and the
files it names are in the package."""

import ast
import py_compile

from conftest import ROOT

LAUNCH = ROOT / "launch" / "allocator.launch.py"


def test_launch_file_compiles():
    py_compile.compile(str(LAUNCH), doraise=True)


def test_launch_file_names_existing_files_and_the_real_executable():
    tree = ast.parse(LAUNCH.read_text())
    constants = {node.targets[0].id: node.value for node in tree.body
                 if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name)}
    config = constants["DEFAULT_CONFIG"]
    parts = [arg.value for arg in config.args]
    assert (ROOT.joinpath(*parts)).is_file()
    strings = {node.value for node in ast.walk(tree) if isinstance(node, ast.Constant)}
    assert {"allocator_pkg", "allocator_node", "thrust_allocator", "config", "namespace"} <= strings
    setup = (ROOT / "setup.py").read_text()
    assert "allocator_node = allocator_pkg.node:main" in setup
