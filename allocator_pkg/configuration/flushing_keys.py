"""The flushing zones' keys checked against each other: every ``protects`` name an actuator
other than its own, and with ``flushing_zones: dnv`` a diameter for every azimuth thruster
and no two thrusters of the [3.11.3] geometry at one horizontal position."""

from __future__ import annotations

from collections.abc import Sequence
from itertools import combinations

from ..effectiveness.zones import unit
from ..vehicle.config import AZIMUTH, ActuatorConfig
from . import schema
from .values import Reader


def check_flushing(reader: Reader, mode: str, actuators: Sequence[ActuatorConfig]) -> None:
    """Record on ``reader`` every problem of the flushing zones' keys."""
    names = [a.name for a in actuators]
    for actuator in actuators:
        if not actuator.rotatable:
            continue
        for name in actuator.rotation.protects:
            if name and (name not in names or name == actuator.name):
                reader.fail(schema.actuator_parameter(actuator.name, "protects"),
                            f"'{name}' is not another actuator ({', '.join(n for n in names if n != actuator.name)})")
    if mode != "dnv":
        return
    for actuator in actuators:
        if actuator.type == AZIMUTH and actuator.diameter <= 0.0:
            reader.fail(schema.actuator_parameter(actuator.name, "diameter"),
                        "required (above 0) for an azimuth thruster with flushing_zones: dnv")
    units = [u for u in map(unit, actuators) if u is not None]
    for first, second in combinations(units, 2):
        if first.x == second.x and first.y == second.y:
            reader.fail("flushing_zones", f"{first.name} and {second.name} are at the same horizontal position: "
                                          "no direction from one to the other ([3.11.3])")
