"""Schema keys to the fields of the configuration types, by name.

A vehicle-wide or node key fills the field named as the key with '.' read as '_'
(``dynamic.gain``: ``Vehicle.dynamic_gain``; ``ros2_control.thrust_topic``:
``NodeSettings.ros2_control_thrust_topic``), except that a key under the name of a struct of
:data:`NESTED` fills the field of the rest in that struct (``solver.eps_abs``:
``SolverSettings.eps_abs``). A per-actuator key fills the field of its name in whichever of
:data:`ACTUATOR_STRUCTS` has one, or the field :data:`RENAMED` gives it (``azimuth_rate_max``:
``RotationConfig.rate_max``). A power source's key (``power.<source>.<key>``) fills the field of
its name in :class:`~allocator_pkg.vehicle.config.PowerSource`, a redundancy group's
(``redundancy_groups.<group>.<key>``) in :class:`~allocator_pkg.vehicle.config.RedundancyGroup`,
a bus tie's (``power.bus_tie.<tie>.<key>``) in :class:`~allocator_pkg.vehicle.config.BusTie`.
A key whose name fills no field (``actuators.names``, ``redundancy_groups.names``, ``link``) is
read by hand.

The builder gives by hand the fields whose values it derives (an order, a default that depends
on other keys, a nested struct); :func:`filled` takes every other field from its key.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, fields
from typing import Any, TypeVar

from ..vehicle.config import (
    ActuatorConfig,
    BiasSettings,
    BusTie,
    CommandMapConfig,
    PowerSource,
    RedundancyGroup,
    RotationConfig,
    SolverSettings,
    SurfaceConfig,
    Vehicle,
    Weights,
)
from ..vehicle.node_settings import NodeSettings

NESTED: dict[str, type] = {"weights": Weights, "solver": SolverSettings, "bias": BiasSettings}
"""Fields of a Vehicle that are structs of their own, filled by the keys ``<field>.<name>``."""

ACTUATOR_STRUCTS: tuple[type, ...] = (ActuatorConfig, CommandMapConfig, RotationConfig, SurfaceConfig)
"""The structs of one actuator; no field name is in two of them."""

RENAMED = {"command_map": "kind", "command_deadband": "deadband", "azimuth_rate_max": "rate_max",
           "azimuth_initial": "initial"}
"""Per-actuator keys whose field has another name: the key says what it belongs to, the field
lives in the struct of that (``CommandMapConfig.kind``, ``RotationConfig.initial``)."""

_FIELD_NAMES = {struct: {field.name for field in fields(struct)}
                for struct in (Vehicle, NodeSettings, PowerSource, RedundancyGroup, BusTie, *NESTED.values(),
                                 *ACTUATOR_STRUCTS)}

Struct = TypeVar("Struct")


@dataclass(frozen=True)
class Field:
    """A field of a configuration type."""

    struct: type
    name: str


def _field(struct: type, name: str) -> Field | None:
    return Field(struct, name) if name in _FIELD_NAMES[struct] else None


def vehicle_field(key: str) -> Field | None:
    """The field a vehicle-wide key fills, or None."""
    head, dot, rest = key.partition(".")
    if dot and head in NESTED:
        return _field(NESTED[head], rest.replace(".", "_"))
    return _field(Vehicle, key.replace(".", "_"))


def node_field(key: str) -> Field | None:
    """The field of NodeSettings a node key fills, or None."""
    return _field(NodeSettings, key.replace(".", "_"))


def actuator_field(key: str) -> Field | None:
    """The field a per-actuator key (its name under ``actuators.<name>.``) fills, or None."""
    name = RENAMED.get(key, key)
    return next((Field(struct, name) for struct in ACTUATOR_STRUCTS if name in _FIELD_NAMES[struct]), None)


def source_field(key: str) -> Field | None:
    """The field of PowerSource a power source's key (its name under ``power.<source>.``) fills."""
    return _field(PowerSource, key)


def group_field(key: str) -> Field | None:
    """The field of RedundancyGroup a group's key (under ``redundancy_groups.<group>.``) fills."""
    return _field(RedundancyGroup, key)


def tie_field(key: str) -> Field | None:
    """The field of BusTie a bus tie's key (under ``power.bus_tie.<tie>.``) fills."""
    return _field(BusTie, key)


def filled(struct: type[Struct], values: Mapping[str, Any], field_of: Callable[[str], Field | None],
           **derived: Any) -> Struct:
    """A ``struct`` of the keys' ``values``: each field that ``derived`` does not give is the
    value of the key whose field (``field_of``) it is."""
    plain = {}
    for key, value in values.items():
        field = field_of(key)
        if field is not None and field.struct is struct and field.name not in derived:
            plain[field.name] = value
    return struct(**plain, **derived)
