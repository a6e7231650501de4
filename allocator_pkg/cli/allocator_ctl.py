"""allocator-ctl: drive and watch a running thrust_allocator without the ros2 CLI.

    allocator-ctl wrench 100 0 0 0 0 20 --rate 20 --duration 5
    allocator-ctl fault main_port failed | degraded 0.5 | stuck 0.3 | nominal
    allocator-ctl group switchboard_a                         (~/set_group_fault: a redundancy group fails)
    allocator-ctl tie bt_ab open | closed                     (~/set_bus_tie: a bus-tie breaker)
    allocator-ctl clear
    allocator-ctl echo [--csv FILE] [--mcap PATH]             (--mcap: wrench, commands, status as ros2 bag records)
    allocator-ctl capability 1 0 0 0 0 0                      (~/get_capability along a wrench)
    allocator-ctl step-test [--share 0.1] [--hold 3] [--rest 2] [--actuators]   (direction check on the bench)
    allocator-ctl params get [NAME ...]
    allocator-ctl params set NAME=VALUE [NAME=VALUE ...]      (applied atomically)

``--node`` names the allocator node (default ``thrust_allocator``) and ``--namespace`` its
namespace; the same options work with ``ros2 run allocator_pkg allocator-ctl``. Every command
says on stderr which node it reached (and when several nodes have that name), or, when none
answers within ``--timeout``, what to check, and ends with exit code 1. SIGINT and SIGTERM end
``wrench`` and ``echo`` cleanly (exit code 0).
"""

from __future__ import annotations

import argparse
import difflib
import os
import sys
import time

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.impl.implementation_singleton import rclpy_implementation
from rclpy.node import Node

from allocator_msgs.srv import GetCapability

from ..configuration import params_file
from ..ros.conversions import array_to_wrench, wrench_to_array
from ..ros.echo import Echo
from ..ros.node_client import FAULT_MODES, NOT_REACHED, Controller, ServiceTimeout
from ..ros.process import UNKNOWN_NODE, dds_environment, node_of
from ..ros.recording import Recording
from ..ros.step_test_client import DirectionCheck
from ..vehicle.node_settings import NODE_NAME

RCLError = rclpy_implementation.RCLError
"""rcl's error, raised by a wait on a context a signal has just shut down."""


def unknown_parameters(names: list[str], declared: list[str], node: str) -> list[str]:
    """What to say of each of ``names`` the node has not declared, with the nearest it has."""
    problems = []
    for name in names:
        if name not in declared:
            nearest = difflib.get_close_matches(name, declared, n=1, cutoff=0.6)
            problems.append(f"'{name}' is not a parameter of {node}"
                            + (f"; did you mean {nearest[0]}?" if nearest else ""))
    return problems


def parse_value(text: str) -> object:
    """A parameter value from the command line, typed as a params file types it (1.5, 1.0e6,
    true, [a, b]); a list of numbers with one float in it is a list of floats."""
    value = params_file.parse_value(text)
    if isinstance(value, list) and value and all(isinstance(v, (int, float)) for v in value) \
            and any(isinstance(v, float) for v in value):
        value = [float(v) for v in value]
    return value


def format_capability(direction: list[float], response: GetCapability.Response) -> str:
    """The answer of ~/get_capability in words."""
    if not response.success:
        return f"no capability: {response.message}"
    achieved = " ".join(f"{v:.2f}" for v in wrench_to_array(response.achieved))
    return (f"scale {response.scale:.4g} along [{' '.join(f'{v:g}' for v in direction)}]; achieved there "
            f"[{achieved}] ({response.message})")


def _share(text: str) -> float:
    value = float(text)
    if not 0.0 < value <= 0.5:
        raise argparse.ArgumentTypeError(f"{text}: a share in (0, 0.5]")
    return value


def _seconds(text: str) -> float:
    value = float(text)
    if not 0.0 <= value <= 30.0:
        raise argparse.ArgumentTypeError(f"{text}: seconds in [0, 30]")
    return value


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="allocator-ctl", description=__doc__.split("\n\n")[0])
    parser.add_argument("--node", default=NODE_NAME, help="allocator node name (default %(default)s)")
    parser.add_argument("--namespace", default="", help="namespace of the allocator node")
    parser.add_argument("--timeout", type=float, default=5.0, help="seconds to wait for a service")
    commands = parser.add_subparsers(dest="command", required=True)
    wrench = commands.add_parser("wrench", help="publish a constant wrench_command")
    for name in ("FX", "FY", "FZ", "MX", "MY", "MZ"):
        wrench.add_argument(name, type=float)
    wrench.add_argument("--rate", type=float, default=10.0, help="Hz (default %(default)s)")
    wrench.add_argument("--duration", type=float, default=None, help="seconds (default: until Ctrl-C)")
    fault = commands.add_parser("fault", help="set an actuator fault")
    fault.add_argument("actuator")
    fault.add_argument("mode", choices=sorted(FAULT_MODES))
    fault.add_argument("value", nargs="?", type=float, default=None,
                       help="efficiency in (0, 1] for degraded, angle [rad] for stuck")
    group = commands.add_parser("group", help="fail a redundancy group (its actuators and power sources)")
    group.add_argument("group")
    tie = commands.add_parser("tie", help="open or close a bus-tie breaker (power.bus_ties)")
    tie.add_argument("tie")
    tie.add_argument("state", choices=("open", "closed"))
    commands.add_parser("clear", help="all actuators back to NOMINAL, every power source back")
    capability = commands.add_parser("capability", help="largest scale along a wrench the actuators can give now")
    for name in ("FX", "FY", "FZ", "MX", "MY", "MZ"):
        capability.add_argument(name, type=float)
    echo = commands.add_parser("echo", help="print a live table of thrust, command, azimuth and status")
    echo.add_argument("--csv", type=argparse.FileType("w"), help="also write every sample to this CSV file")
    echo.add_argument("--mcap", metavar="PATH", help="also record wrench_command, thruster_commands and "
                      "allocation_status as ros2 bag does: into PATH if it ends in .mcap, else into the bag "
                      "directory PATH (ros2 bag, Foxglove, rosbags)")
    echo.add_argument("--rate", type=float, default=2.0, help="printed lines per second (default %(default)s)")
    echo.add_argument("--duration", type=float, default=None, help="seconds (default: until Ctrl-C)")
    step = commands.add_parser("step-test", help="step each controlled DOF +/- (or, with --actuators, each "
                               "actuator alone) and print what every actuator was commanded")
    step.add_argument("--share", type=_share, default=0.1,
                      help="share of the capability along each DOF, or of each actuator's thrust_max with "
                           "--actuators, in (0, 0.5] (default %(default)s)")
    step.add_argument("--hold", type=_seconds, default=3.0, help="seconds of each step, at most 30 "
                      "(default %(default)s)")
    step.add_argument("--rest", type=_seconds, default=2.0, help="seconds of zero between steps, at most 30 "
                      "(default %(default)s)")
    step.add_argument("--rate", type=float, default=10.0, help="wrenches per second (default %(default)s)")
    step.add_argument("--actuators", action="store_true", help="hold one actuator at a time through "
                      "~/hold_actuator (the node's step_test.enabled must be true)")
    params = commands.add_parser("params", help="get or set the allocator's parameters")
    params.add_argument("action", choices=["get", "set"])
    params.add_argument("items", nargs="*", help="names to get, or NAME=VALUE to set")
    return parser


def main(argv: list[str] | None = None) -> int:
    arguments = _parser().parse_args(rclpy.utilities.remove_ros_args(sys.argv if argv is None else ["", *argv])[1:])
    if arguments.command == "fault" and arguments.mode in ("degraded", "stuck") and arguments.value is None:
        print(f"allocator-ctl: fault {arguments.mode} needs a value "
              f"({'efficiency in (0, 1]' if arguments.mode == 'degraded' else 'angle in rad'})", file=sys.stderr)
        return 2
    os.environ.update(dds_environment())            # the nodes' rule: see ros.process.dds_environment
    rclpy.init(args=sys.argv if argv is None else None)
    node = rclpy.create_node("allocator_ctl")
    controller = Controller(node, arguments.node, arguments.namespace)
    try:
        code = _run(arguments, controller)
        if arguments.command not in ("wrench", "echo"):
            _say_reached(controller)
        return code
    except ServiceTimeout as error:
        print(f"allocator-ctl: {error}", file=sys.stderr)
        return 1
    except (KeyboardInterrupt, ExternalShutdownException):
        return 0
    except RCLError:                              # SIGINT or SIGTERM shut rclpy down during a wait
        if rclpy.ok():
            raise
        return 0
    finally:
        controller.close()
        if node.executor is not None:             # step-test's and spin_once's executors end before the node
            node.executor.shutdown()
        node.destroy_node()
        rclpy.try_shutdown()


def _say_reached(controller: Controller) -> None:
    """Which node answered, on stderr; a warning when several nodes have its name."""
    print(f"allocator-ctl: reached {controller.service_prefix}", file=sys.stderr)
    named = controller.nodes_named()
    if named > 1:
        print(f"allocator-ctl: warning: {named} nodes are named {controller.service_prefix} in this domain; any of "
              "them may have answered (give each run a namespace of its own)", file=sys.stderr)


def _nodes(endpoints) -> str:
    return ", ".join(sorted({node_of(endpoint) for endpoint in endpoints}))


def _wait_for(node: Node, found, timeout: float) -> list:
    """Spin until ``found()`` (a list of endpoints) is not empty and the graph knows each one's
    node, for at most ``timeout`` s; the last ``found()``."""
    end = time.monotonic() + timeout
    while True:
        endpoints = found()
        known = all(info.node_name != UNKNOWN_NODE for info in endpoints)
        if (endpoints and known) or time.monotonic() > end or not rclpy.ok():
            return endpoints
        rclpy.spin_once(node, timeout_sec=0.05)


def _spin_for(node: Node, duration: float | None) -> None:
    """Spin until ``duration`` s have passed (None: until SIGINT or SIGTERM shuts rclpy down)."""
    end = None if duration is None else time.monotonic() + duration
    try:
        while rclpy.ok() and (end is None or time.monotonic() < end):
            rclpy.spin_once(node, timeout_sec=0.05)
    except ExternalShutdownException:
        return
    except RCLError:                              # the signal came between rclpy.ok() and the wait
        if rclpy.ok():
            raise


def _run(arguments: argparse.Namespace, controller: Controller) -> int:
    node = controller.node
    if arguments.command == "wrench":
        message = array_to_wrench([arguments.FX, arguments.FY, arguments.FZ, arguments.MX, arguments.MY, arguments.MZ])
        topic = controller.wrench.topic_name
        takers = _wait_for(node, lambda: node.get_subscriptions_info_by_topic(topic), arguments.timeout)
        if not takers:
            print(f"allocator-ctl: no node takes {topic} ({NOT_REACHED})", file=sys.stderr)
            return 1
        print(f"allocator-ctl: {topic} taken by {_nodes(takers)}", file=sys.stderr)
        node.create_timer(1.0 / arguments.rate, lambda: controller.wrench.publish(message))
        controller.wrench.publish(message)
        _spin_for(node, arguments.duration)
        return 0
    if arguments.command == "fault":
        response = controller.set_fault(arguments.actuator, arguments.mode, arguments.value or 0.0)
        print(response.message)
        return 0 if response.success else 1
    if arguments.command == "group":
        response = controller.set_group_fault(arguments.group)
        print(response.message)
        return 0 if response.success else 1
    if arguments.command == "tie":
        response = controller.set_bus_tie(arguments.tie, arguments.state == "closed")
        print(response.message)
        return 0 if response.success else 1
    if arguments.command == "clear":
        print(controller.clear_faults().message)
        return 0
    if arguments.command == "capability":
        direction = [arguments.FX, arguments.FY, arguments.FZ, arguments.MX, arguments.MY, arguments.MZ]
        response = controller.capability(direction)
        print(format_capability(direction, response))
        return 0 if response.success else 1
    if arguments.command == "echo":
        topic = node.resolve_topic_name(controller.topic("allocation_status"))
        publishers = _wait_for(node, lambda: node.get_publishers_info_by_topic(topic), arguments.timeout)
        if not publishers:
            print(f"allocator-ctl: no node publishes {topic} ({NOT_REACHED})", file=sys.stderr)
            return 1
        print(f"allocator-ctl: echoing {_nodes(publishers)} ({topic})", file=sys.stderr)
        recording = Recording(arguments.mcap) if arguments.mcap else None
        try:
            echo = Echo(controller, sys.stdout, arguments.csv, arguments.rate, recording)
            _spin_for(node, arguments.duration)
            echo.close()
        finally:
            if recording is not None:
                recording.close()
        return 0
    if arguments.command == "step-test":
        check = DirectionCheck(controller, sys.stdout, arguments.share, arguments.hold, arguments.rest, arguments.rate)
        return check.run_actuators(arguments.share) if arguments.actuators else check.run_dofs()
    values = {}
    if arguments.action == "set":
        for item in arguments.items:
            name, separator, text = item.partition("=")
            if not separator:
                print(f"allocator-ctl: '{item}' is not NAME=VALUE", file=sys.stderr)
                return 2
            values[name] = parse_value(text)
    names = list(values) if arguments.action == "set" else arguments.items
    unknown = unknown_parameters(names, controller.parameter_names(), controller.service_prefix) if names else []
    for problem in unknown:
        print(f"allocator-ctl: {problem}", file=sys.stderr)
    if unknown:
        return 1
    if arguments.action == "get":
        for name, value in controller.get_parameters(arguments.items).items():
            print(f"{name}: {value}")
        return 0
    result = controller.set_parameters(values)
    print("applied" if result.successful else f"rejected: {result.reason}")
    return 0 if result.successful else 1


if __name__ == "__main__":
    sys.exit(main())
