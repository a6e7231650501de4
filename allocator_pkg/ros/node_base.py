"""What ``allocator_node`` and ``allocator_lifecycle_node`` share: the services, the parameter
checks and loading a configuration (with a robot description) into an
:class:`~allocator_pkg.ros.runtime.AllocationRuntime`; their process's main loop is
:mod:`allocator_pkg.ros.main_loop`.

:class:`AllocatorBase` is a mixin for rclpy's ``Node`` or ``LifecycleNode`` (the first of a
node's bases). Parameters are checked in the on-set callback against the whole configuration
and the running allocator (its actuators, and whether the method can serve the vehicle), and
applied in the post-set callback; while no runtime exists (a lifecycle node not configured) a
change is taken as it is and checked at the next configure, and the services answer
``success: false`` (:func:`when_configured`).
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable
from pathlib import Path

from rcl_interfaces.msg import SetParametersResult
from rclpy.parameter import Parameter
from std_msgs.msg import String
from std_srvs.srv import Trigger

from allocator_msgs.srv import GetCapability, HoldActuator, SetActuatorFault, SetBusTie, SetGroupFault

from ..allocation.allocator import Allocator
from ..configuration import urdf
from ..configuration.parameters import parse_parameters
from ..configuration.schema import ACTUATOR_PREFIX
from ..vehicle.config import ConfigError, Vehicle
from ..vehicle.node_settings import ROBOT_DESCRIPTION, NodeSettings
from . import qos, ros_parameters
from .conversions import array_to_wrench, wrench_to_array
from .ros_parameters import WholeSetParameters
from .runtime import AllocationRuntime

STOP_ACK_TIMEOUT = 1.0       # s the shutdown's zero-thrust command waits for acknowledgements
NOT_CONFIGURED = "not configured: the allocator has no configuration yet"


class NodeConfigError(ConfigError):
    """An invalid configuration of a node: names the node and the parameters it was given."""

    def __init__(self, node_name: str, found: Iterable[str], problems: list[tuple[str, str]]):
        self.node_name = node_name
        self.found = sorted(found)
        super().__init__(problems)

    def report(self) -> str:
        """The problems, then the parameters found (or why there may be none)."""
        lines = [f"{self.node_name}: invalid configuration:"]
        lines += [f"  {name}: {reason}" for name, reason in self.problems]
        if self.found:
            lines.append(f"parameters found for {self.node_name}: {compact(self.found)}")
        else:
            name = self.node_name.rsplit("/", 1)[-1]
            lines.append(f"no allocator parameters found for {self.node_name}: a params file section applies "
                         f"only to the nodes its key matches; key it '/**:' (any node) or '/**/{name}:'")
        return "\n".join(lines)


def compact(names: list[str]) -> str:
    """Parameter names with each actuator's keys in braces: ``actuators.a.{position, type}``."""
    parts: dict[str, list[str]] = {}
    for name in names:
        if name.startswith(ACTUATOR_PREFIX) and name.count(".") >= 2:
            head, _, key = name.rpartition(".")
            parts.setdefault(head + ".", []).append(key)
        else:
            parts.setdefault(name, [])
    return ", ".join(head + "{" + ", ".join(keys) + "}" if keys else head for head, keys in parts.items())


def when_configured(answer: Callable) -> Callable:
    """A service callback that answers ``success: false`` with :data:`NOT_CONFIGURED` while the
    node has no runtime, else ``answer(node, runtime, request, response)``."""

    @functools.wraps(answer)
    def callback(self: AllocatorBase, request, response):
        runtime = self._runtime
        if runtime is None:
            response.success, response.message = False, NOT_CONFIGURED
            return response
        return answer(self, runtime, request, response)

    return callback


class AllocatorBase(WholeSetParameters):
    """Services, parameter callbacks and configuration loading of an allocator node. Call
    :meth:`setup_allocator` once the node is initialised."""

    def setup_allocator(self) -> None:
        """The services, the parameter callbacks and, if the geometry comes from the
        ``robot_description`` topic, its subscription."""
        self.setup_whole_set_parameters()
        self._runtime: AllocationRuntime | None = None
        self._pending_change: tuple[Vehicle, NodeSettings, list[str]] | None = None
        self._description: str | None = None
        self.create_service(SetActuatorFault, "~/set_actuator_fault", self._on_set_fault)
        self.create_service(Trigger, "~/clear_faults", self._on_clear_faults)
        self.create_service(SetGroupFault, "~/set_group_fault", self._on_set_group_fault)
        self.create_service(SetBusTie, "~/set_bus_tie", self._on_set_bus_tie)
        self.create_service(GetCapability, "~/get_capability", self._on_get_capability)
        self.create_service(HoldActuator, "~/hold_actuator", self._on_hold_actuator)
        self.add_pre_set_parameters_callback(ros_parameters.typed)
        self.add_on_set_parameters_callback(self._check_parameters)
        self.add_post_set_parameters_callback(self._apply_parameters)
        given = ros_parameters.allocator_parameters(self)
        self._description_topic: str | None = None
        if given.get("geometry_source") == ROBOT_DESCRIPTION and not given.get("robot_description_file"):
            subscription = self.create_subscription(String, "robot_description", self._on_robot_description,
                                                    qos.robot_description(), qos_overriding_options=qos.overridable())
            self._description_topic = subscription.topic_name

    @property
    def runtime(self) -> AllocationRuntime | None:
        """The running configuration, or None (not configured yet)."""
        return self._runtime

    @property
    def allocator(self) -> Allocator:
        return self._runtime.allocator

    @property
    def period(self) -> float:
        """The allocation timer's period [s]."""
        return self._runtime.period

    @property
    def samples(self) -> int:
        return self._runtime.samples if self._runtime is not None else 0

    @property
    def wrenches_received(self) -> int:
        return self._runtime.wrenches_received if self._runtime is not None else 0

    @property
    def waiting_for_description(self) -> bool:
        """Whether the geometry comes from the robot_description topic and none has come yet."""
        return self._description_topic is not None and self._description is None

    def load(self) -> AllocationRuntime:
        """Check the parameters (and the robot description) as a whole, build the allocator (which
        refuses a method that cannot serve the vehicle), declare every key with its descriptor
        and build the runtime, not yet active. Raises NodeConfigError."""
        parameters = ros_parameters.allocator_parameters(self)
        try:
            geometry = self._geometry(parameters)
            vehicle, settings = parse_parameters({**parameters, **geometry})
            allocator = Allocator(vehicle)
        except ConfigError as error:
            raise NodeConfigError(self.get_fully_qualified_name(), parameters, error.problems) from error
        ros_parameters.declare(self, vehicle)
        ros_parameters.retype(self)
        runtime = AllocationRuntime(self, allocator, settings, geometry)
        logger = self.get_logger()
        for warning in runtime.allocator.warnings:
            logger.warn(warning)
        for note in runtime.allocator.notes:
            logger.info(note)
        left = runtime.allocator.uncontrolled
        source = f" (geometry from {self._description_topic or settings.robot_description_file})" if geometry else ""
        logger.info(f"allocating {', '.join(vehicle.dofs)} over {len(vehicle.actuators)} actuators{source} with "
                    f"'{runtime.allocator.method}' at {vehicle.rate_hz:g} Hz"
                    + (f"; {', '.join(left)} left to the vehicle" if left else ""))
        logger.info(runtime.topics())
        return runtime

    def _geometry(self, parameters: dict) -> dict[str, list[float]]:
        """The flat parameters the robot description supplies (none with geometry_source params)."""
        if parameters.get("geometry_source") != ROBOT_DESCRIPTION:
            return {}
        path = parameters.get("robot_description_file")
        if path:
            try:
                text = Path(path).read_text()
            except OSError as error:
                raise ConfigError([("robot_description_file", f"cannot read '{path}' ({error.strerror})")]) \
                    from error
        elif self._description is None:
            raise ConfigError([("robot_description", f"none received on {self._description_topic} yet")])
        else:
            text = self._description
        return urdf.geometry_parameters(text, parameters)

    def release(self) -> None:
        """Close the runtime (topics, timers, the allocator and its solver)."""
        if self._runtime is not None:
            self._runtime.close()
            self._runtime = None

    def _on_robot_description(self, message: String) -> None:
        self._description = message.data
        self.on_robot_description()

    def on_robot_description(self) -> None:
        """A robot description arrived (stored for :meth:`load`)."""

    # -- services -----------------------------------------------------------------------

    @when_configured
    def _on_set_fault(self, runtime: AllocationRuntime, request: SetActuatorFault.Request,
                      response: SetActuatorFault.Response):
        response.success, response.message = runtime.set_fault(request.fault)
        if response.success:
            self.get_logger().info(response.message)
        return response

    @when_configured
    def _on_set_group_fault(self, runtime: AllocationRuntime, request: SetGroupFault.Request,
                            response: SetGroupFault.Response):
        response.success, response.message = runtime.set_group_fault(request.group)
        if response.success:
            self.get_logger().warn(response.message)
        return response

    @when_configured
    def _on_set_bus_tie(self, runtime: AllocationRuntime, request: SetBusTie.Request, response: SetBusTie.Response):
        response.success, response.message = runtime.set_bus_tie(request.name, request.closed)
        if response.success:
            self.get_logger().warn(response.message)
        return response

    @when_configured
    def _on_clear_faults(self, runtime: AllocationRuntime, request: Trigger.Request, response: Trigger.Response):
        response.success, response.message = True, runtime.clear_faults()
        self.get_logger().info(response.message)
        return response

    @when_configured
    def _on_get_capability(self, runtime: AllocationRuntime, request: GetCapability.Request,
                           response: GetCapability.Response):
        response.success, response.message, response.scale, achieved = \
            runtime.capability(wrench_to_array(request.direction))
        response.achieved = array_to_wrench(achieved)
        return response

    @when_configured
    def _on_hold_actuator(self, runtime: AllocationRuntime, request: HoldActuator.Request,
                          response: HoldActuator.Response):
        response.success, response.message = runtime.hold(request.actuator, request.thrust, request.duration)
        return response

    # -- parameters ---------------------------------------------------------------------

    def _check_parameters(self, parameters: list[Parameter]) -> SetParametersResult:
        """Check a change against the whole schema and the running allocator (the same actuators,
        a method that can serve the vehicle); keep what it builds for :meth:`_apply_parameters`.
        Nothing changes here: a change refused is refused whole."""
        self._pending_change = None
        changes = {p.name: ros_parameters.plain(p.value) for p in parameters
                   if ros_parameters.is_allocator_parameter(p.name)}
        runtime = self._runtime
        if not changes or runtime is None:
            return SetParametersResult(successful=True)
        candidate = ros_parameters.allocator_parameters(self)
        candidate.update(changes)
        try:
            supplied = sorted(set(changes) & set(runtime.geometry))
            if supplied:
                raise ConfigError([(name, "comes from the robot description (geometry_source: "
                                          "robot_description)") for name in supplied])
            vehicle, settings = parse_parameters({**candidate, **runtime.geometry})
            runtime.allocator.check_reconfigure(vehicle)
        except ValueError as error:
            self.get_logger().warn(f"rejected parameter change: {error}")
            return SetParametersResult(successful=False, reason=str(error))
        self._pending_change = (vehicle, settings, sorted(changes))
        return SetParametersResult(successful=True)

    def _apply_parameters(self, parameters: list[Parameter]) -> None:
        """Apply what :meth:`_check_parameters` accepted, between two samples."""
        if self._pending_change is None or self._runtime is None:
            return
        vehicle, settings, names = self._pending_change
        self._pending_change = None
        self._runtime.apply(vehicle, settings)
        self.get_logger().info(f"applied {', '.join(names)}")

    # -- shutdown -------------------------------------------------------------------------

    @property
    def finished(self) -> bool:
        """Whether the process may end (a lifecycle node's shutdown transition)."""
        return False

    def stop(self) -> None:
        """SIGINT/SIGTERM: if commanding, one zero-thrust command, acknowledged if possible."""
        if self._runtime is None or not self._runtime.active:
            return
        if self._runtime.publish_stop(STOP_ACK_TIMEOUT):
            self.get_logger().info("stopped: published zero thrust")
        else:
            self.get_logger().warn(f"stopped: published zero thrust, not acknowledged by every "
                                   f"subscriber within {STOP_ACK_TIMEOUT:g} s")

