"""allocator_pkg.ros.process: the DDS environment of a process and a child process with its output
in a file, stopped with SIGINT, killed if it hangs, reaped, its output on an error."""

import os
import re
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from allocator_pkg.ros.process import (
    child_process,
    dds_environment,
    executable,
    namespace_arguments,
    node_command,
    run_namespace,
)

WAITS_FOR_SIGINT = """
import sys, time
try:
    print("ready", flush=True)
    time.sleep(60)
except KeyboardInterrupt:
    print("interrupted", flush=True)
    sys.exit(3)
"""
IGNORES_SIGINT = """
import signal, time
signal.signal(signal.SIGINT, signal.SIG_IGN)
print("ready", flush=True)
time.sleep(60)
"""


def python(code):
    return [sys.executable, "-c", code]


def wait_for(process, text, timeout=20.0):
    """Until ``text`` is in the child's output. Wait for a whole line: an unbuffered print writes
    the text and the newline apart, and a signal between the two ends the print."""
    deadline = time.monotonic() + timeout
    while text not in process.output():
        assert process.poll() is None and time.monotonic() < deadline, process.output()
        time.sleep(0.02)


def running(pid):
    """Whether process ``pid`` exists and has not ended (a zombie has)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def test_dds_stays_on_this_machine_unless_the_caller_chose():
    assert dds_environment({}) == {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", "ROS_DOMAIN_ID": "42"}
    chosen = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET", "ROS_DOMAIN_ID": "7", "HOME": "/root"}
    assert dds_environment(chosen) == {"ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET", "ROS_DOMAIN_ID": "7"}
    assert dds_environment({"ROS_DOMAIN_ID": "7"})["ROS_AUTOMATIC_DISCOVERY_RANGE"] == "LOCALHOST"


def test_a_child_runs_in_the_dds_environment_whatever_its_parents(monkeypatch):
    monkeypatch.delenv("ROS_AUTOMATIC_DISCOVERY_RANGE", raising=False)
    monkeypatch.setenv("ROS_DOMAIN_ID", "7")
    monkeypatch.setenv("SOMETHING_ELSE", "kept")
    printed = "import os; print(*(os.environ.get(name) for name in ('ROS_AUTOMATIC_DISCOVERY_RANGE', "
    printed += "'ROS_DOMAIN_ID', 'SOMETHING_ELSE')))"
    with child_process(python(printed)) as process:
        process.wait(timeout=20)
    assert process.output() == "LOCALHOST 7 kept\n"
    assert "ROS_AUTOMATIC_DISCOVERY_RANGE" not in os.environ            # the parent's own is left alone


def test_the_node_command_gives_the_params_file_then_parameters_then_ros_arguments():
    assert node_command("v.yaml", "-r", "__ns:=/rov1", parameters=["rate_hz:=100.0", "trigger:=input"]) == [
        str(executable("allocator_node")), "--ros-args", "--params-file", "v.yaml", "-p", "rate_hz:=100.0",
        "-p", "trigger:=input", "-r", "__ns:=/rov1"]
    assert node_command("v.yaml", node="allocator_lifecycle_node")[0] == str(executable("allocator_lifecycle_node"))


def test_a_run_namespace_is_its_own_and_takes_the_shared_topics_into_it():
    first, second = run_namespace(), run_namespace()
    assert re.fullmatch(rf"/run_{os.getpid()}_[0-9a-f]{{8}}", first) and first != second
    assert namespace_arguments("/run_7_0badcafe") == ["-r", "__ns:=/run_7_0badcafe",
                                                       "-r", "/clock:=/run_7_0badcafe/clock",
                                                       "-r", "/diagnostics:=/run_7_0badcafe/diagnostics"]
    for bad in ("run_7", "/", "/run_7/"):
        with pytest.raises(ValueError, match=f"a run's namespace is absolute and not the root: '{bad}'"):
            namespace_arguments(bad)


def test_a_child_is_stopped_with_sigint_and_reaped_its_output_in_a_file(tmp_path):
    log = tmp_path / "child.log"
    log.write_text("a previous run\n")
    with child_process(python(WAITS_FOR_SIGINT), output=log) as process:
        wait_for(process, "ready\n")
    assert process.returncode == 3                      # its own handler ran: SIGINT, not a kill
    assert process.output() == log.read_text() == "ready\ninterrupted\n"
    with pytest.raises(ProcessLookupError):
        os.kill(process.pid, 0)                         # reaped


def test_a_child_that_ignores_sigint_is_killed():
    with child_process(python(IGNORES_SIGINT)) as process:
        wait_for(process, "ready\n")
        assert process.stop(timeout=0.5) == -signal.SIGKILL
    assert process.stop() == -signal.SIGKILL            # ended already: its exit code at once


def test_an_error_raised_while_the_child_runs_carries_its_output():
    with pytest.raises(RuntimeError) as raised, child_process(python(WAITS_FOR_SIGINT)) as process:
        wait_for(process, "ready\n")
        raise RuntimeError("no answer")
    assert raised.value.__notes__ == [f"{os.path.basename(sys.executable)} output:\nready\ninterrupted\n"]
    assert process.returncode == 3


def test_a_child_that_dies_with_its_parent_ends_when_the_parent_is_killed(tmp_path):
    """The parent, killed with SIGKILL, cannot stop the child itself; the kernel sends it SIGTERM."""
    parent = textwrap.dedent("""
        import sys, time
        from allocator_pkg.ros.process import child_process
        with child_process([sys.executable, "-c", "import time; time.sleep(60)"], dies_with_parent=True) as child:
            print(child.pid, flush=True)
            time.sleep(60)
    """)
    with subprocess.Popen(python(parent), stdout=subprocess.PIPE, text=True) as process:
        child = int(process.stdout.readline())
        process.kill()
    deadline = time.monotonic() + 10.0
    try:
        while running(child):
            assert time.monotonic() < deadline, "the child outlived its parent"
            time.sleep(0.05)
    finally:
        if running(child):
            os.kill(child, signal.SIGKILL)
