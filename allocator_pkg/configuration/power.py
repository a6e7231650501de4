"""Power sources, feeds and redundancy groups (``power.*``, ``actuators.<name>.feeds``,
``redundancy_groups.*``) to :class:`~allocator_pkg.vehicle.config.PowerSource` and
:class:`~allocator_pkg.vehicle.config.RedundancyGroup`, checked against each other and the
actuators: a source or group named twice or badly, a feed or group member that names no source
or actuator, feed shares that are not one per feed or do not sum to 1, a thruster without feeds
while sources are set, a group that leaves a thruster outside it with no feed at all. Every
problem is recorded on the :class:`~allocator_pkg.configuration.values.Reader`, naming the key.
The allocation keeps each source's draw within its available power
(:mod:`allocator_pkg.allocation.power_budget`); DNV-ST-0111 capability analysis reads them too.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from typing import Any

from ..vehicle.config import ActuatorConfig, PowerSource, RedundancyGroup
from . import schema
from .fields import filled, group_field, source_field
from .values import MISSING, Reader

SHARE_TOLERANCE = 1e-6
"""How far the feed shares of a thruster may sum from 1."""


def parse_power(reader: Reader, names: list[str], actuators: list[ActuatorConfig]) -> tuple[
        tuple[PowerSource, ...], tuple[RedundancyGroup, ...], set[str]]:
    """(sources, groups, the parameter names of their keys) of the parameters; ``names`` are
    actuators.names, ``actuators`` those built."""
    given = reader.value(schema.VEHICLE_KEY_BY_NAME["power.sources"])
    listed = unique_names(reader, "power.sources", given, names, "an actuator's name; name the source apart")
    sources, known = _sources(reader, listed)
    _feeds(reader, actuators, set(listed))
    groups, group_keys = _groups(reader, names, set(listed))
    for group in groups:
        _stranded(reader, group, actuators)
    return sources, groups, known | group_keys


def unique_names(reader: Reader, key: str, given: Any, taken: Collection[str] = (), clash: str = "") -> list[str]:
    """The unique, valid names of the name list ``key`` (``power.sources``,
    ``redundancy_groups.names``, ``power.bus_ties``) of value ``given``, none of them one of
    ``taken`` (``clash``: what such a name is, in the problem's text)."""
    valid: list[str] = []
    for name in given if given not in (None, MISSING) else []:
        if not schema.ACTUATOR_NAME.match(name):
            reader.fail(key, f"'{name}' is not a valid name (letters, digits, '_', starting with a letter)")
        elif name in valid:
            reader.fail(key, f"duplicate name '{name}'")
        elif name in taken:
            reader.fail(key, f"'{name}' is {clash}")
        else:
            valid.append(name)
    return valid


def _sources(reader: Reader, listed: list[str]) -> tuple[tuple[PowerSource, ...], set[str]]:
    sources, known = [], set()
    for name in listed:
        values = {}
        for key in schema.SOURCE_KEYS:
            parameter = schema.source_parameter(name, key.name)
            known.add(parameter)
            values[key.name] = reader.value(key, parameter)
        if all(value is not MISSING for value in values.values()):
            sources.append(filled(PowerSource, values, source_field, name=name))
    return tuple(sources), known


def _feeds(reader: Reader, actuators: list[ActuatorConfig], sources: set[str]) -> None:
    """Each thruster's feeds name sources, once each, with one share per feed summing to 1."""
    for actuator in actuators:
        feeds, shares = actuator.feeds, actuator.feed_shares
        key = schema.actuator_parameter(actuator.name, "feeds")
        if sources and not feeds and not actuator.is_surface:
            reader.fail(key, f"required with power.sources: the sources this thruster draws from "
                             f"({', '.join(sorted(sources))})")
        unknown = [f for f in feeds if f not in sources]
        if unknown:
            reader.fail(key, f"{', '.join(unknown)} not in power.sources ({', '.join(sorted(sources)) or 'empty'})")
        if len(set(feeds)) != len(feeds):
            reader.fail(key, "names a source twice")
        share_key = schema.actuator_parameter(actuator.name, "feed_shares")
        if len(shares) != len(feeds):
            reader.fail(share_key, f"one share per feed ({len(feeds)}: {', '.join(feeds) or 'none'}); got "
                                   f"{len(shares)}")
        elif feeds and not math.isclose(sum(shares), 1.0, abs_tol=SHARE_TOLERANCE):
            reader.fail(share_key, f"the shares sum to {sum(shares):g}, not 1")


def _groups(reader: Reader, actuators: list[str], sources: set[str]) -> tuple[tuple[RedundancyGroup, ...], set[str]]:
    groups, known = [], set()
    given = reader.value(schema.VEHICLE_KEY_BY_NAME["redundancy_groups.names"])
    for name in unique_names(reader, "redundancy_groups.names", given):
        values: dict[str, Any] = {}
        for key in schema.GROUP_KEYS:
            parameter = schema.group_parameter(name, key.name)
            known.add(parameter)
            listed = reader.value(key, parameter)
            values[key.name] = tuple(listed) if listed not in (None, MISSING) else ()
            allowed = actuators if key.name == "actuators" else sources
            what = "actuators.names" if key.name == "actuators" else "power.sources"
            unknown = [m for m in values[key.name] if m not in allowed]
            if unknown:
                reader.fail(parameter, f"{', '.join(unknown)} not in {what} ({', '.join(sorted(allowed)) or 'empty'})")
            if len(set(values[key.name])) != len(values[key.name]):
                reader.fail(parameter, "names a member twice")
        if not values["sources"] and not values["actuators"]:
            reader.fail(schema.group_parameter(name, "actuators"), "a group loses at least one actuator or source")
        groups.append(filled(RedundancyGroup, {}, group_field, name=name, **values))
    return tuple(groups), known


def _stranded(reader: Reader, group: RedundancyGroup, actuators: list[ActuatorConfig]) -> None:
    """A thruster outside the group whose every feed the group loses belongs in the group."""
    for actuator in actuators:
        if actuator.name in group.actuators or not actuator.feeds:
            continue
        if all(feed in group.sources for feed in actuator.feeds):
            reader.fail(schema.group_parameter(group.name, "actuators"),
                        f"the group loses every feed of {actuator.name} ({', '.join(actuator.feeds)}): list it")
