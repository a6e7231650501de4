"""Actuator geometry from a URDF robot description, parsed with the standard library.

The convention is Gazebo's Thruster system: each actuator has a link (``actuators.<name>.link``,
by default the actuator's name) that hangs on a revolute or continuous joint at the point
where its force acts. For a fixed thruster that joint is the propeller's, and the thrust
direction is its axis; for an azimuth thruster it is the joint that turns the unit, whose axis
must be the body's z (``azimuth``) or y (``azimuth_vertical``); for a rudder or fin only the
point is taken (its lift direction stays in the params file). Every joint between
``base_frame`` and that joint must be fixed, so that the geometry does not move.

The URDF's coordinates are those of ``base_frame``, of the convention ``frame`` (a REP-103
``base_link`` is FLU); they are converted to the library's FRD. The params file keeps the
limits and command maps, and must not give a position, nor a fixed thruster's direction.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ElementTree
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..vehicle.config import AZIMUTH, AZIMUTH_VERTICAL, FIXED, ConfigError
from ..vehicle.frames import vector_between
from . import schema

MOVING = ("revolute", "continuous", "prismatic", "floating", "planar")
ROTATION_AXES = {AZIMUTH: np.array([0.0, 0.0, 1.0]), AZIMUTH_VERTICAL: np.array([0.0, 1.0, 0.0])}
PARALLEL = 1e-3
"""A rotatable thruster's joint axis counts as the body axis when the cross product is below this."""

SOURCE = "robot_description"


@dataclass(frozen=True)
class Joint:
    """One URDF joint: its parent and child links, the child frame in the parent's, its axis."""

    name: str
    type: str
    parent: str
    child: str
    pose: np.ndarray
    axis: np.ndarray


def _numbers(text: str | None, default: tuple[float, float, float]) -> np.ndarray:
    if text is None:
        return np.array(default)
    values = [float(v) for v in text.split()]
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise ValueError(f"expected three finite numbers, got '{text}'")
    return np.array(values)


def pose(xyz: np.ndarray, rpy: np.ndarray) -> np.ndarray:
    """4 x 4 transform of a URDF origin: translation xyz, rotation Rz(yaw) Ry(pitch) Rx(roll)."""
    roll, pitch, yaw = rpy
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch),
                              math.cos(yaw), math.sin(yaw))
    result = np.eye(4)
    result[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                      [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                      [-sp, cp * sr, cp * cr]]
    result[:3, 3] = xyz
    return result


def joints(text: str) -> dict[str, Joint]:
    """The joints of a URDF, by child link. Raises ValueError with what is wrong."""
    try:
        root = ElementTree.fromstring(text)
    except ElementTree.ParseError as error:
        raise ValueError(f"not valid XML: {error}") from error
    if root.tag != "robot":
        raise ValueError(f"the root element is <{root.tag}>, not <robot>")
    found: dict[str, Joint] = {}
    for element in root.iter("joint"):
        name = element.get("name", "?")
        parent, child = element.find("parent"), element.find("child")
        if parent is None or child is None:
            raise ValueError(f"joint '{name}' needs <parent link=...> and <child link=...>")
        origin, axis = element.find("origin"), element.find("axis")
        try:
            xyz = _numbers(origin.get("xyz") if origin is not None else None, (0.0, 0.0, 0.0))
            rpy = _numbers(origin.get("rpy") if origin is not None else None, (0.0, 0.0, 0.0))
            direction = _numbers(axis.get("xyz") if axis is not None else None, (1.0, 0.0, 0.0))
        except ValueError as error:
            raise ValueError(f"joint '{name}': {error}") from error
        norm = float(np.linalg.norm(direction))
        if norm == 0.0:
            raise ValueError(f"joint '{name}': the axis is the zero vector")
        found[child.get("link", "")] = Joint(name=name, type=element.get("type", ""), parent=parent.get("link", ""),
                                             child=child.get("link", ""), pose=pose(xyz, rpy), axis=direction / norm)
    return found


def link_in_base(by_child: Mapping[str, Joint], base_frame: str, link: str) -> tuple[np.ndarray, Joint]:
    """The link's frame in base_frame (4 x 4) and the joint it hangs on; every joint above that
    one, up to base_frame, must be fixed. Raises ValueError with what is wrong."""
    if link not in by_child:
        raise ValueError(f"no joint has link '{link}' as its child" + (" (it is base_frame)" if link == base_frame
                                                                        else ""))
    own = by_child[link]
    transform = own.pose
    current = own.parent
    while current != base_frame:
        joint = by_child.get(current)
        if joint is None:
            raise ValueError(f"link '{link}' is not below base_frame '{base_frame}'")
        if joint.type in MOVING:
            raise ValueError(f"joint '{joint.name}' between '{base_frame}' and '{link}' is {joint.type}: only "
                             "fixed joints may lie between them")
        transform = joint.pose @ transform
        current = joint.parent
    return transform, own


def geometry_parameters(text: str, parameters: Mapping[str, Any]) -> dict[str, list[float]]:
    """The positions (and fixed thrusters' directions) of the actuators named in ``parameters``
    (flat ROS parameters), from the URDF ``text``, as flat parameters in FRD. Raises ConfigError
    naming each actuator's problem; keys the params file sets that the URDF supplies are one."""
    base_frame = parameters.get("base_frame", schema.NODE_KEY_BY_NAME["base_frame"].default)
    frame = parameters.get("frame", schema.NODE_KEY_BY_NAME["frame"].default)
    try:
        by_child = joints(text)
    except ValueError as error:
        raise ConfigError([(SOURCE, str(error))]) from error
    names = parameters.get("actuators.names")
    if not isinstance(names, list):
        return {}
    problems: list[tuple[str, str]] = []
    result: dict[str, list[float]] = {}
    for name in names:
        kind = parameters.get(schema.actuator_parameter(name, "type"))
        supplied = ["position"] + (["direction"] if kind == FIXED else [])
        for key in supplied:
            if schema.actuator_parameter(name, key) in parameters:
                problems.append((schema.actuator_parameter(name, key), "comes from the robot description "
                                 "(geometry_source: robot_description); remove it from the params file"))
        link = parameters.get(schema.actuator_parameter(name, "link"), name)
        if not isinstance(link, str):
            continue
        try:
            transform, joint = link_in_base(by_child, base_frame, link)
        except ValueError as error:
            problems.append((schema.actuator_parameter(name, "link"), str(error)))
            continue
        axis = vector_between(transform[:3, :3] @ joint.axis, frame)
        result[schema.actuator_parameter(name, "position")] = _rounded(vector_between(transform[:3, 3], frame))
        if kind == FIXED:
            if joint.type not in ("revolute", "continuous"):
                problems.append((schema.actuator_parameter(name, "link"), f"hangs on the {joint.type or 'untyped'} "
                                 f"joint '{joint.name}': a thruster needs a revolute or continuous joint whose "
                                 "axis is its thrust direction"))
            result[schema.actuator_parameter(name, "direction")] = _rounded(axis)
        elif kind in ROTATION_AXES and np.linalg.norm(np.cross(axis, ROTATION_AXES[kind])) > PARALLEL:
            problems.append((schema.actuator_parameter(name, "link"), f"the axis of joint '{joint.name}' is "
                             f"{_rounded(axis)} in FRD; an {kind} thruster turns about "
                             f"{ROTATION_AXES[kind].tolist()}"))
    if problems:
        raise ConfigError(problems)
    return result


def _rounded(values: np.ndarray) -> list[float]:
    """Values without the last bits of rounding noise of the transforms (and no -0.0)."""
    return [round(float(v), 12) + 0.0 for v in values]
