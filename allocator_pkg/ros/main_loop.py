"""The process of ``allocator_node`` and ``allocator_lifecycle_node``: rclpy set up without its
signal handlers, the node made and spun by the executor its ``executor`` parameter names until
SIGINT/SIGTERM (or the node's end), then stopped and freed."""

from __future__ import annotations

import gc
import os
import signal
import sys
import threading
import time
from collections.abc import Callable

import rclpy
from rclpy.executors import Executor, SingleThreadedExecutor
from rclpy.experimental import EventsExecutor
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions

from ..vehicle.node_settings import EVENTS, SINGLE_THREADED
from .node_base import AllocatorBase, NodeConfigError
from .process import dds_environment

SPIN_TIMEOUT = 0.1           # s: the longest the main loop waits before it looks for the end again


def make_executor(node: Node) -> Executor:
    """The executor the ``executor`` parameter names (read-only; checked with the others, so a
    value it does not know leaves the default here and is refused by the configuration)."""
    name = node.get_parameter("executor").value if node.has_parameter("executor") else EVENTS
    return SingleThreadedExecutor() if name == SINGLE_THREADED else EventsExecutor()


def spin(make_node: Callable[[], AllocatorBase | Node], args: list[str] | None = None) -> int:
    """A node's process: spin it until SIGINT/SIGTERM (or its end), then stop it. Exit code 1
    with the report of an invalid configuration found at start.

    What exists once the node is made (modules, the node, its solvers) lives as long as the
    process, so it is frozen out of the garbage collector's reach (``gc.freeze``): a full
    collection then scans only what came since rather than the whole heap, a pause that would
    hold up samples. docs/performance.md gives what the process spends per sample against a
    bare rclpy node (``bench/overhead.py``) and the periods it misses over a long run
    (``bench/soak.py``). DDS runs in the environment's domain and discovery range, on this
    machine in domain 42 when they are not set (:func:`~.process.dds_environment`), as every
    entry point of the package does."""
    os.environ.update(dds_environment())
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    stop = threading.Event()
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signal_number, lambda *_: stop.set())
    try:
        node = make_node()
    except NodeConfigError as error:
        print(error.report(), file=sys.stderr)
        rclpy.try_shutdown()
        return 1
    gc.collect()
    gc.freeze()
    executor = make_executor(node)
    executor.add_node(node)
    try:
        check = 0.0
        while not stop.is_set():
            executor.spin_once(timeout_sec=SPIN_TIMEOUT)
            now = time.monotonic()
            if now >= check:        # a lifecycle shutdown or a context gone: looked for every SPIN_TIMEOUT
                check = now + SPIN_TIMEOUT
                if node.finished or not rclpy.ok():
                    break
        node.stop()
    finally:
        executor.shutdown()
        node.release()
        node.destroy_node()
        rclpy.try_shutdown()
    return 0
