"""Recordings (allocator_pkg.ros.recording) as rosbag2 writes them: ``rosbags`` (the pure-Python
rosbag2 reader) and mcap-ros2-support decode every message of every type the node and the
simulator publish, field for field, from the definitions stored in the file; the schema text,
type hashes, QoS profiles and bag metadata are rosbag2's; allocator-ctl echo --mcap records what
a running node sends.

:func:`rosbags_messages` is the reader the end-to-end tests of ``allocator-sim`` and
``allocator-ctl echo`` use on what those tools record."""

import importlib
import io
import math
from pathlib import Path

import pytest
import yaml
from conftest import ROOT
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rosbags.highlevel import AnyReader
from rosbags.rosbag2 import Reader
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from rosidl_parser.definition import AbstractNestedType, AbstractString, Array, BoundedSequence, NamespacedType

from allocator_pkg.ros.recording import (
    NEVER,
    SEPARATOR,
    TF_MESSAGE,
    MessageDefinition,
    Recording,
    definition_hash,
    field_types,
    fields,
    interface_file,
    ros2msg_schema,
    type_hash,
    type_name,
)

TYPES = [("nav_msgs.msg", "Odometry"), ("geometry_msgs.msg", "Wrench"), ("geometry_msgs.msg", "WrenchStamped"),
         ("geometry_msgs.msg", "PoseStamped"), ("allocator_msgs.msg", "ThrusterCommands"),
         ("allocator_msgs.msg", "AllocationStatus"), ("allocator_msgs.msg", "ActuatorFault"),
         ("std_msgs.msg", "Float64MultiArray"), ("std_msgs.msg", "Float64"), ("std_msgs.msg", "String"),
         ("sensor_msgs.msg", "BatteryState"), ("rosgraph_msgs.msg", "Clock"),
         ("visualization_msgs.msg", "MarkerArray"), ("diagnostic_msgs.msg", "DiagnosticArray")]
"""Every message type the node, allocator-ctl and allocator-sim publish or record."""


def message_class(module: str, name: str) -> type:
    return getattr(importlib.import_module(module), name)


def rosbags_messages(path: Path) -> dict[str, list]:
    """Every message of a recording (a ``.mcap`` file or a bag directory), topic by topic in log
    order, as ``rosbags`` decodes it from the definitions stored in the recording."""
    found: dict[str, list] = {}
    with AnyReader([Path(path)]) as reader:
        for connection, _, data in reader.messages():
            found.setdefault(connection.topic, []).append(reader.deserialize(data, connection.msgtype))
    return found


def filled(kind: type, seed: int):
    """A message of ``kind`` whose every field, nested ones too, holds a value unlike its default
    (sequences two long, fixed arrays full), drawn from ``seed``."""
    message = kind()
    for offset, (name, slot) in enumerate(zip(kind.get_fields_and_field_types(), kind.SLOT_TYPES)):
        setattr(message, name, _value(slot, seed + 7 * offset))
    return message


def _value(slot, seed: int):
    if isinstance(slot, AbstractNestedType):
        size = slot.size if isinstance(slot, Array) else 2
        if isinstance(slot, BoundedSequence):
            size = min(size, slot.maximum_size)
        return [_value(slot.value_type, seed + k) for k in range(size)]
    if isinstance(slot, NamespacedType):
        return filled(message_class(".".join(slot.namespaces), slot.name), seed)
    if isinstance(slot, AbstractString):
        return f"text {seed}"
    if slot.typename == "boolean":
        return True
    if slot.typename in ("float", "double"):
        return seed + 0.25
    if slot.typename == "octet":
        return bytes([1 + seed % 250])
    return 1 + seed % 100                         # integers, in range of every width


def differences(written, read, where: str = "") -> list[str]:
    """Where a decoded message differs from the one written (empty: every field equal)."""
    if hasattr(written, "get_fields_and_field_types"):
        if read.__msgtype__ != type_name(type(written)):
            return [f"{where}: {read.__msgtype__} is not {type_name(type(written))}"]
        return [found for name in written.get_fields_and_field_types()
                for found in differences(getattr(written, name), getattr(read, name), f"{where}.{name}")]
    if not isinstance(written, (str, bytes)) and hasattr(written, "__len__"):
        if len(written) != len(read):
            return [f"{where}: {len(read)} items, not {len(written)}"]
        return [found for i, (a, b) in enumerate(zip(written, read)) for found in differences(a, b, f"{where}[{i}]")]
    if isinstance(written, bytes):
        written = written[0]
    if isinstance(written, float) and math.isnan(written) and math.isnan(read):
        return []
    return [] if written == read else [f"{where}: {read!r}, not {written!r}"]


@pytest.fixture(scope="module")
def samples():
    """Three messages of every type, on a topic of its own: two filled, the status with a NaN
    voltage, then a default one (empty sequences and strings)."""
    messages = {f"/{name.lower()}": [filled(message_class(module, name), 3), filled(message_class(module, name), 11),
                                     message_class(module, name)()] for module, name in TYPES}
    messages["/allocationstatus"][1].voltage = math.nan
    return messages


def record(path: Path, samples: dict[str, list], qos: dict[str, list[QoSProfile]] | None = None) -> Recording:
    recording = Recording(path)
    for topic, profiles in (qos or {}).items():
        recording.add_topic(topic, type(samples[topic][0]), profiles)
    for i, topic in enumerate(samples):
        for k, message in enumerate(samples[topic]):
            recording.write(topic, message, log_time=1_000_000_000 + 1000 * k + i, publish_time=500 + i)
    recording.close()
    return recording


def test_a_schema_is_the_msg_text_then_each_dependency_depth_first_once():
    text = ros2msg_schema("allocator_msgs/msg/AllocationStatus")
    parts = text.split("\n" + SEPARATOR + "\n")
    assert parts[0] == (ROOT / "allocator_msgs" / "msg" / "AllocationStatus.msg").read_text()
    assert [part.split("\n", 1)[0] for part in parts[1:]] == [
        "MSG: geometry_msgs/Wrench", "MSG: geometry_msgs/Vector3", "MSG: std_msgs/Header",
        "MSG: builtin_interfaces/Time"]
    assert parts[2] == "MSG: geometry_msgs/Vector3\n" + interface_file("geometry_msgs/Vector3", ".msg").read_text()
    assert text == ros2msg_schema("allocator_msgs/AllocationStatus")


def test_field_types_skip_primitives_constants_bounds_and_comments():
    text = ("uint8 A=1  # constant\nstring<=8 name\nint32[<=4] v\nHeader h\n# geometry_msgs/Point p\n"
            "geometry_msgs/Wrench[] w  # list\nstd_msgs/Header again\n")
    assert field_types(text, "std_msgs") == ["geometry_msgs/Wrench", "std_msgs/Header"]


@pytest.mark.parametrize(("module", "name"), TYPES)
def test_rosbags_hashes_each_stored_definition_to_the_types_own_hash(module, name):
    """The schema is the whole definition: from it alone rosbags computes the RIHS01 hash ROS 2
    gave the type (a missing or altered field, constant or dependency would change it)."""
    kind = type_name(message_class(module, name))
    store = get_typestore(Stores.EMPTY)
    store.register(get_types_from_msg(ros2msg_schema(kind), kind))
    assert store.hash_rihs01(kind) == type_hash(kind)
    assert type_hash(kind).startswith("RIHS01_")


@pytest.mark.parametrize("name", ["run.mcap", "bag"])
def test_rosbags_decodes_every_field_of_every_type(tmp_path, samples, name):
    path = tmp_path / name
    record(path, samples)
    if name == "bag":
        assert sorted(p.name for p in path.iterdir()) == ["bag_0.mcap", "metadata.yaml"]
    decoded = rosbags_messages(path)
    assert set(decoded) == set(samples)
    for topic, messages in samples.items():
        assert len(decoded[topic]) == len(messages)
        for written, read in zip(messages, decoded[topic]):
            assert differences(written, read, topic) == []


def test_mcap_ros2_decodes_them_too(tmp_path, samples):
    record(tmp_path / "run.mcap", samples)
    decoded: dict[str, list] = {}
    with open(tmp_path / "run.mcap", "rb") as stream:
        for _, channel, _, message in make_reader(stream, decoder_factories=[DecoderFactory()]).iter_decoded_messages():
            decoded.setdefault(channel.topic, []).append(message)
    odometry = samples["/odometry"][1]
    assert list(decoded["/odometry"][1].pose.covariance) == list(odometry.pose.covariance)
    commands = samples["/thrustercommands"][0]
    assert list(decoded["/thrustercommands"][0].thrust) == list(commands.thrust)
    assert decoded["/thrustercommands"][0].name == list(commands.name)


def test_the_file_has_rosbag2s_schemas_channels_and_metadata_record(tmp_path, samples):
    best_effort = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
    recording = record(tmp_path / "run.mcap", samples, {"/wrench": [best_effort, QoSProfile(depth=10)]})
    with open(tmp_path / "run.mcap", "rb") as stream:
        reader = make_reader(stream)
        assert reader.get_header().profile == "ros2"
        summary = reader.get_summary()
        records = {record.name: record.metadata for record in reader.iter_metadata()}
    schemas = {schema.name: schema for schema in summary.schemas.values()}
    assert set(schemas) == {type_name(message_class(module, name)) for module, name in TYPES}
    assert all(schema.encoding == "ros2msg" and schema.data.decode() == ros2msg_schema(name)
               for name, schema in schemas.items())
    channels = {channel.topic: channel for channel in summary.channels.values()}
    wrench = channels["/wrench"]
    assert wrench.message_encoding == "cdr"
    assert summary.schemas[wrench.schema_id].name == "geometry_msgs/msg/Wrench"
    assert wrench.metadata["topic_type_hash"] == type_hash("geometry_msgs/msg/Wrench")
    profiles = yaml.safe_load(wrench.metadata["offered_qos_profiles"])
    assert [(p["history"], p["depth"], p["reliability"], p["durability"]) for p in profiles] == [
        ("keep_last", 1, "best_effort", "volatile"), ("keep_last", 10, "reliable", "volatile")]
    assert profiles[0]["deadline"] == {"sec": 0, "nsec": 0} and profiles[0]["liveliness"] == "system_default"
    assert yaml.safe_load(channels["/odometry"].metadata["offered_qos_profiles"]) == []
    assert yaml.safe_load(records["rosbag2"]["serialized_metadata"]) == recording.metadata()


def test_the_metadata_are_true_and_rosbags_reads_them(tmp_path, samples):
    best_effort = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
    record(tmp_path / "bag", samples, {"/wrench": [best_effort]})
    metadata = yaml.safe_load((tmp_path / "bag" / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    count = 3 * len(TYPES)
    last = 1_000_000_000 + 2000 + len(TYPES) - 1
    assert (metadata["version"], metadata["storage_identifier"], metadata["ros_distro"]) == (9, "mcap", "jazzy")
    assert metadata["message_count"] == count
    assert metadata["starting_time"] == {"nanoseconds_since_epoch": 1_000_000_000}
    assert metadata["duration"] == {"nanoseconds": last - 1_000_000_000}
    assert metadata["relative_file_paths"] == ["bag_0.mcap"]
    assert metadata["files"] == [{"path": "bag_0.mcap", "starting_time": metadata["starting_time"],
                                  "duration": metadata["duration"], "message_count": count}]
    topics = {t["topic_metadata"]["name"]: t for t in metadata["topics_with_message_count"]}
    assert {name: t["message_count"] for name, t in topics.items()} == dict.fromkeys(samples, 3)
    assert topics["/clock"]["topic_metadata"]["type"] == "rosgraph_msgs/msg/Clock"
    assert topics["/clock"]["topic_metadata"]["type_description_hash"] == type_hash("rosgraph_msgs/msg/Clock")
    assert topics["/wrench"]["topic_metadata"]["offered_qos_profiles"][0]["reliability"] == "best_effort"
    with Reader(tmp_path / "bag") as reader:
        assert reader.message_count == count and reader.start_time == 1_000_000_000
        assert reader.end_time == last + 1 and reader.ros_distro == "jazzy"
        assert {topic: info.msgcount for topic, info in reader.topics.items()} == dict.fromkeys(samples, 3)
        assert {c.topic: c.msgtype for c in reader.connections}["/odometry"] == "nav_msgs/msg/Odometry"
        wrench = next(c for c in reader.connections if c.topic == "/wrench")
        assert [q.depth for q in wrench.ext.offered_qos_profiles] == [1]
        assert sum(1 for _ in reader.messages()) == count      # storage channels match metadata.yaml's


def test_an_empty_recording_opens_with_no_messages(tmp_path):
    recording = Recording(tmp_path / "empty")
    recording.close()
    assert recording.metadata()["starting_time"] == {"nanoseconds_since_epoch": NEVER}
    assert rosbags_messages(tmp_path / "empty") == {}
    assert rosbags_messages(tmp_path / "empty" / "empty_0.mcap") == {}


def test_a_mapping_of_the_fields_records_as_the_message_itself(tmp_path, samples):
    odometry = samples["/odometry"][0]
    kind = type(odometry)
    mapping = type(kind.__name__, (dict,), {"__module__": kind.__module__})(fields(odometry))
    for path, message in ((tmp_path / "a.mcap", odometry), (tmp_path / "b.mcap", mapping)):
        recording = Recording(path)
        recording.write("/odometry", message, 5)
        recording.close()
    assert differences(odometry, rosbags_messages(tmp_path / "b.mcap")["/odometry"][0]) == []
    with open(tmp_path / "a.mcap", "rb") as a, open(tmp_path / "b.mcap", "rb") as b:
        assert next(make_reader(a).iter_messages())[2].data == next(make_reader(b).iter_messages())[2].data


def test_a_topic_is_declared_once_and_keeps_its_type(tmp_path, samples):
    recording = Recording(tmp_path / "run.mcap")
    assert "/wrench" not in recording
    recording.write("/wrench", samples["/wrench"][0], 1)
    assert "/wrench" in recording
    with pytest.raises(ValueError, match="geometry_msgs/msg/Wrench, not geometry_msgs/msg/WrenchStamped"):
        recording.write("/wrench", samples["/wrenchstamped"][0], 2)
    with pytest.raises(ValueError, match="/wrench is declared already"):
        recording.add_topic("/wrench", type(samples["/wrench"][0]))
    recording.close()


def tf_message(seed: int) -> dict:
    """The fields of a tf2_msgs/msg/TFMessage of two transforms, every field drawn from ``seed``."""
    def transform(k: int) -> dict:
        value = seed + 10 * k
        return {"header": {"stamp": {"sec": value, "nanosec": value + 1}, "frame_id": f"parent {value}"},
                "child_frame_id": f"child {value}",
                "transform": {"translation": {"x": value + 0.25, "y": value + 0.5, "z": value + 0.75},
                              "rotation": {"x": 0.5, "y": -0.5, "z": 0.5, "w": value + 0.125}}}
    return {"transforms": [transform(0), transform(1)]}


def test_a_defined_type_hashes_as_ros_2_hashes_it():
    """TFMessage from its definition: the hash and schema rosbags computes for Jazzy's own
    tf2_msgs (a definition of its own) and from the stored schema; a changed field changes it."""
    jazzy = get_typestore(Stores.ROS2_JAZZY)
    assert definition_hash(TF_MESSAGE) == jazzy.hash_rihs01("tf2_msgs/msg/TFMessage")
    store = get_typestore(Stores.EMPTY)
    store.register(get_types_from_msg(ros2msg_schema(TF_MESSAGE.name, TF_MESSAGE.text), TF_MESSAGE.name))
    assert store.hash_rihs01(TF_MESSAGE.name) == definition_hash(TF_MESSAGE)
    bounded = dict(TF_MESSAGE.fields[0], type={**TF_MESSAGE.fields[0]["type"], "type_id": 97, "capacity": 4})
    assert definition_hash(MessageDefinition(TF_MESSAGE.name, TF_MESSAGE.text, (bounded,))) != \
        definition_hash(TF_MESSAGE)


@pytest.mark.parametrize("name", ["run.mcap", "bag"])
def test_a_defined_type_records_from_mappings_and_rosbags_decodes_it(tmp_path, name):
    recording = Recording(tmp_path / name)
    recording.add_topic("/tf", TF_MESSAGE)
    written = [tf_message(3), tf_message(20), {"transforms": []}]
    for k, message in enumerate(written):
        recording.write("/tf", message, 1000 + k)
    recording.close()
    decoded = rosbags_messages(tmp_path / name)["/tf"]
    assert [m.__msgtype__ for m in decoded] == ["tf2_msgs/msg/TFMessage"] * 3
    for message, read in zip(written, decoded):
        assert len(read.transforms) == len(message["transforms"])
        for fields_, transform in zip(message["transforms"], read.transforms):
            assert (transform.header.stamp.sec, transform.header.stamp.nanosec, transform.header.frame_id,
                    transform.child_frame_id) == (fields_["header"]["stamp"]["sec"],
                                                  fields_["header"]["stamp"]["nanosec"],
                                                  fields_["header"]["frame_id"], fields_["child_frame_id"])
            assert (transform.transform.translation.y, transform.transform.rotation.w) == (
                fields_["transform"]["translation"]["y"], fields_["transform"]["rotation"]["w"])
    path = tmp_path / name if name.endswith(".mcap") else tmp_path / name / f"{name}_0.mcap"
    with open(path, "rb") as stream:
        summary = make_reader(stream).get_summary()
    channel = next(iter(summary.channels.values()))
    assert channel.metadata["topic_type_hash"] == definition_hash(TF_MESSAGE)
    assert summary.schemas[channel.schema_id].data.decode() == ros2msg_schema(TF_MESSAGE.name, TF_MESSAGE.text)
    assert recording.metadata()["topics_with_message_count"][0]["topic_metadata"]["type"] == TF_MESSAGE.name


def test_a_mapping_goes_on_a_declared_topic_only(tmp_path):
    recording = Recording(tmp_path / "run.mcap")
    with pytest.raises(ValueError, match="declare the topic"):
        recording.write("/tf", tf_message(1), 1)
    recording.close()


def test_echo_records_wrench_commands_and_status_that_rosbags_reads_back(harness, tmp_path):
    from allocator_pkg.ros.echo import Echo
    from allocator_pkg.ros.node_client import Controller

    class Counted(Recording):
        def write(self, topic, message, log_time, publish_time=None):
            super().write(topic, message, log_time, publish_time)
            self.written[topic] = self.written.get(topic, 0) + 1

    path = tmp_path / "session.mcap"
    recording = Counted(path)
    recording.written = {}
    echo = Echo(Controller(harness.probe), io.StringIO(), rate=0.0, recording=recording)
    harness.spin_until(lambda: all(s.get_publisher_count() for s in (echo._status, echo._commands))
                       and echo._wrench is not None and echo._wrench.get_publisher_count() > 0)
    before = len(harness.commands)
    harness.send_wrench([100.0, 20.0, 0.0, 0.0, 0.0, 10.0])
    harness.tick(3)
    sent = len(harness.commands)
    namespace = harness.node.get_namespace()                  # the harness's run: its topics are in it
    wrench_topic, commands_topic, status_topic = (f"{namespace}/{name}" for name in (
        "wrench_command", "thruster_commands", "allocation_status"))
    harness.spin_until(lambda: recording.written.get(commands_topic, 0) >= sent - before
                       and recording.written.get(status_topic, 0) >= sent - before)
    recording.close()

    decoded = rosbags_messages(path)
    assert set(decoded) == {wrench_topic, commands_topic, status_topic}
    assert decoded[wrench_topic][-1].__msgtype__ == "geometry_msgs/msg/Wrench"
    wrench = decoded[wrench_topic][-1]
    assert (wrench.force.x, wrench.force.y, wrench.torque.z) == (100.0, 20.0, 10.0)
    commands = decoded[commands_topic]
    assert len(commands) == sent - before == 3
    assert differences(harness.commands[sent - 1], commands[-1]) == []
    status = decoded[status_topic]
    assert differences(harness.status[sent - 1], status[-1]) == []
    assert status[-1].requested.force.x == 100.0
