"""The flushing zones of a vehicle in force, given which thrusters work.

Two kinds of zone, each tied to the thruster it protects, lift while that thruster does not
work and return when it works again:

- the sectors of a rotatable thruster's ``forbidden_sectors`` that its ``protects`` ties to
  another thruster (a sector tied to none is always in force);
- with ``flushing_zones: dnv``, the DNV-ST-0111 [3.11.3] zones of the geometry
  (:func:`~.flushing.flushing_zones`) of every azimuth thruster with a diameter (a fixed
  thruster with one: the side of its force range that pushes into a zone is closed), and in
  place of a zone onto a dead thruster the [3.11.4] loss (:func:`~.flushing.dead_flushing`).

:func:`zones_in_force` gives every actuator's rotation with the sectors in force, the sides
of fixed thrusters closed, and the losses; computed when the faults change, never per sample.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

from ..vehicle.config import AZIMUTH, FIXED, ActuatorConfig, RotationConfig, Vehicle
from .flushing import DeadFlushing, Unit, dead_flushing, flushing_zones

HORIZONTAL = 1e-9
"""A fixed thruster whose direction's horizontal part is below this pushes vertically: no unit."""


@dataclass(frozen=True)
class ZonesInForce:
    """Per actuator (configuration order): ``rotations``, a rotatable thruster's rotation with
    the sectors in force (None for others); ``closed``, the (reverse, forward) sides of a fixed
    thruster's force range that push into a zone; ``losses``, each thruster's [3.11.4] losses
    onto dead thrusters, by actuator index."""

    rotations: tuple[RotationConfig | None, ...]
    closed: tuple[tuple[bool, bool], ...]
    losses: dict[int, tuple[DeadFlushing, ...]]


def has_zones(vehicle: Vehicle) -> bool:
    """Whether any zone of this vehicle can lift: ``flushing_zones`` dnv, or a sector tied to a
    thruster by ``protects``."""
    return vehicle.flushing_zones == "dnv" or any(a.rotatable and any(a.rotation.protects)
                                                  for a in vehicle.actuators)


def unit(actuator: ActuatorConfig) -> Unit | None:
    """The thruster as a [3.11.3] unit: an azimuth thruster, or a fixed one that pushes
    horizontally; None otherwise."""
    if actuator.type == FIXED:
        if math.hypot(actuator.direction[0], actuator.direction[1]) < HORIZONTAL:
            return None
    elif actuator.type != AZIMUTH:
        return None
    return Unit(actuator.name, actuator.position[0], actuator.position[1], actuator.diameter, actuator.tunnel,
                actuator.ducted)


def zones_in_force(vehicle: Vehicle, working: Sequence[bool]) -> ZonesInForce:
    """The zones in force when the thrusters ``working`` (one flag per actuator) work."""
    actuators = vehicle.actuators
    index = {a.name: i for i, a in enumerate(actuators)}
    sectors: list[list[tuple[float, float]]] = [[] for _ in actuators]
    for i, actuator in enumerate(actuators):
        if actuator.rotatable:
            protects = actuator.rotation.protects or ("",) * len(actuator.rotation.forbidden_sectors)
            sectors[i] = [sector for sector, name in zip(actuator.rotation.forbidden_sectors, protects)
                          if not name or working[index[name]]]
    closed = [(False, False)] * len(actuators)
    losses: dict[int, tuple[DeadFlushing, ...]] = {}
    if vehicle.flushing_zones == "dnv":
        units = {i: u for i, u in ((i, unit(a)) for i, a in enumerate(actuators)) if u is not None}
        alive = [u for i, u in units.items() if working[i]]
        for zone in flushing_zones(alive):
            i = index[zone.thruster]
            if actuators[i].rotatable:
                sectors[i].append(zone.sector)
            else:
                direction = math.atan2(actuators[i].direction[1], actuators[i].direction[0])
                reverse, forward = closed[i]
                closed[i] = (reverse or zone.forbids(direction + math.pi), forward or zone.forbids(direction))
        dead = [u for i, u in units.items() if not working[i]]
        for i, flushing in units.items():
            if working[i] and actuators[i].rotatable and flushing.diameter > 0.0:
                found = tuple(loss for loss in (dead_flushing(flushing, d) for d in dead) if loss is not None)
                if found:
                    losses[i] = found
    rotations = tuple(
        None if not a.rotatable
        else a.rotation if tuple(sectors[i]) == a.rotation.forbidden_sectors and not a.rotation.protects
        else replace(a.rotation, forbidden_sectors=tuple(sectors[i]), protects=())
        for i, a in enumerate(actuators))
    return ZonesInForce(rotations, tuple(closed), losses)


def potential_rotations(vehicle: Vehicle) -> tuple[RotationConfig | None, ...]:
    """Every rotatable thruster's rotation with every zone it can have (all thrusters working):
    what the configuration must be ready for."""
    return zones_in_force(vehicle, [True] * len(vehicle.actuators)).rotations
