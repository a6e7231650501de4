"""The bare rclpy nodes the allocator's own cost is measured against, each in its own process.

``echo``: subscribes a WrenchStamped on ``wrench_command`` (best effort, as the allocator's
input) and publishes it back at once on ``echo``: one subscription, one publisher, one message
per sample, nothing else in its wait set. ``timer RATE``: one timer publishing one
WrenchStamped on ``echo`` at RATE Hz. Both spin a SingleThreadedExecutor until SIGINT.

Started by ``bench/overhead.py`` as a child process, in the DDS environment of every process of
the package (``allocator_pkg.ros.process``); it imports nothing of ``allocator_pkg`` itself, so
that it carries nothing but rclpy.

    .venv/bin/python bench/bare.py echo | timer RATE_HZ
"""

import contextlib
import sys

import rclpy
from geometry_msgs.msg import WrenchStamped
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.qos import QoSProfile, ReliabilityPolicy


def main(argv: list[str]) -> int:
    """``argv``: ``echo`` or ``timer RATE``, then the ROS arguments (its namespace)."""
    rclpy.init(args=["bare", *argv])
    argv = rclpy.utilities.remove_ros_args(["bare", *argv])[1:]
    node = rclpy.create_node("bare_bench_node")
    publisher = node.create_publisher(WrenchStamped, "echo", QoSProfile(depth=10))
    if argv[0] == "echo":
        node.create_subscription(WrenchStamped, "wrench_command", publisher.publish,
                                 QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT))
    else:
        message = WrenchStamped()
        node.create_timer(1.0 / float(argv[1]), lambda: publisher.publish(message))
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    with contextlib.suppress(KeyboardInterrupt, ExternalShutdownException):
        executor.spin()
    node.destroy_node()
    rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
