"""ROS 2 managed node ``thrust_allocator`` (executable ``allocator_lifecycle_node``): the same
parameters, topics and services as ``allocator_node``, driven by the lifecycle_msgs services.

- configure: reads and checks the parameters (and the robot description), builds the
  allocator and its solver, creates the topics; a bad configuration fails the transition with
  the reasons logged, and the node stays unconfigured;
- activate: rclpy enables the output topics (lifecycle publishers), then commands start (the
  watchdog waits for the first wrench);
- deactivate: one zero-thrust command, then none: sampling stops and rclpy disables the
  output topics;
- cleanup: frees the allocator, its solver and the topics;
- shutdown, from any state: as deactivate if active, then cleanup; the process then exits.

The fault services answer in every state (``success: false`` until configured).
"""

from __future__ import annotations

import sys

from rclpy.lifecycle import LifecycleNode, LifecycleState, TransitionCallbackReturn

from ..vehicle.node_settings import NODE_NAME
from .main_loop import spin
from .node_base import AllocatorBase, NodeConfigError


class AllocatorLifecycleNode(AllocatorBase, LifecycleNode):
    """The managed allocation node; starts unconfigured."""

    def __init__(self, **kwargs):
        super().__init__(NODE_NAME, automatically_declare_parameters_from_overrides=True, **kwargs)
        self.setup_allocator()
        self._finished = False

    @property
    def finished(self) -> bool:
        return self._finished

    def on_configure(self, state: LifecycleState) -> TransitionCallbackReturn:
        try:
            self._runtime = self.load()
        except NodeConfigError as error:
            self.get_logger().error(error.report())
            return TransitionCallbackReturn.FAILURE
        return super().on_configure(state)

    def on_activate(self, state: LifecycleState) -> TransitionCallbackReturn:
        """rclpy enables the lifecycle publishers, then sampling starts: the first sample is published."""
        result = super().on_activate(state)
        if result != TransitionCallbackReturn.SUCCESS:
            return result
        self._runtime.activate()
        self.get_logger().info("active: commanding")
        return result

    def on_deactivate(self, state: LifecycleState) -> TransitionCallbackReturn:
        """The zero-thrust command goes out and sampling stops, then rclpy disables the lifecycle publishers."""
        self._runtime.deactivate()
        self.get_logger().info("inactive: published zero thrust, commanding nothing")
        return super().on_deactivate(state)

    def on_cleanup(self, state: LifecycleState) -> TransitionCallbackReturn:
        self.release()
        return super().on_cleanup(state)

    def on_shutdown(self, state: LifecycleState) -> TransitionCallbackReturn:
        self._stop_and_release()
        self._finished = True
        return super().on_shutdown(state)

    def on_error(self, state: LifecycleState) -> TransitionCallbackReturn:
        self.get_logger().error(f"error in a transition from {state.label}: zero thrust, back to unconfigured")
        self._stop_and_release()
        return super().on_error(state)

    def _stop_and_release(self) -> None:
        """One zero-thrust command if active (acknowledged if possible), then free everything."""
        self.stop()
        self.release()


def main(args: list[str] | None = None) -> int:
    """Entry point of ``allocator_lifecycle_node``: spin until SIGINT/SIGTERM or the shutdown
    transition; on a signal while active, command zero thrust."""
    return spin(AllocatorLifecycleNode, args)


if __name__ == "__main__":
    sys.exit(main())
