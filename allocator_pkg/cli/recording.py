"""Recordings that ``ros2 bag`` and Foxglove open: ROS 2 messages into an MCAP file with the
``mcap-ros2-support`` writer (profile ``ros2``, CDR messages, ``ros2msg`` schemas).

A ``ros2msg`` schema is what ``ros2 bag`` stores: the type's own ``.msg`` text, then the text
of every type it uses, directly or not, each once, after a line of 80 ``=`` and a line
``MSG: package/Type``. The texts come from the ``.msg`` files the message packages install
(``share/<package>/msg/<Type>.msg`` under a prefix of ``AMENT_PREFIX_PATH`` or the prefix
the package's Python module was installed into).
"""

from __future__ import annotations

import contextlib
import importlib
import os
import re
from pathlib import Path
from typing import Any

from mcap.records import Schema
from mcap_ros2.writer import Writer

PRIMITIVES = {"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32", "uint32",
              "int64", "uint64", "string", "wstring"}
SEPARATOR = "=" * 80


def type_name(message_type: type) -> str:
    """``package/Type`` of a generated message class (``std_msgs/Float64MultiArray``)."""
    package = message_type.__module__.split(".")[0]
    return f"{package}/{message_type.__name__}"


def msg_file(name: str) -> Path:
    """The installed ``.msg`` file of ``package/Type``. FileNotFoundError if there is none."""
    package, _, message = name.partition("/")
    prefixes = [Path(p) for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    with contextlib.suppress(ImportError, TypeError, IndexError):      # not installed, or not in a prefix
        prefixes.append(Path(importlib.import_module(package).__file__).resolve().parents[4])
    for prefix in prefixes:
        path = prefix / "share" / package / "msg" / f"{message}.msg"
        if path.is_file():
            return path
    raise FileNotFoundError(f"no {package}/msg/{message}.msg under {', '.join(map(str, prefixes)) or 'any prefix'}")


def field_types(text: str, package: str) -> list[str]:
    """The ``package/Type`` of every field of a ``.msg`` text that is a message (primitives and
    constants left out; a bare ``Type`` is of the same package)."""
    found = []
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        base = re.sub(r"<=\d+$", "", re.sub(r"\[.*\]$", "", line.split()[0]))
        if base in PRIMITIVES:                            # constants are primitives too
            continue
        found.append(base if "/" in base else f"{package}/{base}")
    return found


def ros2msg_schema(name: str) -> str:
    """The ``ros2msg`` schema text of ``package/Type``: its ``.msg`` text, then its dependencies'."""
    text = msg_file(name).read_text().rstrip("\n")
    parts, seen, queue = [text], {name}, field_types(text, name.split("/")[0])
    while queue:
        dependency = queue.pop(0)
        if dependency in seen:
            continue
        seen.add(dependency)
        dependency_text = msg_file(dependency).read_text().rstrip("\n")
        parts.append(f"{SEPARATOR}\nMSG: {dependency}\n{dependency_text}")
        queue.extend(field_types(dependency_text, dependency.split("/")[0]))
    return "\n".join(parts) + "\n"


class Recording:
    """ROS 2 messages into an MCAP file, one channel per topic; :meth:`close` finishes the file."""

    def __init__(self, path: str | Path):
        self._file = open(path, "wb")                  # noqa: SIM115 (closed in close())
        self._writer = Writer(self._file)
        self._schemas: dict[type, Schema] = {}

    def write(self, topic: str, message: Any, log_time: int, publish_time: int | None = None) -> None:
        """One message on ``topic``, logged at ``log_time`` [ns] (published at ``publish_time``,
        default the log time)."""
        kind = type(message)
        schema = self._schemas.get(kind)
        if schema is None:
            name = type_name(kind)
            schema = self._schemas[kind] = self._writer.register_msgdef(name, ros2msg_schema(name))
        self._writer.write_message(topic, schema, message, log_time=log_time, publish_time=publish_time)

    def close(self) -> None:
        self._writer.finish()
        self._file.close()
