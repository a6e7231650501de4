"""allocator-ctl: drive and watch a running thrust_allocator without the ros2 CLI.

    allocator-ctl wrench 100 0 0 0 0 20 --rate 20 --duration 5
    allocator-ctl fault main_port failed | degraded 0.5 | stuck 0.3 | nominal
    allocator-ctl clear
    allocator-ctl echo [--csv FILE] [--mcap FILE]             (--mcap: wrench, commands, status for ros2 bag, Foxglove)
    allocator-ctl capability 1 0 0 0 0 0                      (~/get_capability along a wrench)
    allocator-ctl step-test [--share 0.1] [--hold 3] [--rest 2] [--actuators]   (direction check on the bench)
    allocator-ctl params get [NAME ...]
    allocator-ctl params set NAME=VALUE [NAME=VALUE ...]      (applied atomically)

``--node`` names the allocator node (default ``thrust_allocator``) and ``--namespace`` its
namespace; the same options work with ``ros2 run allocator_pkg allocator-ctl``.
"""

from __future__ import annotations

import argparse
import csv
import difflib
import math
import sys
import time
from typing import TextIO

import rclpy
from geometry_msgs.msg import Wrench, WrenchStamped
from rcl_interfaces.srv import GetParameters, ListParameters, SetParametersAtomically
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter, parameter_value_to_python
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_srvs.srv import Trigger

from allocator_msgs.msg import ActuatorFault, AllocationStatus, ThrusterCommands
from allocator_msgs.srv import GetCapability, SetActuatorFault

from ..configuration import params_file
from ..ros.conversions import OUTCOME_NAMES, array_to_wrench, wrench_to_array
from ..vehicle.node_settings import NODE_NAME
from .direction_check import DirectionCheck
from .recording import Recording

FAULT_MODES = {"nominal": ActuatorFault.NOMINAL, "degraded": ActuatorFault.DEGRADED,
               "failed": ActuatorFault.FAILED, "stuck": ActuatorFault.STUCK}


class ServiceTimeout(RuntimeError):
    pass


class Controller:
    """A client node for one allocator: publishes wrenches, calls its services, listens."""

    def __init__(self, node: Node, target: str = NODE_NAME, namespace: str = ""):
        self.node = node
        self.namespace = f"/{namespace.strip('/')}" if namespace.strip("/") else ""
        self.service_prefix = f"{self.namespace}/{target}"
        self.wrench = node.create_publisher(Wrench, self.topic("wrench_command"), 10)

    def topic(self, name: str) -> str:
        """The allocator's topic ``name`` in its namespace."""
        return f"{self.namespace}/{name}" if self.namespace else name

    def call(self, kind, name: str, request, timeout: float = 5.0):
        client = self.node.create_client(kind, f"{self.service_prefix}/{name}")
        try:
            if not client.wait_for_service(timeout_sec=timeout):
                raise ServiceTimeout(f"service {self.service_prefix}/{name} not available (is the node running, "
                                     "with the same ROS_DOMAIN_ID and ROS_AUTOMATIC_DISCOVERY_RANGE?)")
            future = client.call_async(request)
            executor = self.node.executor
            if executor is None:
                executor = SingleThreadedExecutor(context=self.node.context)
                executor.add_node(self.node)
            executor.spin_until_future_complete(future, timeout_sec=timeout)
            if not future.done():
                raise ServiceTimeout(f"service {self.service_prefix}/{name} did not answer within {timeout:g} s")
            return future.result()
        finally:
            self.node.destroy_client(client)

    def set_fault(self, actuator: str, mode: str, value: float = 0.0) -> SetActuatorFault.Response:
        fault = ActuatorFault(actuator=actuator, mode=FAULT_MODES[mode])
        if mode == "degraded":
            fault.efficiency = value
        elif mode == "stuck":
            fault.azimuth = value
        return self.call(SetActuatorFault, "set_actuator_fault", SetActuatorFault.Request(fault=fault))

    def clear_faults(self) -> Trigger.Response:
        return self.call(Trigger, "clear_faults", Trigger.Request())

    def capability(self, direction: list[float]) -> GetCapability.Response:
        return self.call(GetCapability, "get_capability", GetCapability.Request(direction=array_to_wrench(direction)))

    def parameter_names(self) -> list[str]:
        """Every parameter the node has declared, sorted."""
        return sorted(self.call(ListParameters, "list_parameters", ListParameters.Request()).result.names)

    def get_parameters(self, names: list[str]) -> dict[str, object]:
        names = names or self.parameter_names()
        response = self.call(GetParameters, "get_parameters", GetParameters.Request(names=names))
        return {name: parameter_value_to_python(value) for name, value in zip(names, response.values)}

    def set_parameters(self, values: dict[str, object]):
        request = SetParametersAtomically.Request(
            parameters=[Parameter(name, value=value).to_parameter_msg() for name, value in values.items()])
        return self.call(SetParametersAtomically, "set_parameters_atomically", request).result


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


def format_sample(commands: ThrusterCommands, status: AllocationStatus | None) -> str:
    """One compact line: every actuator's thrust [N], command (set-point) and azimuth [deg] if it
    has one, then the solver figures; when saturated the unallocated wrench, the actuators at a
    thrust (!) or rate (~) limit, and the supply voltage in use."""
    parts = []
    for name, thrust, command, azimuth in zip(commands.name, commands.thrust, commands.command, commands.azimuth):
        angle = f" @{math.degrees(azimuth):6.1f}" if azimuth != 0.0 else " " * 8
        parts.append(f"{name} {thrust:9.1f} N cmd {command:8.2f}{angle}")
    line = " | ".join(parts)
    if status is not None:
        line += (f" || sat {'YES' if status.saturated else 'no '} {status.solve_time * 1e6:7.0f} us "
                 f"{status.iterations:5d} it {status.solver_status}")
        if status.saturated:
            line += " | unallocated " + " ".join(f"{v:.1f}" for v in wrench_to_array(status.unallocated))
        flagged = [f"{name}{'!' if thrust else ''}{'~' if rate else ''}" for name, thrust, rate
                   in zip(commands.name, status.at_thrust_limit, status.at_rate_limit) if thrust or rate]
        if flagged:
            line += f" | at limit (! thrust, ~ rate): {' '.join(flagged)}"
        if status.voltage > 0.0:                     # NaN: no voltage tables
            line += f" | {status.voltage:.2f} V"
    return line


def format_capability(direction: list[float], response: GetCapability.Response) -> str:
    """The answer of ~/get_capability in words."""
    if not response.success:
        return f"no capability: {response.message}"
    achieved = " ".join(f"{v:.2f}" for v in wrench_to_array(response.achieved))
    return (f"scale {response.scale:.4g} along [{' '.join(f'{v:g}' for v in direction)}]; achieved there "
            f"[{achieved}] ({response.message})")


WRENCH_TYPES = {"geometry_msgs/msg/Wrench": Wrench, "geometry_msgs/msg/WrenchStamped": WrenchStamped}


def wrench_type_on(node: Node, topic: str, wait: float = 2.0) -> type:
    """The wrench type on ``topic`` in the ROS graph (the allocator's ``wrench_type``), waiting up
    to ``wait`` seconds for it to be discovered; Wrench if none is seen."""
    end = time.monotonic() + wait
    while True:
        for name, types in node.get_topic_names_and_types():
            found = [WRENCH_TYPES[kind] for kind in types if kind in WRENCH_TYPES]
            if name == topic and found:
                return found[0]
        if time.monotonic() >= end:
            return Wrench
        time.sleep(0.05)


class Echo:
    """Prints a compact live table of commands and status; optionally writes every sample to CSV,
    and records the wrenches (Wrench or WrenchStamped), commands and status to an MCAP file."""

    def __init__(self, controller: Controller, out: TextIO, csv_file: TextIO | None = None, rate: float = 2.0,
                 recording: Recording | None = None):
        self.out = out
        self.recording = recording
        self.period = 1.0 / rate if rate > 0 else 0.0
        self.last_print = 0.0
        self.status: AllocationStatus | None = None
        self.writer = csv.writer(csv_file) if csv_file else None
        self.header_done = False
        node = self.node = controller.node
        self._status = node.create_subscription(AllocationStatus, controller.topic("allocation_status"),
                                                self._on_status, 10)
        self._commands = node.create_subscription(ThrusterCommands, controller.topic("thruster_commands"),
                                                  self._on_commands, 10)
        if recording is not None:
            topic = node.resolve_topic_name(controller.topic("wrench_command"))
            self._wrench = node.create_subscription(wrench_type_on(node, topic), topic, self._on_wrench,
                                                    QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))

    def _on_wrench(self, message: Wrench | WrenchStamped) -> None:
        self._record(self._wrench.topic_name, message)

    def _record(self, topic: str, message) -> None:
        self.recording.write(topic, message, self.node.get_clock().now().nanoseconds)

    def _on_status(self, message: AllocationStatus) -> None:
        self.status = message
        if self.recording is not None:
            self._record(self._status.topic_name, message)

    def _on_commands(self, message: ThrusterCommands) -> None:
        if self.recording is not None:
            self._record(self._commands.topic_name, message)
        if self.writer is not None:
            self._write_csv(message)
        now = time.monotonic()
        if now - self.last_print >= self.period:
            self.last_print = now
            print(format_sample(message, self.status), file=self.out, flush=True)

    def _write_csv(self, message: ThrusterCommands) -> None:
        if not self.header_done:
            header = ["stamp"]
            for name in message.name:
                header += [f"{name}.thrust", f"{name}.command", f"{name}.azimuth", f"{name}.mode"]
            header += [f"{name}.at_{kind}_limit" for kind in ("thrust", "rate") for name in message.name]
            header += ["saturated", "solve_time", "iterations", "solver_status", "outcome", "voltage"]
            header += [f"unallocated.{axis}" for axis in ("x", "y", "z", "k", "m", "n")]
            self.writer.writerow(header)
            self.header_done = True
        row = [message.header.stamp.sec + message.header.stamp.nanosec * 1e-9]
        for values in zip(message.thrust, message.command, message.azimuth, message.mode):
            row += list(values)
        status = self.status
        if status is None:
            row += [""] * (2 * len(message.name) + 12)
        else:
            row += list(status.at_thrust_limit) + list(status.at_rate_limit)
            row += [status.saturated, status.solve_time, status.iterations, status.solver_status,
                    OUTCOME_NAMES.get(status.outcome, str(status.outcome)), status.voltage]
            row += wrench_to_array(status.unallocated).tolist()
        self.writer.writerow(row)


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
    commands.add_parser("clear", help="all actuators back to NOMINAL")
    capability = commands.add_parser("capability", help="largest scale along a wrench the actuators can give now")
    for name in ("FX", "FY", "FZ", "MX", "MY", "MZ"):
        capability.add_argument(name, type=float)
    echo = commands.add_parser("echo", help="print a live table of thrust, command, azimuth and status")
    echo.add_argument("--csv", type=argparse.FileType("w"), help="also write every sample to this CSV file")
    echo.add_argument("--mcap", metavar="FILE", help="also record wrench_command, thruster_commands and "
                      "allocation_status to this MCAP file (ros2 bag, Foxglove)")
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
    rclpy.init(args=sys.argv if argv is None else None)
    node = rclpy.create_node("allocator_ctl")
    controller = Controller(node, arguments.node, arguments.namespace)
    try:
        return _run(arguments, controller)
    except ServiceTimeout as error:
        print(f"allocator-ctl: {error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 0
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


def _spin_for(node: Node, duration: float | None) -> None:
    end = None if duration is None else time.monotonic() + duration
    while rclpy.ok() and (end is None or time.monotonic() < end):
        rclpy.spin_once(node, timeout_sec=0.05)


def _run(arguments: argparse.Namespace, controller: Controller) -> int:
    node = controller.node
    if arguments.command == "wrench":
        message = array_to_wrench([arguments.FX, arguments.FY, arguments.FZ, arguments.MX, arguments.MY, arguments.MZ])
        node.create_timer(1.0 / arguments.rate, lambda: controller.wrench.publish(message))
        controller.wrench.publish(message)
        _spin_for(node, arguments.duration)
        return 0
    if arguments.command == "fault":
        response = controller.set_fault(arguments.actuator, arguments.mode, arguments.value or 0.0)
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
        recording = Recording(arguments.mcap) if arguments.mcap else None
        try:
            Echo(controller, sys.stdout, arguments.csv, arguments.rate, recording)
            _spin_for(node, arguments.duration)
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
