"""The Foxglove layouts (config/foxglove/*.json, allocator_pkg.cli.foxglove_layout): each is what
the generator makes of its vehicle, every panel is placed, the heading (and the ROV's depth) has
a panel, angles are in degrees, and every topic, frame and message path it names is in a
recording of that vehicle, leading to a number (the path functions applied as Foxglove
defines them)."""

import json
import math
import re
from numbers import Number

import numpy as np
import pytest
from conftest import ROOT
from test_sim_recording import recorded

from allocator_pkg.cli.foxglove_layout import layout, main
from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.effectiveness.faults import thrust_limits
from allocator_pkg.simulation.kinematics import euler

LAYOUTS = {"dp_vessel": "dp_azimuth_failure", "bluerov2_heavy": "rov_battery_sag"}
"""Each shipped layout, with the shipped scenario whose recording it is checked against."""
PATH = re.compile(r"^(?P<topic>/[A-Za-z0-9_/]+)\.(?P<fields>[A-Za-z0-9_.@\[\]]+)$")
FIELD = re.compile(r"^(?P<name>@?[A-Za-z0-9_]+)(?:\[(?P<index>\d+)\])?$")


def shipped(vehicle: str) -> dict:
    return json.loads((ROOT / "config" / "foxglove" / f"{vehicle}.json").read_text())


def placed(node) -> list[str]:
    """The panel ids of a layout tree."""
    return [node] if isinstance(node, str) else placed(node["first"]) + placed(node["second"])


def message_paths(document: dict) -> list[str]:
    """Every message path of the Plot and State Transitions panels (reference lines left out)."""
    found = []
    for key, config in document["configById"].items():
        if key.split("!")[0] in ("Plot", "StateTransitions"):
            found += [p["value"] for p in config["paths"] if not re.fullmatch(r"-?[0-9.e+]+", p["value"])]
            if "xAxisPath" in config:
                found.append(config["xAxisPath"]["value"])
    return found


def ypr(q) -> dict[str, float]:
    """Foxglove's ``@ypr``: a unit quaternion's yaw, pitch and roll [rad], ZYX."""
    return {"yaw": math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z)),
            "pitch": math.asin(max(-1.0, min(1.0, 2.0 * (q.w * q.y - q.z * q.x)))),
            "roll": math.atan2(2.0 * (q.w * q.x + q.y * q.z), 1.0 - 2.0 * (q.x * q.x + q.y * q.y))}


FUNCTIONS = {"@ypr": ypr, "@degrees": math.degrees}
"""The message path functions the layouts use, as Foxglove's message path syntax defines them."""


def resolve(message, fields: str):
    value = message
    for part in fields.split("."):
        match = FIELD.match(part)
        assert match, part
        if match["name"].startswith("@"):
            value = FUNCTIONS[match["name"]](value)
        else:
            value = value[match["name"]] if isinstance(value, dict) else getattr(value, match["name"])
        if match["index"] is not None:
            value = value[int(match["index"])]
    return value


@pytest.mark.parametrize("vehicle", sorted(LAYOUTS))
def test_the_shipped_layout_is_the_generated_one(vehicle, capsys):
    assert shipped(vehicle) == layout(load_vehicle(ROOT / "config" / f"{vehicle}.yaml"))
    assert main([str(ROOT / "config" / f"{vehicle}.yaml")]) == 0
    assert json.loads(capsys.readouterr().out) == shipped(vehicle)


@pytest.mark.parametrize("vehicle", sorted(LAYOUTS))
def test_every_panel_is_placed_once_and_the_thrust_limits_are_the_vehicles(vehicle):
    document = shipped(vehicle)
    assert sorted(placed(document["layout"])) == sorted(document["configById"])
    assert {"globalVariables", "userNodes", "playbackConfig"} <= set(document)
    config = load_vehicle(ROOT / "config" / f"{vehicle}.yaml")
    low, high = thrust_limits(config, None)
    lines = {float(p["value"]) for p in document["configById"]["Plot!thrust"]["paths"] if p["value"][0] != "/"}
    assert lines == {float(v) for v in np.concatenate([low, high]) if v != 0.0}
    thrust = [p["value"] for p in document["configById"]["Plot!thrust"]["paths"] if p["value"][0] == "/"]
    assert thrust == [f"/thruster_commands.thrust[{i}]" for i in range(len(config.names))]
    assert ("Plot!azimuth" in document["configById"]) == any(a.rotatable for a in config.actuators)
    assert ("Plot!depth" in document["configById"]) == ("heave" in config.dofs)
    heading = [p["value"] for p in document["configById"]["Plot!heading"]["paths"]]
    assert heading == ["/odometry.pose.pose.orientation.@ypr.yaw.@degrees",
                       "/setpoint.pose.orientation.@ypr.yaw.@degrees"]


def test_angles_are_in_degrees_as_in_the_figures():
    document = shipped("dp_vessel")
    azimuth = document["configById"]["Plot!azimuth"]
    assert azimuth["foxglovePanelTitle"] == "azimuth [deg]"
    assert [p["value"] for p in azimuth["paths"]] == ["/thruster_commands.azimuth[0].@degrees",
                                                      "/thruster_commands.azimuth[1].@degrees"]
    assert all(p["label"].endswith("[deg]") for p in azimuth["paths"])
    depth = shipped("bluerov2_heavy")["configById"]["Plot!depth"]
    assert [p["value"] for p in depth["paths"]] == ["/odometry.pose.pose.position.z", "/setpoint.pose.position.z"]


@pytest.mark.slow
@pytest.mark.parametrize("vehicle", sorted(LAYOUTS))
def test_every_topic_frame_and_path_of_the_layout_is_in_a_recording(vehicle, tmp_path_factory):
    document = shipped(vehicle)
    _, _, messages = recorded(LAYOUTS[vehicle], tmp_path_factory)
    scene = document["configById"]["3D!vehicle"]
    assert set(scene["topics"]) <= set(messages)
    frames = {name for message in messages["/tf"] for t in message.transforms
              for name in (t.header.frame_id, t.child_frame_id)}
    assert scene["followTf"] in frames
    assert {key.removeprefix("frame:") for key in scene["transforms"]} <= frames
    assert {layer["frameId"] for layer in scene["layers"].values()} <= frames
    summary = document["configById"]["DiagnosticSummary!diagnostics"]["topicToRender"]
    assert messages[summary][0].__msgtype__ == "diagnostic_msgs/msg/DiagnosticArray"
    paths = message_paths(document)
    assert len(paths) > 10
    for path in paths:
        match = PATH.match(path)
        assert match and match["topic"] in messages, path
        value = resolve(messages[match["topic"]][-1], match["fields"])
        assert isinstance(value, (Number, np.number, bool, np.bool_)), (path, value)
    pose = messages["/odometry"][-1].pose.pose
    heading = math.degrees(euler(pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w)[2])
    assert resolve(messages["/odometry"][-1], "pose.pose.orientation.@ypr.yaw.@degrees") == pytest.approx(heading)
