"""The keys of this package's YAML input files that are not ROS params files (particulars, site,
scenario, Level 3 criteria), each format declared once as a table of :class:`FileKey`: the
readers' checks (:func:`check_keys`, :meth:`FileKey.holds`), the defaults of the typed objects
they fill (:func:`defaults`) and the key tables of the docs (:func:`markdown_table`) come from
it, as :mod:`allocator_pkg.configuration.schema` does for the ROS parameters."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

NUMBER = "number"
INTEGER = "integer"
TEXT = "text"
BOOLEAN = "boolean"
NUMBERS = "numbers"
"""A list of numbers."""
MAPPING = "mapping"
LIST = "list"
EACH = "[]"
"""``FileKey.item``: the value is a list of mappings of ``keys`` (any other ``item``, such as
``<actuator>``, names what the value maps to mappings of ``keys``)."""


@dataclass(frozen=True)
class FileKey:
    """One key of an input file: its kind, meaning, default, range and unit.

    ``default`` is the value used when the key is absent (None: not set, or ``default_doc``
    says what stands in); ``required`` means it must be given. ``minimum`` and ``maximum`` bound
    a number (``exclusive_*``: the bound itself refused), ``choices`` a text, ``range_doc`` says
    in words what the reader checks beyond them. A mapping's own keys are ``keys``, reached as
    ``item`` says (:data:`EACH`, a ``<placeholder>`` of the names, or directly).
    """

    name: str
    kind: str
    text: str
    default: Any = None
    default_doc: str = ""
    required: bool = False
    unit: str = ""
    minimum: float | None = None
    maximum: float | None = None
    exclusive_minimum: bool = False
    exclusive_maximum: bool = False
    choices: tuple[str, ...] = ()
    range_doc: str = ""
    keys: tuple[FileKey, ...] = ()
    item: str = ""
    list_keys: bool = True
    """False: the docs' table names this key only, not each of its ``keys`` (one per metric, say)."""

    def holds(self, value: float) -> bool:
        """Whether the number ``value`` is within this key's bounds."""
        low = self.minimum is None or (value > self.minimum if self.exclusive_minimum else value >= self.minimum)
        high = self.maximum is None or (value < self.maximum if self.exclusive_maximum else value <= self.maximum)
        return low and high

    def interval(self) -> str:
        """The bounds as an interval, ``(0, 70]``."""
        low = "(" if self.exclusive_minimum else "["
        high = ")" if self.exclusive_maximum else "]"
        return f"{low}{self.minimum:g}, {self.maximum:g}{high}"

    def documented_default(self) -> str:
        if self.required:
            return "required"
        if self.default_doc:
            return self.default_doc
        if self.default is None:
            return ""
        if isinstance(self.default, bool):
            return str(self.default).lower()
        if isinstance(self.default, (list, tuple)):
            return "[" + ", ".join(f"{v:g}" for v in self.default) + "]"
        return f"{self.default:g}" if isinstance(self.default, float) else str(self.default)

    def documented_range(self) -> str:
        parts = []
        if self.choices:
            parts.append(", ".join(self.choices))
        if self.minimum is not None and self.maximum is not None:
            parts.append(self.interval())
        elif self.minimum is not None:
            parts.append(f"{'>' if self.exclusive_minimum else '>='} {self.minimum:g}")
        elif self.maximum is not None:
            parts.append(f"{'<' if self.exclusive_maximum else '<='} {self.maximum:g}")
        if self.range_doc:
            parts.append(self.range_doc)
        return ", ".join(parts)


def names(keys: Sequence[FileKey]) -> tuple[str, ...]:
    """The names of a table, in its order."""
    return tuple(key.name for key in keys)


def key_named(keys: Sequence[FileKey], name: str) -> FileKey:
    """The key of ``keys`` called ``name``."""
    return next(key for key in keys if key.name == name)


def defaults(keys: Sequence[FileKey]) -> dict[str, Any]:
    """Name: default of every key of a table that has one."""
    return {key.name: key.default for key in keys if key.default is not None}


def check_keys(data: Mapping[str, Any], keys: Sequence[FileKey], where: str = "", *, sort_known: bool = False) -> None:
    """A ``ValueError`` naming ``where`` when ``data`` has a key the table does not know
    ("unknown key(s) ...; known: ..." in the table's order, or sorted) or misses a required one
    (:func:`check_required`)."""
    known = names(keys)
    unknown = sorted(str(key) for key in data if key not in known)
    if unknown:
        listed = sorted(known) if sort_known else known
        raise ValueError(f"{_head(where, 'unknown key(s)')} {', '.join(unknown)}; known: {', '.join(listed)}")
    check_required(data, keys, where)


def check_required(data: Mapping[str, Any], keys: Sequence[FileKey], where: str = "") -> None:
    """A ``ValueError`` naming ``where`` and every required key of the table ``data`` misses
    ("missing key(s) ...")."""
    missing = [key.name for key in keys if key.required and key.name not in data]
    if missing:
        raise ValueError(f"{_head(where, 'missing key(s)')} {', '.join(missing)}")


def finite_number(value: Any, where: str) -> float:
    """``value`` as a finite float, or a ``ValueError`` naming ``where``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{where}: a finite number, not {value!r}")
    return float(value)


def markdown_table(keys: Sequence[FileKey], prefix: str = "") -> str:
    """The key table of a file format for the docs: one row per key at any depth."""
    rows = ["| key | unit | default | range | meaning |", "|---|---|---|---|---|"]
    for path, key in _flattened(keys, prefix):
        cells = [f"`{path}`", key.unit, key.documented_default(), key.documented_range(), key.text]
        rows.append("| " + " | ".join(cell.replace("|", "\\|") for cell in cells) + " |")
    return "\n".join(rows) + "\n"


def _flattened(keys: Sequence[FileKey], prefix: str) -> Iterator[tuple[str, FileKey]]:
    for key in keys:
        path = prefix + key.name
        yield path, key
        if not key.list_keys:
            continue
        inner = f"{path}[]." if key.item == EACH else f"{path}.{key.item}." if key.item else f"{path}."
        yield from _flattened(key.keys, inner)


def _head(where: str, what: str) -> str:
    return f"{where}: {what}" if where else f"{what}:"
