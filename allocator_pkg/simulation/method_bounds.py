"""What a scenario expects of a method other than of the rest (``methods.<method>`` of a scenario
file, :data:`~.scenario_keys.METHOD_KEYS`): its own bounds over the run and over the file's
named windows, each in place of the scenario's bound of that metric, and a note saying why."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ..vehicle.config import Vehicle
from .scenario_check import check_method_serves, unknown_keys
from .scenario_keys import METHOD_KEYS
from .scenario_values import ScenarioError, read_bounds
from .windows import Window


@dataclass(frozen=True)
class MethodBounds:
    """What a scenario expects of one method other than of the rest (its ``methods.<name>``):
    bounds over the run and over named windows, each in place of the scenario's own bound of
    that metric, and why."""

    bounds: dict[str, float] = field(default_factory=dict)
    windows: dict[str, dict[str, float]] = field(default_factory=dict)
    """Window name: its bounds for this method."""
    note: str = ""


def method_bounds(data: Any, windows: list[Window], vehicle: Vehicle) -> dict[str, MethodBounds]:
    """The ``methods`` section: per method (one that can serve the vehicle), its own ``bounds``
    over the run, ``windows`` (a named window's name: its bounds) and a ``note``."""
    if not isinstance(data, dict):
        raise ScenarioError(f"methods: a mapping of method names to what the scenario expects of each, not {data!r}")
    found = {}
    names = [w.name for w in windows]
    for method, body in data.items():
        where = f"methods.{method}"
        try:
            check_method_serves(str(method), vehicle)
        except ValueError as error:
            raise ScenarioError(f"{where}: {error}") from error
        if not isinstance(body, dict) or not body:
            raise ScenarioError(f"{where}: a mapping of bounds, windows and a note, not {body!r}")
        unknown = unknown_keys(body, METHOD_KEYS, where)
        if unknown:
            raise ScenarioError("; ".join(unknown))
        own_windows = body.get("windows", {}) or {}
        if not isinstance(own_windows, dict):
            raise ScenarioError(f"{where}.windows: a mapping of window names to bounds, not {own_windows!r}")
        for name in own_windows:
            if name not in names:
                raise ScenarioError(f"{where}.windows.{name}: not a window of the file ("
                                    + (", ".join(names) if names else "it has none") + ")")
        if "note" in body and not isinstance(body["note"], str):
            raise ScenarioError(f"{where}.note: a text, not {body['note']!r}")
        found[str(method)] = MethodBounds(
            bounds=read_bounds(body.get("bounds", {}) or {}, f"{where}.bounds"),
            windows={name: read_bounds(limits, f"{where}.windows.{name}") for name, limits in own_windows.items()},
            note=body.get("note", ""))
    return found
