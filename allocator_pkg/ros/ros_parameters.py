"""The configuration schema as ROS 2 parameters: descriptors, declaration, current values.

Parameters are declared with dynamic typing and checked by the schema itself, so that a
params file may write ``thrust_max: 50`` for a float and the error messages (from a file or a
runtime ``set_parameters``) are the ones the library gives; only a number outside a key's
range is refused first by rclpy, with its own message naming the parameter and the range.
"""

from __future__ import annotations

import array
import sys
import threading
from typing import Any

from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor, SetParametersResult
from rcl_interfaces.srv import SetParameters
from rclpy.exceptions import ParameterNotDeclaredException
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import qos_profile_parameters

from ..configuration import schema
from ..configuration.declared import declared_keys
from ..configuration.schema import FLOAT, FLOAT_LIST, INT, Key
from ..vehicle.config import Vehicle

INT64_MAX = 2**63 - 1

ROS_BUILT_IN = ("use_sim_time", "start_type_description_service")
"""Parameters rclpy declares on every node; they are not the allocator's."""


def is_allocator_parameter(name: str) -> bool:
    return not (name in ROS_BUILT_IN or name.startswith("qos_overrides."))


def descriptor(key: Key) -> ParameterDescriptor:
    """A ParameterDescriptor with the key's documentation, range and read-only flag. A bound
    on one side only gets the largest value of the type on the other; an exclusive bound is
    checked by the schema (ROS ranges include their ends) and named in the constraints text."""
    text = key.description
    if key.unit:
        text += f" [{key.unit}]"
    text += f" Default: {key.documented_default()}."
    result = ParameterDescriptor(description=text, read_only=key.read_only, dynamic_typing=True,
                                 additional_constraints=key.documented_range())
    if key.minimum is None and key.maximum is None:
        return result
    if key.kind == FLOAT:
        low = -sys.float_info.max if key.minimum is None else float(key.minimum)
        high = sys.float_info.max if key.maximum is None else float(key.maximum)
        result.floating_point_range = [FloatingPointRange(from_value=low, to_value=high, step=0.0)]
    elif key.kind == INT:
        low = -INT64_MAX if key.minimum is None else int(key.minimum)
        high = INT64_MAX if key.maximum is None else int(key.maximum)
        result.integer_range = [IntegerRange(from_value=low, to_value=high, step=1)]
    return result


def plain(value: Any) -> Any:
    """A parameter value as the schema takes it (arrays as lists)."""
    return list(value) if isinstance(value, (array.array, tuple)) else value


def typed(parameters: list[Parameter]) -> list[Parameter]:
    """The parameters with the schema's types: an integer (or integer list) set for a float key
    (``rate_hz:=25``) becomes a float, so that the parameter keeps its type. For rclpy's
    pre-set callback, and for values read from the command line or a params file."""
    result = []
    for parameter in parameters:
        key = schema.key_for(parameter.name)
        if key is not None and key.kind == FLOAT and parameter.type_ == Parameter.Type.INTEGER:
            parameter = Parameter(parameter.name, Parameter.Type.DOUBLE, float(parameter.value))
        elif key is not None and key.kind == FLOAT_LIST and parameter.type_ == Parameter.Type.INTEGER_ARRAY:
            parameter = Parameter(parameter.name, Parameter.Type.DOUBLE_ARRAY, [float(v) for v in parameter.value])
        result.append(parameter)
    return result


def retype(node: Node) -> None:
    """Give the node's parameters the schema's types (:func:`typed`)."""
    current = [parameter for parameter in node.get_parameters_by_prefix("").values()
               if is_allocator_parameter(parameter.name)]
    changed = [new for old, new in zip(current, typed(current)) if new.type_ != old.type_]
    if changed:
        node.set_parameters(changed)


def allocator_parameters(node: Node) -> dict[str, Any]:
    """The node's allocator parameters by name (unset ones left out)."""
    return {name: plain(parameter.value) for name, parameter in node.get_parameters_by_prefix("").items()
            if parameter.value is not None and is_allocator_parameter(name)}


def declare(node: Node, vehicle: Vehicle) -> None:
    """Declare every schema key of this vehicle, its actuators, power sources and redundancy
    groups (those the params file set already are), each with its descriptor, so that
    ``ros2 param list/describe`` shows all of them."""
    for name, key in declared_keys(vehicle):
        if node.has_parameter(name) and node.describe_parameter(name).read_only:
            continue                                 # described by an earlier configure (lifecycle)
        if node.has_parameter(name):
            node.set_descriptor(name, descriptor(key))
        else:
            node.declare_parameter(name, key.default, descriptor(key))


class WholeSetParameters:
    """Mixin for a Node (listed before it): several values set in one call are checked and
    applied as a whole, and changes are serialised across threads.

    rclpy sets the values of a ``set_parameters`` call (and of a ``~/set_parameters`` request)
    one by one, so values valid only together (``dofs`` with ``weights.slack``) could never be
    set that way. Here :meth:`set_parameters` is ``set_parameters_atomically`` with one result
    per value, all alike, and the ``~/set_parameters`` service answers with it, through rclpy's
    public API only (rclpy's service is found by its type and replaced). Call
    :meth:`setup_whole_set_parameters` once the Node is initialised.
    """

    def setup_whole_set_parameters(self) -> None:
        """Create the lock and answer ``~/set_parameters`` with :meth:`set_parameters` in
        place of rclpy's service."""
        self._parameters_lock = threading.RLock()
        for service in list(self.services):
            if service.srv_type is SetParameters:
                self.destroy_service(service)
        self.create_service(SetParameters, "~/set_parameters", self._on_set_parameters_request,
                            qos_profile=qos_profile_parameters)

    def set_parameters(self, parameter_list: list[Parameter]) -> list[SetParametersResult]:
        result = self.set_parameters_atomically(parameter_list)
        return [SetParametersResult(successful=result.successful, reason=result.reason) for _ in parameter_list]

    def set_parameters_atomically(self, parameter_list: list[Parameter]) -> SetParametersResult:
        """rclpy's ``set_parameters_atomically`` (also behind the parameter services), serialised."""
        with self._parameters_lock:
            return super().set_parameters_atomically(parameter_list)

    def _on_set_parameters_request(self, request: SetParameters.Request, response: SetParameters.Response):
        parameters = [Parameter.from_parameter_msg(message) for message in request.parameters]
        try:
            response.results = self.set_parameters(parameters)
        except ParameterNotDeclaredException as error:
            response.results = [SetParametersResult(successful=False, reason=str(error)) for _ in parameters]
        return response

