"""colcon builds both packages the way a ROS workspace does (the nested allocator_msgs named
with --base-paths), and installs what `ros2 run` and `ros2 launch` need."""

import os
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT

pytestmark = pytest.mark.slow


def test_colcon_build_installs_both_packages(tmp_path):
    venv = Path(sys.prefix)
    env = dict(os.environ)
    env["PATH"] = f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["CMAKE_PREFIX_PATH"] = str(venv)
    env["AMENT_PREFIX_PATH"] = str(venv)
    result = subprocess.run(
        [str(venv / "bin" / "colcon"), "--log-base", str(tmp_path / "log"), "build",
         "--base-paths", str(ROOT), str(ROOT / "allocator_msgs"),
         "--build-base", str(tmp_path / "build"), "--install-base", str(tmp_path / "install"),
         "--cmake-args", f"-DPython3_EXECUTABLE={venv / 'bin' / 'python'}", "-DBUILD_TESTING=OFF"],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    assert "Finished <<< allocator_msgs" in result.stdout and "Finished <<< allocator_pkg" in result.stdout
    install = tmp_path / "install"
    assert (install / "allocator_pkg" / "lib" / "allocator_pkg" / "allocator_node").is_file()
    assert (install / "allocator_pkg" / "lib" / "allocator_pkg" / "allocator-ctl").is_file()
    share = install / "allocator_pkg" / "share" / "allocator_pkg"
    configs = {p.name for p in (share / "config").glob("*.yaml")}
    assert {p.name for p in (ROOT / "config").glob("*.yaml")} == configs
    assert (share / "launch" / "allocator.launch.py").is_file()
    assert (share / "package.xml").is_file()
    index = install / "allocator_pkg" / "share" / "ament_index" / "resource_index" / "packages"
    assert (index / "allocator_pkg").is_file()
    python = "lib/python3*/site-packages/allocator_msgs"
    assert list((install / "allocator_msgs").glob(f"{python}/msg/_thruster_commands.py")), "no generated types"
    assert list((install / "allocator_msgs").glob(f"{python}/srv/_set_actuator_fault.py")), "no generated service"
