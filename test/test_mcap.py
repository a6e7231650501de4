"""allocator-ctl echo --mcap: the wrench, commands and status of a running node recorded as MCAP
and read back with mcap_ros2's decoder; the ros2msg schema text as ros2 bag writes it."""

import io

from conftest import ROOT

from allocator_pkg.cli.recording import SEPARATOR, field_types, ros2msg_schema

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


def test_a_schema_is_the_msg_text_then_each_dependency_once():
    text = ros2msg_schema("allocator_msgs/AllocationStatus")
    own = (ROOT / "allocator_msgs" / "msg" / "AllocationStatus.msg").read_text().rstrip("\n")
    assert text.split("\n" + SEPARATOR + "\n")[0] == own
    dependencies = [part.split("\n", 1)[0] for part in text.split(SEPARATOR + "\n")[1:]]
    assert dependencies == ["MSG: std_msgs/Header", "MSG: geometry_msgs/Wrench", "MSG: builtin_interfaces/Time",
                            "MSG: geometry_msgs/Vector3"]


def test_field_types_skip_primitives_constants_and_bounds():
    text = "uint8 A=1  # constant\nstring<=8 name\nint32[<=4] v\nHeader h\ngeometry_msgs/Wrench[] w  # list\n"
    assert field_types(text, "std_msgs") == ["std_msgs/Header", "geometry_msgs/Wrench"]


def test_echo_records_wrench_commands_and_status_that_mcap_ros2_reads_back(harness, tmp_path):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    from allocator_pkg.cli.ctl import Controller, Echo
    from allocator_pkg.cli.recording import Recording

    class Counted(Recording):
        def write(self, topic, message, log_time, publish_time=None):
            super().write(topic, message, log_time, publish_time)
            self.written[topic] = self.written.get(topic, 0) + 1

    path = tmp_path / "session.mcap"
    recording = Counted(path)
    recording.written = {}
    echo = Echo(Controller(harness.probe), io.StringIO(), rate=0.0, recording=recording)
    harness.spin_until(lambda: all(s.get_publisher_count() for s in (echo._status, echo._commands))
                       and echo._wrench.get_publisher_count() > 0)
    before = len(harness.commands)
    harness.send_wrench([100.0, 20.0, 0.0, 0.0, 0.0, 10.0])
    harness.tick(3)
    sent = len(harness.commands)
    harness.spin_until(lambda: recording.written.get("/thruster_commands", 0) >= sent - before
                       and recording.written.get("/allocation_status", 0) >= sent - before)
    recording.close()

    decoded = {}
    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros2"
        for schema, channel, _, message in reader.iter_decoded_messages():
            assert schema.encoding == "ros2msg" and channel.message_encoding == "cdr"
            decoded.setdefault((channel.topic, schema.name), []).append(message)
    assert set(decoded) == {("/wrench_command", "geometry_msgs/Wrench"),
                            ("/thruster_commands", "allocator_msgs/ThrusterCommands"),
                            ("/allocation_status", "allocator_msgs/AllocationStatus")}
    wrench = decoded[("/wrench_command", "geometry_msgs/Wrench")][-1]
    assert (wrench.force.x, wrench.force.y, wrench.torque.z) == (100.0, 20.0, 10.0)
    commands = decoded[("/thruster_commands", "allocator_msgs/ThrusterCommands")]
    assert len(commands) == sent - before == 3
    last = harness.commands[sent - 1]
    assert commands[-1].name == list(last.name)
    assert list(commands[-1].thrust) == list(last.thrust)
    assert list(commands[-1].azimuth) == list(last.azimuth)
    assert (commands[-1].header.stamp.sec, commands[-1].header.stamp.nanosec) == (last.header.stamp.sec,
                                                                                  last.header.stamp.nanosec)
    status = decoded[("/allocation_status", "allocator_msgs/AllocationStatus")][-1]
    assert status.requested.force.x == 100.0 and status.solver_status == harness.status[sent - 1].solver_status
    assert list(status.at_thrust_limit) == list(harness.status[sent - 1].at_thrust_limit)
