"""The parameters an allocator node holds, without ROS: the keys it declares for a vehicle,
their values once declared, and a value retyped as the node keeps it. The node
(:mod:`allocator_pkg.ros.ros_parameters`) declares these keys; the in-process closed loop
(:mod:`allocator_pkg.simulation.in_process`) checks a parameter change against the same
values the node would."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..vehicle.config import Vehicle
from . import schema
from .key import FLOAT, FLOAT_LIST, Key


def declared_keys(vehicle: Vehicle) -> list[tuple[str, Key]]:
    """(parameter name, key) of every parameter a node declares for ``vehicle``: the
    vehicle-wide and node keys, then those of its actuators, power sources and groups."""
    return [(key.name, key) for key in schema.VEHICLE_KEYS + schema.NODE_KEYS] + schema.instance_keys(vehicle)


def typed_value(name: str, value: Any) -> Any:
    """``value`` as the node keeps parameter ``name``: an integer (or a list of integers) for a
    float key becomes a float (``rate_hz:=25``), a tuple a list."""
    key = schema.key_for(name)
    if isinstance(value, tuple):
        value = list(value)
    if key is None:
        return value
    if key.kind == FLOAT and type(value) is int:
        return float(value)
    if key.kind == FLOAT_LIST and isinstance(value, list) and value and all(type(v) is int for v in value):
        return [float(v) for v in value]
    return value


def declared(given: Mapping[str, Any], vehicle: Vehicle) -> dict[str, Any]:
    """The node's parameters once it has declared every key of ``vehicle``: those ``given``,
    and the default of each other key that has one (a key whose default depends on other
    keys stays unset)."""
    values = {name: typed_value(name, value) for name, value in given.items()}
    for name, key in declared_keys(vehicle):
        if name not in values and key.default is not None:
            values[name] = typed_value(name, key.default)
    return values
