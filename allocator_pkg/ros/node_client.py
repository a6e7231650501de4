"""A client of one running allocator, as allocator-ctl, allocator-sim and the tests drive it:
wrenches published, its services and parameters called, each call bounded in time."""

from __future__ import annotations

import time

from geometry_msgs.msg import Wrench
from rcl_interfaces.srv import GetParameters, ListParameters, SetParametersAtomically
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter, parameter_value_to_python
from std_srvs.srv import Trigger

from allocator_msgs.msg import ActuatorFault
from allocator_msgs.srv import GetCapability, SetActuatorFault, SetBusTie, SetGroupFault

from ..allocation.sample_rules import fault_request
from ..effectiveness.faults import FaultMode
from ..vehicle.node_settings import NODE_NAME
from .conversions import array_to_wrench

RESEND_AFTER = 1.0
"""[s] How long a request waits for its answer before it is sent again (:meth:`Controller.call`)."""
FAULT_MODES = {"nominal": ActuatorFault.NOMINAL, "degraded": ActuatorFault.DEGRADED,
               "failed": ActuatorFault.FAILED, "stuck": ActuatorFault.STUCK}


NOT_REACHED = ("is the node running, with the same ROS_DOMAIN_ID and ROS_AUTOMATIC_DISCOVERY_RANGE, and "
               "--namespace and --node its namespace and name?")
"""What to check when no allocator answers."""


class ServiceTimeout(RuntimeError):
    pass


class Controller:
    """A client node for one allocator: publishes wrenches, calls its services, listens.
    :meth:`close` shuts down the executor it made for a node that had none."""

    def __init__(self, node: Node, target: str = NODE_NAME, namespace: str = ""):
        self.node = node
        self._executor: SingleThreadedExecutor | None = None
        self.namespace = f"/{namespace.strip('/')}" if namespace.strip("/") else ""
        self.service_prefix = node.resolve_service_name(f"{self.namespace}/{target}" if self.namespace else target)
        """The node's fully qualified name: ``target`` in ``namespace``, else in the client node's namespace."""
        self.wrench = node.create_publisher(Wrench, self.topic("wrench_command"), 10)

    def topic(self, name: str) -> str:
        """The allocator's topic ``name`` in its namespace."""
        return f"{self.namespace}/{name}" if self.namespace else name

    def call(self, kind, name: str, request, timeout: float = 5.0):
        """The node's answer to ``request`` on its service ``name``, within ``timeout`` [s].

        Every service called here is idempotent, so a request without an answer after
        :data:`RESEND_AFTER` is sent again, and the first answer to any of them is taken: a
        server that answers before it has discovered the client's response reader drops its
        answer (Fast DDS: "failed to send response"), and a new request gets through."""
        client = self.node.create_client(kind, f"{self.service_prefix}/{name}")
        try:
            if not client.wait_for_service(timeout_sec=timeout):
                raise ServiceTimeout(f"service {self.service_prefix}/{name} not available ({NOT_REACHED})")
            executor = self.node.executor
            if executor is None:
                executor = self._executor = SingleThreadedExecutor(context=self.node.context)
                executor.add_node(self.node)
            futures = []
            deadline = time.monotonic() + timeout
            while (left := deadline - time.monotonic()) > 0.0:
                futures.append(client.call_async(request))
                wait_until = time.monotonic() + min(RESEND_AFTER, left)
                while time.monotonic() < wait_until and not any(future.done() for future in futures):
                    executor.spin_once(timeout_sec=0.05)
                answered = next((future for future in futures if future.done()), None)
                if answered is not None:
                    return answered.result()
            raise ServiceTimeout(f"service {self.service_prefix}/{name} did not answer within {timeout:g} s")
        finally:
            self.node.destroy_client(client)

    def close(self) -> None:
        """Shut down the executor :meth:`call` made, before the node and its context end (left to
        the garbage collector, it would outlive them and end with an InvalidHandle error)."""
        if self._executor is not None:
            self._executor.shutdown()
            self._executor = None

    def nodes_named(self) -> int:
        """How many nodes of the graph have the allocator's fully qualified name (more than one:
        any of them may answer): by their names, or by the servers of its parameter service,
        whichever the graph knows more of."""
        named = sum(f"{namespace.rstrip('/')}/{name}" == self.service_prefix
                    for name, namespace in self.node.get_node_names_and_namespaces())
        return max(named, self.node.count_services(f"{self.service_prefix}/get_parameters"))

    def set_fault(self, actuator: str, mode: str, value: float = 0.0) -> SetActuatorFault.Response:
        efficiency, angle = fault_request(FaultMode(FAULT_MODES[mode]), value)
        fault = ActuatorFault(actuator=actuator, mode=FAULT_MODES[mode], efficiency=efficiency, azimuth=angle)
        return self.call(SetActuatorFault, "set_actuator_fault", SetActuatorFault.Request(fault=fault))

    def set_group_fault(self, group: str) -> SetGroupFault.Response:
        return self.call(SetGroupFault, "set_group_fault", SetGroupFault.Request(group=group))

    def set_bus_tie(self, name: str, closed: bool) -> SetBusTie.Response:
        return self.call(SetBusTie, "set_bus_tie", SetBusTie.Request(name=name, closed=closed))

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
