"""Parameter values against their keys: typed as a ROS 2 params file types them, then held to
the key's choices, length and range (:class:`~allocator_pkg.configuration.schema.Key`).

A :class:`Reader` reads the values of flat parameter names and collects every problem, each
as (parameter name, reason), so that one :class:`~allocator_pkg.vehicle.config.ConfigError`
can name them all.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .schema import BOOL, FLOAT, FLOAT_LIST, INT, INT_LIST, STR, Key

MISSING = object()
"""A value that is required and absent, or invalid (its problem recorded)."""


class Reader:
    """Flat parameters read key by key, every problem collected in ``problems``.

    A parameter whose value is None counts as not given."""

    def __init__(self, parameters: Mapping[str, Any]):
        self.parameters = {name: value for name, value in parameters.items() if value is not None}
        self.problems: list[tuple[str, str]] = []

    def fail(self, name: str, reason: str) -> None:
        self.problems.append((name, reason))

    def value(self, key: Key, name: str | None = None, actuator_type: str | None = None) -> Any:
        """The typed value of a key (under the parameter name ``name``, by default the key's),
        its default (for an actuator of ``actuator_type``), or MISSING (after recording why)."""
        name = name or key.name
        raw = self.parameters.get(name, MISSING)
        if raw is MISSING:
            if key.required:
                self.fail(name, "required key is missing")
                return MISSING
            return key.default_for(actuator_type)
        value = coerce(key, raw)
        if isinstance(value, Invalid):
            self.fail(name, value.reason)
            return MISSING
        reason = limit_problem(key, value)
        if reason:
            self.fail(name, reason)
            return MISSING
        return value


@dataclass(frozen=True)
class Invalid:
    """Why a value cannot be of its key's type."""

    reason: str


def _describe(raw: Any) -> str:
    if isinstance(raw, str):
        return f"the string '{raw}'"
    if isinstance(raw, bool):
        return f"the boolean {str(raw).lower()}"
    if isinstance(raw, (list, tuple)):
        return f"a list {list(raw)!r}"
    return f"{type(raw).__name__} {raw!r}"


def _number(raw: Any) -> float | None:
    if isinstance(raw, bool) or not isinstance(raw, (int, float)):
        return None
    return float(raw)


def coerce(key: Key, raw: Any) -> Any:
    """Convert a parameter value to the key's type, or explain why it cannot be (Invalid)."""
    if key.kind == FLOAT:
        value = _number(raw)
        if value is None:
            return Invalid(f"expected a number, got {_describe(raw)}")
        if not math.isfinite(value):
            return Invalid(f"must be finite, got {value}")
        return value
    if key.kind == INT:
        value = _number(raw)
        if value is None or not math.isfinite(value) or value != int(value):
            return Invalid(f"expected an integer, got {_describe(raw)}")
        return int(value)
    if key.kind == BOOL:
        if not isinstance(raw, bool):
            return Invalid(f"expected true or false, got {_describe(raw)}")
        return raw
    if key.kind == STR:
        if not isinstance(raw, str):
            return Invalid(f"expected a string, got {_describe(raw)}")
        return raw
    if not isinstance(raw, (list, tuple)):
        return Invalid(f"expected a list ({key.kind}), got {_describe(raw)}")
    if key.kind == INT_LIST:
        values = [_number(item) for item in raw]
        if any(item is None or not math.isfinite(item) or item != int(item) for item in values):
            return Invalid(f"expected a list of integers, got {_describe(raw)}")
        return [int(item) for item in values]
    if key.kind == FLOAT_LIST:
        values = [_number(item) for item in raw]
        if any(item is None for item in values):
            return Invalid(f"expected a list of numbers, got {_describe(raw)}")
        if not all(math.isfinite(item) for item in values):
            return Invalid(f"every element must be finite, got {list(raw)!r}")
        return values
    if not all(isinstance(item, str) for item in raw):
        return Invalid(f"expected a list of strings, got {_describe(raw)}")
    return list(raw)


def limit_problem(key: Key, value: Any) -> str:
    """The reason a typed value breaks the key's limits, or ''."""
    if key.choices and value not in key.choices:
        return f"'{value}' is not one of {', '.join(key.choices)}"
    if key.length is not None and len(value) != key.length:
        return f"needs {key.length} elements, got {len(value)}"
    items = value if isinstance(value, list) else [value]
    if key.kind in (FLOAT, INT, FLOAT_LIST, INT_LIST):
        for item in items:
            if key.minimum is not None:
                if key.exclusive_minimum and item <= key.minimum:
                    return f"must be > {key.minimum:g}, got {item:g}"
                if item < key.minimum:
                    return f"must be >= {key.minimum:g}, got {item:g}"
            if key.maximum is not None and item > key.maximum:
                return f"must be <= {key.maximum:g}, got {item:g}"
    return ""
