"""Per-actuator parameters (``actuators.<name>.<key>``) to an
:class:`~allocator_pkg.vehicle.config.ActuatorConfig`: the keys of its type, its direction,
thrust range, command map (1.3), (1.4) or measured table, rotation limits and sectors, or
hydrofoil data (1.48), (1.49), each checked, every problem recorded on the
:class:`~allocator_pkg.configuration.values.Reader`.
"""

from __future__ import annotations

import math
from itertools import pairwise
from typing import Any

from ..effectiveness.actuators import command_map
from ..effectiveness.sectors import allowed_arcs, in_feasible_sector, in_forbidden_sector
from ..vehicle.angles import ANGLE_TOLERANCE, TWO_PI
from ..vehicle.config import (
    AZIMUTH,
    AZIMUTH_VERTICAL,
    FIXED,
    SURFACE_TYPES,
    ActuatorConfig,
    CommandMapConfig,
    RotationConfig,
    SurfaceConfig,
)
from . import schema
from .fields import actuator_field, filled
from .schema import ACTUATOR_KEY_BY_NAME
from .values import MISSING, Reader

MIN_ALLOWED_ARC = math.radians(1.0)
"""[rad] The least total angle a rotatable thruster's feasible sector, less its forbidden
sectors, must leave to thrust in. One degree is about the pointing accuracy of an azimuth
drive: a thruster confined to a narrower arc is a fixed thruster whose direction cannot be
held, and sectors that leave so little are a slip (a start and end swapped, degrees for
radians) far more often than a design."""


def parse_actuator(reader: Reader, name: str) -> ActuatorConfig | None:
    """One actuator: the keys of its type, its position and direction here, a control
    surface's hydrofoil data too, a thruster's the rest by :func:`_thruster`."""
    def param(key: str) -> str:
        return schema.actuator_parameter(name, key)

    actuator_type = reader.value(ACTUATOR_KEY_BY_NAME["type"], param("type"))
    if actuator_type is MISSING:
        return None
    applicable = schema.keys_for_type(actuator_type)
    applicable_names = {key.name for key in applicable}
    for key in schema.ACTUATOR_KEYS:
        if key.name not in applicable_names and param(key.name) in reader.parameters:
            reader.fail(param(key.name), f"does not apply to a {actuator_type} actuator; its keys are "
                                         f"{', '.join(sorted(applicable_names))}")
    v = {key.name: reader.value(key, param(key.name), actuator_type) for key in applicable}
    if any(value is MISSING for value in v.values()):
        return None
    feeds = tuple(v.get("feeds") or ())
    shares = v.get("feed_shares")
    if shares is None:
        shares = (1.0,) if len(feeds) == 1 else ()             # one feed: all of the power from it
    derived = dict(name=name, position=tuple(v["position"]),
                   direction=_direction(reader, actuator_type, v.get("direction"), param("direction")),
                   feeds=feeds, feed_shares=tuple(shares))
    if actuator_type in SURFACE_TYPES:
        return filled(ActuatorConfig, v, actuator_field, **derived, surface=filled(SurfaceConfig, v, actuator_field))
    return _thruster(reader, name, v, derived)


def _thruster(reader: Reader, name: str, v: dict[str, Any], derived: dict[str, Any]) -> ActuatorConfig | None:
    """A fixed or rotatable thruster: thrust range, command map and, if it turns, rotation."""
    rotatable = v["type"] in (AZIMUTH, AZIMUTH_VERTICAL)
    rotation = _rotation(reader, name, v) if rotatable else None
    reversible = rotation.reversible if rotation else True
    thrust_max = v["thrust_max"]
    thrust_min = v["thrust_min"]
    if thrust_min is None:
        thrust_min = -thrust_max if reversible else 0.0
    elif thrust_min < 0.0 and not reversible:
        reader.fail(schema.actuator_parameter(name, "thrust_min"), "negative thrust needs 'reversible: true'")
    command = _command_map(reader, name, v, thrust_min, thrust_max)
    if command is None or (rotatable and rotation is None):
        return None
    return filled(ActuatorConfig, v, actuator_field, **derived, thrust_min=thrust_min, command=command,
                  rotation=rotation)


def _direction(reader: Reader, actuator_type: str, direction: list[float] | None,
               name: str) -> tuple[float, float, float]:
    if direction is None:
        if actuator_type == FIXED:
            reader.fail(name, "required for a fixed actuator")
            return (1.0, 0.0, 0.0)
        return (0.0, 0.0, 0.0)
    norm = math.sqrt(sum(c * c for c in direction))
    if norm < 1e-9:
        reader.fail(name, "must not be the zero vector")
        return (1.0, 0.0, 0.0)
    return tuple(c / norm for c in direction)


def _command_map(reader: Reader, name: str, v: dict[str, Any], thrust_min: float,
                 thrust_max: float) -> CommandMapConfig | None:
    def param(key: str) -> str:
        return schema.actuator_parameter(name, key)

    kind = v["command_map"]
    command_min = v["command_min"] if v["command_min"] is not None else -math.inf
    command_max = v["command_max"] if v["command_max"] is not None else math.inf
    if command_min >= command_max:
        reader.fail(param("command_min"), f"must be below command_max ({command_min:g} >= {command_max:g})")
        return None
    table_command: tuple[float, ...] = ()
    table_thrust: tuple[float, ...] = ()
    table_voltage: tuple[float, ...] = ()
    deadband = v["command_deadband"]
    if kind == "table":
        if v["table_command"] is None or v["table_thrust"] is None:
            reader.fail(param("table_command" if v["table_command"] is None else "table_thrust"),
                        "required with command_map: table")
            return None
        table_command, table_thrust = tuple(v["table_command"]), tuple(v["table_thrust"])
        table_voltage = tuple(v["table_voltage"] or ())
        if deadband > 0.0:
            reader.fail(param("command_deadband"), "applies to linear and quadratic maps; a table's flat "
                                                   "stretch of zero force is its dead band")
            return None
        if any(b <= a for a, b in pairwise(table_voltage)) or any(volts <= 0.0 for volts in table_voltage):
            reader.fail(param("table_voltage"), f"must be positive and strictly increasing, got "
                                                f"{list(table_voltage)}")
            return None
        rows = max(len(table_voltage), 1)
        if len(table_command) < 2 or len(table_thrust) != rows * len(table_command):
            per = f" (one row of {len(table_command)} per voltage of table_voltage, {rows})" if table_voltage \
                else ""
            reader.fail(param("table_thrust"), f"needs {rows * len(table_command)} entries{per}, as many per row "
                                               f"as table_command (>= 2); got {len(table_thrust)}")
            return None
        if any(b <= a for a, b in pairwise(table_command)):
            reader.fail(param("table_command"), "must be strictly increasing")
            return None
        width = len(table_command)
        for row_index in range(rows):
            row = table_thrust[row_index * width:(row_index + 1) * width]
            at = f" (the row at {table_voltage[row_index]:g} V)" if table_voltage else ""
            if any(b < a for a, b in pairwise(row)):
                reader.fail(param("table_thrust"), f"must not decrease as the command increases{at}")
                return None
            if not row[0] <= 0.0 <= row[-1]:
                reader.fail(param("table_thrust"), f"must span zero force{at}; spans [{row[0]:g}, {row[-1]:g}]")
                return None
    else:
        for key in ("table_command", "table_thrust", "table_voltage"):
            if v[key] is not None:
                reader.fail(param(key), f"only used with command_map: table (this one is {kind})")
                return None
        if deadband > 0.0 and not (deadband < command_max and -deadband > command_min):
            reader.fail(param("command_deadband"), f"{deadband:g} leaves no command beyond it in "
                                                   f"[{command_min:g}, {command_max:g}]")
            return None
    config = filled(CommandMapConfig, v, actuator_field,
                    gain_reverse=v["gain_reverse"] if v["gain_reverse"] is not None else v["gain"],
                    command_min=command_min, command_max=command_max, table_command=table_command,
                    table_thrust=table_thrust, table_voltage=table_voltage)
    low, high = command_map(config, table_voltage[0] if table_voltage else None).force_range()
    if not low <= 0.0 <= high:
        reader.fail(param("command_min"), f"the command range [{command_min:g}, {command_max:g}] must include "
                                          "the set-point of zero force")
        return None
    if thrust_min > thrust_max:
        reader.fail(param("thrust_min"), f"must not exceed thrust_max ({thrust_min:g} > {thrust_max:g})")
        return None
    return config


def _rotation(reader: Reader, name: str, v: dict[str, Any]) -> RotationConfig | None:
    def param(key: str) -> str:
        return schema.actuator_parameter(name, key)

    low, high = v["azimuth_min"], v["azimuth_max"]
    if low >= high:
        reader.fail(param("azimuth_min"), f"must be below azimuth_max ({low:g} >= {high:g})")
        return None
    if high - low > TWO_PI + ANGLE_TOLERANCE:
        reader.fail(param("azimuth_max"), f"the feasible sector may span at most 2 pi; spans {high - low:g} rad")
        return None
    flat = v["forbidden_sectors"] or []
    if len(flat) % 2:
        reader.fail(param("forbidden_sectors"), f"needs [start, end] pairs; got {len(flat)} numbers")
        return None
    sectors = tuple((flat[i], flat[i + 1]) for i in range(0, len(flat), 2))
    for start, end in sectors:
        width = (end - start) % TWO_PI
        if width < ANGLE_TOLERANCE:
            reader.fail(param("forbidden_sectors"), f"sector [{start:g}, {end:g}] is empty or the whole circle")
            return None
    protects = tuple(v["protects"] or ())
    if protects and len(protects) != len(sectors):
        reader.fail(param("protects"), f"needs one name per forbidden sector ({len(sectors)}); got {len(protects)}")
        return None
    rotation = filled(RotationConfig, v, actuator_field, forbidden_sectors=sectors, protects=protects)
    allowed = sum(end - start for start, end in allowed_arcs(rotation))
    if allowed < MIN_ALLOWED_ARC:
        key = "forbidden_sectors" if sectors else "azimuth_max"
        reader.fail(param(key), f"leaves {math.degrees(allowed):.3g} deg of the circle to thrust in; at least "
                                f"{math.degrees(MIN_ALLOWED_ARC):g} deg is needed")
        return None
    if not in_feasible_sector(rotation, rotation.initial):
        reader.fail(param("azimuth_initial"), f"{rotation.initial:g} rad is outside the feasible sector "
                                              f"[{low:g}, {high:g}]")
        return None
    if in_forbidden_sector(rotation, rotation.initial):
        reader.fail(param("azimuth_initial"), f"{rotation.initial:g} rad is inside a forbidden sector")
        return None
    return rotation
