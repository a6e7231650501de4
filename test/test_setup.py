"""Set-up prerequisites are named plainly, without a traceback."""

import os
import shutil
import subprocess
import sys

from conftest import ROOT

CHECK = ROOT / "tools" / "check_prereqs.sh"


def run(python, path):
    return subprocess.run(["sh", str(CHECK), python], capture_output=True, text=True,
                          env={**os.environ, "PATH": path})


def test_all_present_here():
    result = run(sys.executable, os.environ["PATH"])
    assert result.returncode == 0, result.stderr


def test_missing_python_and_tools_are_named(tmp_path):
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for tool in ("sh", "dirname"):
        if shutil.which(tool):
            os.symlink(shutil.which(tool), bin_dir / tool)
    result = run("python3.99", str(bin_dir))
    assert result.returncode == 1
    assert "'python3.99' not found" in result.stderr
    assert "cmake not found" in result.stderr
    assert "no C compiler" in result.stderr
    assert "Traceback" not in result.stderr


def test_wrong_python_version_is_named(tmp_path):
    fake = tmp_path / "python3"
    # answers the version query with 3.9.1 and fails every other check
    fake.write_text('#!/bin/sh\ncase "$2" in *platform*) echo 3.9.1;; *) exit 1;; esac\n')
    fake.chmod(0o755)
    result = run(str(fake), os.environ["PATH"])
    assert result.returncode == 1
    assert "is Python 3.9.1; the ROS 2 Jazzy wheels need 3.11 or 3.12" in result.stderr


def test_an_interpreter_that_does_not_run_is_named_with_what_it_said(tmp_path):
    shim = tmp_path / "python3.12"
    shim.write_text('#!/bin/sh\necho "pyenv: python3.12: command not found" >&2\nexit 127\n')
    shim.chmod(0o755)
    result = run(str(shim), os.environ["PATH"])
    assert result.returncode == 1
    assert f"'{shim}' does not run ({shim}: pyenv: python3.12: command not found)" in result.stderr
    assert "is Python ;" not in result.stderr
