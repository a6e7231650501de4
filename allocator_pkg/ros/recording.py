"""Recordings as ``ros2 bag record -s mcap`` writes them (rosbag2_storage_mcap, Jazzy), which
``ros2 bag``, Foxglove and ``rosbags`` open and decode.

A path ending in ``.mcap`` becomes one MCAP file, complete in itself: ``ros2 bag`` and
``rosbags`` open the file alone. Any other path becomes a bag directory, as
``ros2 bag record -o <path>`` makes it: ``<path>/<name>_0.mcap`` and ``<path>/metadata.yaml``.

In the file: the profile ``ros2``; per message type a schema named ``package/msg/Type``,
encoding ``ros2msg`` (:func:`ros2msg_schema`); per topic a channel, message encoding ``cdr``,
metadata ``offered_qos_profiles`` (the publishers' QoS profiles, YAML) and ``topic_type_hash``
(the type's RIHS01 hash); the messages in CDR; and, at close, the metadata record
``rosbag2`` whose ``serialized_metadata`` is the bag's metadata (rosbag2's BagMetadata,
version 9), the same document metadata.yaml holds under ``rosbag2_bagfile_information``.

The ``.msg`` texts and hashes come from the files the message packages install
(``share/<package>/msg/<Type>.msg`` and ``.json``) under a prefix of ``AMENT_PREFIX_PATH`` or the
prefix the package's Python module was installed into. A type no installed package provides
(``tf2_msgs/msg/TFMessage``: no wheel of it for Jazzy) is written from a
:class:`MessageDefinition`, its messages given as mappings of their fields; its hash is computed
as rosidl computes one (:func:`definition_hash`).
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib
import json
import os
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from mcap.writer import Writer
from mcap_ros2._dynamic import serialize_dynamic
from rclpy.duration import Duration
from rclpy.qos import QoSProfile

PRIMITIVES = {"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32", "uint32",
              "int64", "uint64", "string", "wstring"}
SEPARATOR = "=" * 80
FIELD_TYPE = re.compile(r"(?:^|\n)\s*([a-zA-Z0-9_/]+)(?:\[[^\]]*\])?\s+")
"""The type of a field (or constant) of a ``.msg`` text, as rosbag2 finds it (comments never match)."""
TYPE_NAME = re.compile(r"^([a-zA-Z0-9_]+)/(?:msg/)?([a-zA-Z0-9_]+)$")
METADATA_VERSION = 9
ROS_DISTRO = "jazzy"
"""The ROS 2 distribution of the message definitions (the ros-jazzy-* wheels of requirements.lock)."""
NEVER = 2**63 - 1
"""rosbag2's starting time of a bag without messages."""


@dataclass(frozen=True)
class MessageDefinition:
    """A message type that no installed package provides: its name (``package/msg/Type``), its
    ``.msg`` text and its fields as rosidl describes them in the type description
    (type_description_interfaces/Field: ``name`` and ``type``, without ``default_value``). Every
    type its fields use must be installed."""

    name: str
    text: str
    fields: tuple[dict[str, Any], ...]


TF_MESSAGE = MessageDefinition(
    "tf2_msgs/msg/TFMessage", "geometry_msgs/TransformStamped[] transforms\n",
    ({"name": "transforms", "type": {"type_id": 145, "capacity": 0, "string_capacity": 0,     # unbounded sequence
                                     "nested_type_name": "geometry_msgs/msg/TransformStamped"}},))
"""``/tf`` and ``/tf_static`` (tf2_msgs, geometry2 for Jazzy), which Foxglove's 3-D panel reads."""


def type_name(message_type: type) -> str:
    """``package/msg/Type`` of a generated message class (``std_msgs/msg/Float64MultiArray``), or of
    a class named and placed like one."""
    package = message_type.__module__.split(".")[0]
    return f"{package}/msg/{message_type.__name__}"


def interface_file(name: str, suffix: str) -> Path:
    """The installed ``share/<package>/msg/<Type><suffix>`` of ``package/Type`` or
    ``package/msg/Type``. FileNotFoundError if there is none."""
    match = TYPE_NAME.match(name)
    if match is None:
        raise ValueError(f"{name!r} is not a message type name (package/msg/Type)")
    package, message = match.groups()
    prefixes = [Path(p) for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    with contextlib.suppress(ImportError, TypeError, IndexError):      # not installed, or not in a prefix
        prefixes.append(Path(importlib.import_module(package).__file__).resolve().parents[4])
    for prefix in prefixes:
        path = prefix / "share" / package / "msg" / f"{message}{suffix}"
        if path.is_file():
            return path
    raise FileNotFoundError(f"no {package}/msg/{message}{suffix} under {', '.join(map(str, prefixes)) or 'any prefix'}")


def field_types(text: str, package: str) -> list[str]:
    """The message types the fields of a ``.msg`` text use, sorted, each once (primitives and
    constants left out; a bare ``Type`` is of ``package``)."""
    found = {base if "/" in base else f"{package}/{base}"
             for base in FIELD_TYPE.findall(text) if base not in PRIMITIVES}
    return sorted(found)


def ros2msg_schema(name: str, text: str | None = None) -> str:
    """The ``ros2msg`` schema of a type, as rosbag2 writes it: the type's ``.msg`` text (the
    installed one, or ``text``), then, depth first, each type it uses (sorted by name, each once)
    after a line of 80 ``=`` and a line ``MSG: package/Type``, each followed in turn by the types
    it uses first."""
    seen: set[str] = set()

    def text_and_dependencies(type_: str, own: str | None = None) -> str:
        text = interface_file(type_, ".msg").read_text() if own is None else own
        for dependency in field_types(text, TYPE_NAME.match(type_).group(1)):
            if dependency not in seen:
                seen.add(dependency)
                text += f"\n{SEPARATOR}\nMSG: {dependency}\n" + text_and_dependencies(dependency)
        return text

    return text_and_dependencies(name, text)


def type_hash(name: str) -> str:
    """The RIHS01 hash of ``package/msg/Type`` (what ROS 2 checks publishers and subscriptions
    against), from the type description the package installs."""
    hashes = json.loads(interface_file(name, ".json").read_text())["type_hashes"]
    return next(entry["hash_string"] for entry in hashes if entry["type_name"] == name)


def _hashable(description: dict[str, Any]) -> dict[str, Any]:
    """An individual type description without its fields' default values (they are not hashed)."""
    return {"type_name": description["type_name"],
            "fields": [{key: value for key, value in field.items() if key != "default_value"}
                       for field in description["fields"]]}


def definition_hash(definition: MessageDefinition) -> str:
    """The RIHS01 hash (REP-2011) of a type given by its fields, as rosidl_generator_type_description
    computes it: SHA-256 of the JSON (separators ``, `` and ``: ``, ASCII) of the type's
    description and of every type it uses, sorted by name, each as its package installs it."""
    used: dict[str, dict[str, Any]] = {}
    for field in definition.fields:
        nested = field["type"]["nested_type_name"]
        if nested:
            described = json.loads(interface_file(nested, ".json").read_text())["type_description_msg"]
            for each in (described["type_description"], *described["referenced_type_descriptions"]):
                used[each["type_name"]] = each
    document = {"type_description": _hashable({"type_name": definition.name, "fields": definition.fields}),
                "referenced_type_descriptions": [_hashable(used[name]) for name in sorted(used)]}
    text = json.dumps(document, ensure_ascii=True, allow_nan=False, separators=(", ", ": "))
    return "RIHS01_" + hashlib.sha256(text.encode()).hexdigest()


def fields(message: Any) -> Any:
    """A message as mcap-ros2-support's encoder takes it: a generated message as the mapping of
    its fields, nested alike, with arrays (numpy's, for fixed sizes) as lists and a ``byte``
    (rclpy's one-byte ``bytes``) as its number; a mapping of fields as it is."""
    if hasattr(message, "get_fields_and_field_types"):
        return {name: fields(getattr(message, name)) for name in message.get_fields_and_field_types()}
    if isinstance(message, np.ndarray):
        return message.tolist()
    if isinstance(message, (list, tuple)):
        return [fields(item) for item in message]
    if isinstance(message, bytes) and len(message) == 1:
        return message[0]
    return message


def _time(duration: Duration) -> dict[str, int]:
    seconds, nanoseconds = divmod(duration.nanoseconds, 1_000_000_000)
    return {"sec": seconds, "nsec": nanoseconds}


def qos_dict(profile: QoSProfile) -> dict[str, Any]:
    """A QoS profile as rosbag2 (metadata version 9) writes one."""
    return {"history": profile.history.name.lower(), "depth": profile.depth,
            "reliability": profile.reliability.name.lower(), "durability": profile.durability.name.lower(),
            "deadline": _time(profile.deadline), "lifespan": _time(profile.lifespan),
            "liveliness": profile.liveliness.name.lower(),
            "liveliness_lease_duration": _time(profile.liveliness_lease_duration),
            "avoid_ros_namespace_conventions": profile.avoid_ros_namespace_conventions}


class _Dumper(yaml.SafeDumper):
    """YAML as rosbag2 writes it: a mapping used twice is written twice (no anchors, no aliases)."""

    def ignore_aliases(self, data: Any) -> bool:
        return True


def _yaml(document: Any) -> str:
    return yaml.dump(document, Dumper=_Dumper, sort_keys=False, default_flow_style=False)


@dataclass
class _Topic:
    """One topic of a recording: its channel, metadata, and what has been written on it."""

    channel: int
    type: str
    offered_qos: list[dict[str, Any]]
    hash: str
    messages: int = 0

    def metadata(self, name: str) -> dict[str, Any]:
        return {"topic_metadata": {"name": name, "type": self.type, "serialization_format": "cdr",
                                   "offered_qos_profiles": self.offered_qos, "type_description_hash": self.hash},
                "message_count": self.messages}


class Recording:
    """ROS 2 messages into a recording (a ``.mcap`` file, or a bag directory for any other path),
    one channel per topic; :meth:`close` finishes it and writes its metadata."""

    def __init__(self, path: str | Path):
        path = Path(path)
        self.directory = None if path.suffix == ".mcap" else path
        if self.directory is not None:
            self.directory.mkdir(parents=True, exist_ok=True)
        self.path = path if self.directory is None else path / f"{path.name}_0.mcap"
        self._file = open(self.path, "wb")                  # noqa: SIM115 (closed in close())
        self._writer = Writer(self._file)
        self._writer.start(profile="ros2")
        self._types: dict[str, tuple[int, Callable[[Any], bytes]]] = {}
        """Per type: its schema's id and its CDR encoder (see :meth:`write`)."""
        self._topics: dict[str, _Topic] = {}
        self._first = NEVER
        self._last = 0

    def __contains__(self, topic: str) -> bool:
        """Whether ``topic`` is declared (by :meth:`add_topic` or a first :meth:`write`)."""
        return topic in self._topics

    def add_topic(self, topic: str, message_type: type | MessageDefinition,
                  offered_qos: Sequence[QoSProfile] = ()) -> None:
        """Declare ``topic``, of ``message_type`` (a message class, or the definition of a type no
        installed package provides), offered by publishers with ``offered_qos`` (rosbag2 records
        every publisher's profile; ``ros2 bag play`` offers them again). A topic first written
        without being declared is declared with no profile."""
        if topic in self._topics:
            raise ValueError(f"{topic} is declared already")
        defined = isinstance(message_type, MessageDefinition)
        name = message_type.name if defined else type_name(message_type)
        if name not in self._types:
            schema = ros2msg_schema(name, message_type.text if defined else None)
            self._types[name] = (self._writer.register_schema(name, "ros2msg", schema.encode()),
                                 serialize_dynamic(name, schema)[name])
        qos = [qos_dict(profile) for profile in offered_qos]
        digest = definition_hash(message_type) if defined else type_hash(name)
        channel = self._writer.register_channel(topic, "cdr", self._types[name][0],
                                                {"offered_qos_profiles": _yaml(qos), "topic_type_hash": digest})
        self._topics[topic] = _Topic(channel, name, qos, digest)

    def write(self, topic: str, message: Any, log_time: int, publish_time: int | None = None) -> None:
        """One message on ``topic``, logged (received) at ``log_time`` [ns] and published at
        ``publish_time`` (default the log time). ``message`` is a generated message, a mapping
        of its fields whose class has the message class's name and module, or, on a declared
        topic, a plain ``dict`` of the fields of the topic's type.

        The CDR comes from mcap-ros2-support's encoder, made from the type's schema: rclpy's
        ``serialize_message`` (rmw_fastrtps, Jazzy) returns as many bytes as its size estimate,
        which exceeds the message after an empty float64 sequence, and ``rosbags`` refuses a
        message with trailing bytes."""
        plain = type(message) is dict
        if topic not in self._topics:
            if plain:
                raise ValueError(f"{topic}: declare the topic (add_topic) before writing a dict on it")
            self.add_topic(topic, type(message))
        entry = self._topics[topic]
        if not plain and type_name(type(message)) != entry.type:
            raise ValueError(f"{topic} carries {entry.type}, not {type_name(type(message))}")
        self._writer.add_message(entry.channel, log_time, self._types[entry.type][1](fields(message)),
                                 log_time if publish_time is None else publish_time)
        entry.messages += 1
        self._first, self._last = min(self._first, log_time), max(self._last, log_time)

    def metadata(self) -> dict[str, Any]:
        """The bag's metadata as rosbag2 writes it (BagMetadata, version 9) for what has been written."""
        count = sum(entry.messages for entry in self._topics.values())
        duration = {"nanoseconds": self._last - self._first if count else 0}
        start = {"nanoseconds_since_epoch": self._first if count else NEVER}
        return {"version": METADATA_VERSION, "storage_identifier": "mcap", "duration": duration,
                "starting_time": start, "message_count": count,
                "topics_with_message_count": [entry.metadata(name) for name, entry in self._topics.items()],
                "compression_format": "", "compression_mode": "", "relative_file_paths": [self.path.name],
                "files": [{"path": self.path.name, "starting_time": start, "duration": duration,
                           "message_count": count}],
                "custom_data": None, "ros_distro": ROS_DISTRO}

    def close(self) -> None:
        """Finish the file with its ``rosbag2`` metadata record; in a bag directory, write metadata.yaml."""
        metadata = self.metadata()
        self._writer.add_metadata("rosbag2", {"serialized_metadata": _yaml(metadata)})
        self._writer.finish()
        self._file.close()
        if self.directory is not None:
            (self.directory / "metadata.yaml").write_text(_yaml({"rosbag2_bagfile_information": metadata}))
