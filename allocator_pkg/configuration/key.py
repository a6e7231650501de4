"""One configuration key (:class:`Key`): its type, default, limits, unit and documentation, as
the schema (:mod:`allocator_pkg.configuration.schema`) lists every parameter."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

FLOAT = "float"
INT = "int"
BOOL = "bool"
STR = "str"
FLOAT_LIST = "float[]"
INT_LIST = "integer[]"
STR_LIST = "string[]"


@dataclass(frozen=True)
class Key:
    """One parameter: its type, default, limits and documentation.

    ``default`` is the value used when the parameter is absent; ``None`` means the key is
    optional with a default that depends on other keys (``default_doc`` says which), and
    ``required`` means it must be given. A per-actuator key whose default differs by actuator
    type has it in ``type_defaults`` (type: default). ``constraint`` says in words what the
    checks of :mod:`allocator_pkg.configuration.parameters` and
    :mod:`allocator_pkg.configuration.actuator_parsers` want beyond type, choices, range and length.
    """

    name: str
    kind: str
    description: str
    default: Any = None
    default_doc: str = ""
    required: bool = False
    minimum: float | None = None
    maximum: float | None = None
    exclusive_minimum: bool = False
    choices: tuple[str, ...] = ()
    length: int | None = None
    applies_to: tuple[str, ...] = ()
    read_only: bool = False
    unit: str = ""
    constraint: str = ""
    type_defaults: Mapping[str, Any] = field(default_factory=dict)

    def default_for(self, actuator_type: str | None) -> Any:
        """The default of this key for an actuator of ``actuator_type`` (None: not per actuator)."""
        return self.type_defaults.get(actuator_type, self.default)

    def documented_default(self) -> str:
        if self.required:
            return "required"
        if self.default_doc:
            return self.default_doc
        if self.default is None:
            return "not set"
        if isinstance(self.default, bool):
            return str(self.default).lower()
        if isinstance(self.default, str):
            return f"`{self.default}`" if self.default else "empty"
        if isinstance(self.default, list):
            return "[" + ", ".join(map(str, self.default)) + "]"
        return f"{self.default:g}" if isinstance(self.default, float) else str(self.default)

    def documented_range(self) -> str:
        parts = []
        if self.choices:
            parts.append("one of " + ", ".join(f"`{c}`" for c in self.choices))
        if self.minimum is not None:
            parts.append(f"{'>' if self.exclusive_minimum else '>='} {self.minimum:g}")
        if self.maximum is not None:
            parts.append(f"<= {self.maximum:g}")
        if self.length is not None:
            parts.append(f"{self.length} elements")
        if self.constraint:
            parts.append(self.constraint)
        if self.kind == BOOL:
            parts.append("true or false")
        return ", ".join(parts)
