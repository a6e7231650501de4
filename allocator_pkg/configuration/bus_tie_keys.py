"""Bus-tie breakers (``power.bus_ties``, ``power.bus_tie.<tie>.sources``,
``power.bus_tie.<tie>.closed``) to :class:`~allocator_pkg.vehicle.config.BusTie`, checked
against the power sources: a tie named twice or badly, or named as a source; sources that are
not two different names of ``power.sources``; two ties between the same two sources; ties
without sources. Every problem is recorded on the
:class:`~allocator_pkg.configuration.values.Reader`, naming the key. The allocation pools the
sources of closed ties into one bus (:mod:`allocator_pkg.allocation.bus_ties`; docs/power.md).
"""

from __future__ import annotations

from ..vehicle.config import BusTie
from . import schema
from .fields import filled, tie_field
from .power import unique_names
from .values import MISSING, Reader

TIES_KEY = "power.bus_ties"


def parse_bus_ties(reader: Reader, sources: list[str]) -> tuple[tuple[BusTie, ...], set[str]]:
    """(bus ties, the parameter names of their keys) of the parameters; ``sources`` are the
    valid names of power.sources."""
    given = reader.value(schema.VEHICLE_KEY_BY_NAME[TIES_KEY])
    if given not in (None, MISSING) and given and not sources:
        reader.fail(TIES_KEY, "a bus tie joins two of power.sources; there are none")
        return (), set()
    ties: list[BusTie] = []
    known: set[str] = set()
    pairs: dict[frozenset[str], str] = {}
    for name in unique_names(reader, TIES_KEY, given, sources, "a power source's name; name the tie apart"):
        values = {}
        for key in schema.TIE_KEYS:
            parameter = schema.tie_parameter(name, key.name)
            known.add(parameter)
            values[key.name] = reader.value(key, parameter)
        joined = values["sources"]
        if joined is MISSING or values["closed"] is MISSING:
            continue
        parameter = schema.tie_parameter(name, "sources")
        unknown = [s for s in joined if s not in sources]
        if unknown:
            reader.fail(parameter, f"{', '.join(unknown)} not in power.sources ({', '.join(sources)})")
        elif joined[0] == joined[1]:
            reader.fail(parameter, f"joins {joined[0]} to itself; name two different sources")
        elif frozenset(joined) in pairs:
            reader.fail(parameter, f"{joined[0]} and {joined[1]} are joined by {pairs[frozenset(joined)]} already")
        else:
            pairs[frozenset(joined)] = name
            ties.append(filled(BusTie, values, tie_field, name=name, sources=tuple(joined)))
    return tuple(ties), known
