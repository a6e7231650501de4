"""ROS 2 node ``thrust_allocator`` (executable ``allocator_node``): starts allocating as soon as
its configuration is valid.

The topics, timers and samples are :mod:`allocator_pkg.ros.runtime`'s, the services, parameter
checks and loading :mod:`allocator_pkg.ros.node_base`'s and the process's main loop
:mod:`allocator_pkg.ros.main_loop`'s, shared with the managed variant
:mod:`allocator_pkg.ros.lifecycle_node`. See README.md for the interface.
"""

from __future__ import annotations

import sys

from rclpy.node import Node

from ..vehicle.node_settings import NODE_NAME
from .main_loop import spin
from .node_base import AllocatorBase, NodeConfigError


class AllocatorNode(AllocatorBase, Node):
    """The allocation node. Raises NodeConfigError if its parameters are invalid.

    With the geometry from the ``robot_description`` topic it waits for the first description,
    then starts (an invalid one is reported and the next awaited)."""

    def __init__(self, **kwargs):
        super().__init__(NODE_NAME, automatically_declare_parameters_from_overrides=True, **kwargs)
        self.setup_allocator()
        if self.waiting_for_description:
            self.get_logger().info(f"waiting for {self._description_topic}")
        else:
            self._start()

    def _start(self) -> None:
        self._runtime = self.load()
        self._runtime.activate()

    def on_robot_description(self) -> None:
        if self._runtime is not None:
            self.get_logger().warn(f"a new robot description on {self._description_topic} is not used: the "
                                   "geometry is read once, at start")
            return
        try:
            self._start()
        except NodeConfigError as error:
            self.get_logger().error(error.report())

    def publish_stop(self, timeout: float) -> bool:
        """One zero-thrust command, angles held; whether every subscriber acknowledged it in ``timeout`` s."""
        return self._runtime.publish_stop(timeout)


def main(args: list[str] | None = None) -> int:
    """Entry point of ``allocator_node``: spin until SIGINT/SIGTERM, then command zero thrust."""
    return spin(AllocatorNode, args)


if __name__ == "__main__":
    sys.exit(main())
