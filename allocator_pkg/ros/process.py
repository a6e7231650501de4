"""The processes of this package: the DDS environment each one starts with, and a node (or any
command) run as a child process.

Every process keeps DDS discovery on this machine unless the caller chose otherwise:
``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST`` and ``ROS_DOMAIN_ID=42``, as the Makefile and the
test suite set them. A script applies them before rclpy loads::

    os.environ.update(dds_environment())

A child process runs in that DDS environment too, whatever its parent's, and writes its output
(stdout and stderr) to a file, not to a pipe that nobody reads and that would block it once
full; it is stopped with SIGINT, as Ctrl-C would, killed if it does not end, and reaped. An
error raised while it runs carries that output as a note.

A run (``allocator-sim``, the pytest plugin's harness, a test) puts its nodes in a namespace of
its own (``run_namespace``, given as ``namespace_arguments``), so that any number of runs share
a machine and a domain, or a vehicle's network: the nodes' topics and services are relative and
follow the namespace, and the topics every node shares by name (``/clock``, ``/diagnostics``)
move into it too.

Nothing here imports rclpy: this is process machinery, used before ROS loads.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import secrets
import signal
import subprocess
import sys
import tempfile
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import IO

DDS_DEFAULTS = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", "ROS_DOMAIN_ID": "42"}
"""The DDS environment of a process whose caller did not set it: discovery on this machine only."""
NODE = "allocator_node"
STOP_TIMEOUT = 10.0
"""[s] a child process has to end after SIGINT before it is killed."""
SHARED_TOPICS = ("/clock", "/diagnostics")
"""The absolute topics of a node, which a run's namespace would not move without a remapping."""
PR_SET_PDEATHSIG = 1
"""prctl option: the signal a process gets when its parent ends (linux/prctl.h)."""


def dds_environment(environment: Mapping[str, str] = os.environ) -> dict[str, str]:
    """The DDS variables a process runs with: each as ``environment`` has it, else its default
    (``DDS_DEFAULTS``)."""
    return {name: environment.get(name, default) for name, default in DDS_DEFAULTS.items()}


def run_namespace() -> str:
    """A namespace of one run's own: ``/run_<process id>_<8 random hex digits>``, unique among the
    runs of a machine (and, with its randomness, of a network)."""
    return f"/run_{os.getpid()}_{secrets.token_hex(4)}"


def namespace_arguments(namespace: str) -> list[str]:
    """The ROS arguments (after ``--ros-args``) that put a node in ``namespace`` with its shared
    topics (``SHARED_TOPICS``: ``/clock`` becomes ``<namespace>/clock``). Given to ``rclpy.init``
    they apply to every node of that context."""
    if not namespace.startswith("/") or namespace == "/" or namespace.endswith("/"):
        raise ValueError(f"a run's namespace is absolute and not the root: '{namespace}'")
    remaps = [f"__ns:={namespace}", *(f"{topic}:={namespace}{topic}" for topic in SHARED_TOPICS)]
    return [argument for remap in remaps for argument in ("-r", remap)]


UNKNOWN_NODE = "_NODE_NAME_UNKNOWN_"
"""The node name the ROS graph gives an endpoint whose node it has not discovered yet."""


def node_of(endpoint) -> str:
    """The fully qualified name of the node of a publisher or subscription (an rclpy
    ``TopicEndpointInfo``)."""
    return f"{endpoint.node_namespace.rstrip('/')}/{endpoint.node_name}"


def executable(name: str) -> Path:
    """The console script ``name`` installed beside this Python (``allocator_node``, ``allocator-ctl``)."""
    return Path(sys.executable).parent / name


def node_command(params_file: str | Path, *ros_arguments: str, parameters: Iterable[str] = (),
                 node: str = NODE) -> list[str]:
    """The command line of the allocator node ``node`` on ``params_file``: each of ``parameters``
    (``name:=value``) as ``-p``, then ``ros_arguments`` (``-r __ns:=/rov1``, ``--log-level warn``)."""
    return [str(executable(node)), "--ros-args", "--params-file", str(params_file),
            *(argument for parameter in parameters for argument in ("-p", parameter)), *ros_arguments]


def _ends_with_parent() -> None:
    """In the child, before its program starts: SIGTERM when the parent ends (Linux's
    PR_SET_PDEATHSIG; strictly, when the parent's thread that started it ends), so that a parent
    killed mid-run leaves no node behind answering in its domain, where it would take the next
    run's messages for its own."""
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)


class ChildProcess(subprocess.Popen):
    """A child process in this process's environment with the DDS defaults (``dds_environment``),
    its output (stdout and stderr) into the file ``log``."""

    def __init__(self, command: Sequence[str], log: IO[str], dies_with_parent: bool = False) -> None:
        super().__init__(list(command), stdout=log, stderr=subprocess.STDOUT, text=True,
                         env={**os.environ, **dds_environment()},
                         preexec_fn=_ends_with_parent if dies_with_parent else None)
        self.log = log
        self._kept: str | None = None

    def output(self) -> str:
        """Everything the process has written so far (all of it, once ``keep_output`` has run)."""
        if self._kept is not None:
            return self._kept
        self.log.flush()
        self.log.seek(0)
        return self.log.read()

    def keep_output(self) -> None:
        """Read the output once and for all, so that it outlives its file."""
        self._kept = self.output()

    def stop(self, timeout: float = STOP_TIMEOUT) -> int:
        """SIGINT, then ``timeout`` seconds to end before it is killed; its exit code (at once
        if it has ended already)."""
        if self.poll() is None:
            self.send_signal(signal.SIGINT)
            try:
                self.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                self.kill()
                self.wait()
        return self.returncode


@contextlib.contextmanager
def child_process(command: Sequence[str], output: Path | None = None,
                  dies_with_parent: bool = False) -> Iterator[ChildProcess]:
    """``command`` as a child process, its output in the file ``output`` (a temporary one by
    default), stopped (``ChildProcess.stop``) and reaped on exit. An exception raised inside
    gets the process's output as a note. ``dies_with_parent``: it ends when this process (this
    thread) does, however it ends."""
    with contextlib.ExitStack() as stack:
        if output is None:
            log = stack.enter_context(tempfile.TemporaryFile("a+"))
        else:
            output.write_text("")
            log = stack.enter_context(output.open("a+"))
        process = ChildProcess(command, log, dies_with_parent)
        try:
            yield process
        except Exception as error:
            process.stop()
            error.add_note(f"{Path(command[0]).name} output:\n{process.output()}")
            raise
        finally:
            process.stop()
            process.keep_output()
