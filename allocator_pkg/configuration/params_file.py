"""ROS 2 params files: one node section read into flat, dotted parameter names, and flat names
written back as a file (``/**: ros__parameters:``), as rcl reads and matches them."""

from __future__ import annotations

import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml

from ..vehicle.config import ConfigError

ANY_NODE = "/**"
"""The section key that applies to every node, whatever its namespace and name."""


class _ParamsLoader(yaml.SafeLoader):
    """YAML as ROS reads params files: also ``1e6`` and ``1.0e6`` are floats (YAML 1.1
    alone reads them as strings; rcl converts them with strtod)."""


_ParamsLoader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(?:[0-9][0-9_]*(?:\.[0-9_]*)?|\.[0-9_]+)[eE][-+]?[0-9]+$"),
    list("-+0123456789."),
)


def section_matches(section: str, node_name: str) -> bool:
    """Whether a params file's section key applies to a node, as rcl matches them: ``/**``
    stands for any namespace and name, ``*`` for one token, and a key without a leading
    ``/`` is in the root namespace. A ``node_name`` without a namespace (no leading ``/``)
    also matches a section of that name in any namespace."""
    pattern = section if section.startswith("/") else f"/{section}"
    expression = "".join("(?:/[^/]+)*" if token == "**" else "/" + re.escape(token).replace(r"\*", "[^/]*")
                         for token in pattern.split("/")[1:])
    if re.fullmatch(expression, node_name if node_name.startswith("/") else f"/{node_name}"):
        return True
    return not node_name.startswith("/") and pattern.rsplit("/", 1)[-1] == node_name


def read_parameters(path: str | Path, node_name: str | None = None) -> dict[str, Any]:
    """Flat parameters of one node section of a ROS 2 params file: the first section, or the
    first that applies to ``node_name`` (a full name such as ``/rov1/thrust_allocator``, or
    a name alone; :func:`section_matches`)."""
    path = Path(path)
    try:
        document = yaml.load(path.read_text(), Loader=_ParamsLoader)
    except OSError as error:
        raise ConfigError([(str(path), f"cannot read the file ({error.strerror})")]) from error
    except yaml.YAMLError as error:
        raise ConfigError([(str(path), f"not valid YAML: {error}")]) from error
    if not isinstance(document, dict) or not document:
        raise ConfigError([(str(path), "expected '<node_name>: ros__parameters: {...}' sections")])
    sections = {
        str(name): body["ros__parameters"]
        for name, body in document.items()
        if isinstance(body, dict) and isinstance(body.get("ros__parameters"), dict)
    }
    if not sections:
        raise ConfigError([(str(path), "no '<node_name>: ros__parameters:' section found")])
    if node_name is None:
        section = next(iter(sections.values()))
    else:
        matches = [body for name, body in sections.items() if section_matches(name, node_name)]
        if not matches:
            raise ConfigError([(str(path), f"no section for node '{node_name}'; sections: {', '.join(sections)}")])
        section = matches[0]
    flat: dict[str, Any] = {}
    problems: list[tuple[str, str]] = []
    _flatten(section, "", flat, problems)
    if problems:
        raise ConfigError(problems)
    return flat


def parse_value(text: str) -> Any:
    """One value written as in a params file, typed as rcl types it (``1.0e6`` a double,
    ``[a, b]`` a list of strings, ``true`` a bool)."""
    return yaml.load(text, Loader=_ParamsLoader)


def params_text(parameters: Mapping[str, Any]) -> str:
    """Flat parameters as the text of a ROS 2 params file whose one section applies to any node
    (``/**``), in their order: what :func:`read_parameters` reads back."""
    nested: dict[str, Any] = {}
    for name, value in parameters.items():
        level = nested
        *parents, leaf = name.split(".")
        for parent in parents:
            level = level.setdefault(parent, {})
        level[leaf] = value
    return yaml.safe_dump({ANY_NODE: {"ros__parameters": nested}}, sort_keys=False)


def write_parameters(path: str | Path, parameters: Mapping[str, Any]) -> Path:
    """Write flat parameters as a ROS 2 params file (:func:`params_text`); returns the path."""
    path = Path(path)
    path.write_text(params_text(parameters))
    return path


def _flatten(node: Mapping[str, Any], prefix: str, out: dict[str, Any], problems: list[tuple[str, str]]) -> None:
    for key, value in node.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            _flatten(value, name + ".", out, problems)
        elif isinstance(value, list):
            if not value:
                continue  # rcl reads an empty list as "not set"
            kinds = {_ros_type(item) for item in value}
            if len(kinds) > 1:
                problems.append((name, f"a ROS parameter list holds one type, got {sorted(kinds)}; "
                                       "write floats as 1.0, not 1"))
            else:
                out[name] = value
        else:
            out[name] = value


def _ros_type(value: Any) -> str:
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "double"
    if isinstance(value, str):
        return "string"
    return type(value).__name__
