"""Foxglove layouts of an ``allocator-sim`` recording (``config/foxglove/<vehicle>.json``), made
from the vehicle: a 3-D panel following ``base_link`` over a grid in ``map`` with the node's
thrust markers and the set-point; the track (north against east); the heading and its
set-point [deg]; the depth and its set-point [m] (a vehicle that controls heave); each
actuator's thrust against its limits (at the nominal voltage for thrust tables measured at
several voltages, with the supply voltage beside); the azimuth angles [deg]; the saturation
flags; the unallocated wrench in the controlled DOFs; the diagnostics. Angles in degrees as the
figures of ``allocator-sim`` give them, through the message path functions ``@ypr`` (a
quaternion's yaw, pitch and roll, ZYX as the odometry's attitude) and ``@degrees``. Only topics
and fields the recording holds (:mod:`..ros.sim_recording`).

    python -m allocator_pkg.cli.foxglove_layout config/dp_vessel.yaml > config/foxglove/dp_vessel.json

The file is Foxglove's layout export: ``configById`` (one configuration per panel, keyed
``<panel type>!<id>``), ``layout`` (the panels' splits), ``globalVariables``, ``userNodes``
and ``playbackConfig``.
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

import numpy as np

from ..configuration.parameters import load_vehicle
from ..effectiveness.faults import thrust_limits
from ..ros.sim_recording import BODY, TOPICS, WORLD
from ..simulation.report.style import LIMIT_COLOUR, PALETTE
from ..vehicle.config import Vehicle

COMMANDS, STATUS = "/thruster_commands", "/allocation_status"
HEADING = ".pose.pose.orientation.@ypr.yaw.@degrees"
"""The heading [deg] of an odometry's attitude (NED to FRD, ZYX)."""
UNALLOCATED = {"surge": ("force.x", "N"), "sway": ("force.y", "N"), "heave": ("force.z", "N"),
               "roll": ("torque.x", "N m"), "pitch": ("torque.y", "N m"), "yaw": ("torque.z", "N m")}


def _series(value: str, label: str, colour: str | None = None) -> dict[str, Any]:
    series = {"value": value, "enabled": True, "timestampMethod": "receiveTime", "label": label}
    return series if colour is None else {**series, "color": colour}


def _plot(title: str, paths: list[dict[str, Any]], **more: Any) -> dict[str, Any]:
    return {"foxglovePanelTitle": title, "paths": paths, "showLegend": True, "legendDisplay": "floating",
            "showPlotValuesInLegend": False, "isSynced": True, "xAxisVal": "timestamp", **more}


def _stack(direction: str, panels: list[Any]) -> Any:
    """``panels`` side by side (``row``) or one above the other (``column``), in equal shares."""
    if len(panels) == 1:
        return panels[0]
    return {"direction": direction, "first": panels[0], "second": _stack(direction, panels[1:]),
            "splitPercentage": round(100.0 / len(panels), 2)}


def _scene(vehicle: Vehicle) -> dict[str, Any]:
    """The 3-D panel: the camera follows base_link's position over a grid on the surface."""
    extent = max((float(np.linalg.norm(a.position)) for a in vehicle.actuators), default=1.0)
    cell = float(10.0 ** np.round(np.log10(extent / 2.0)))
    return {
        "foxglovePanelTitle": "vehicle and thrust (map: ENU; ned; base_link: FRD)",
        "cameraState": {"distance": 6.0 * extent, "perspective": True, "phi": 50.0, "thetaOffset": 45.0,
                        "target": [0, 0, 0], "targetOffset": [0, 0, 0], "targetOrientation": [0, 0, 0, 1],
                        "fovy": 45.0, "near": 0.01, "far": 5000.0},
        "followMode": "follow-position", "followTf": BODY,
        "scene": {"transforms": {"showLabel": True, "axisScale": round(extent / 4.0, 3)}},
        "transforms": {f"frame:{WORLD}": {"visible": True}, "frame:ned": {"visible": False},
                       f"frame:{BODY}": {"visible": True}},
        "topics": {TOPICS["markers"]: {"visible": True}, "/setpoint": {"visible": True},
                   "/odometry": {"visible": False}},
        "layers": {"grid": {"layerId": "foxglove.Grid", "instanceId": "grid", "label": f"grid, {cell:g} m",
                            "visible": True, "frameId": WORLD, "size": 40 * cell, "divisions": 40, "lineWidth": 1,
                            "color": "#808080a0", "position": [0, 0, 0], "rotation": [0, 0, 0], "order": 1}},
        "publish": {"type": "point", "poseTopic": "/move_base_simple/goal", "pointTopic": "/clicked_point",
                    "poseEstimateTopic": "/initialpose", "poseEstimateXDeviation": 0.5,
                    "poseEstimateYDeviation": 0.5, "poseEstimateThetaDeviation": 0.26179939},
        "imageMode": {}}


def _thrust(vehicle: Vehicle) -> dict[str, Any]:
    """Thrust of every actuator; its limits as reference lines, once per distinct value."""
    names = vehicle.names
    low, high = thrust_limits(vehicle, None)
    tables = vehicle.nominal_voltage is not None
    at = f" at {vehicle.nominal_voltage:g} V" if tables else ""
    paths = [_series(f"{COMMANDS}.thrust[{i}]", f"{name} [N]", PALETTE[i % len(PALETTE)])
             for i, name in enumerate(names)]
    limits: dict[float, list[int]] = {}
    for i in range(len(names)):
        for bound in (low[i], high[i]):
            if bound != 0.0:
                limits.setdefault(float(bound), []).append(i)
    for bound, members in sorted(limits.items()):
        who = "limit" if len(members) == len(names) else f"{', '.join(names[i] for i in members)} limit"
        colour = LIMIT_COLOUR if len(members) > 1 else PALETTE[members[0] % len(PALETTE)]
        paths.append(_series(f"{bound:g}", f"{who}{at}", colour))
    title = "thrust [N] against its limits" + (f" (limits{at}: the supply voltage moves them)" if tables else "")
    return _plot(title, paths)


def layout(vehicle: Vehicle) -> dict[str, Any]:
    """The layout of a recording of ``vehicle``."""
    names = vehicle.names
    rotating = [i for i, actuator in enumerate(vehicle.actuators) if actuator.rotatable]
    panels: dict[str, dict[str, Any]] = {
        "3D!vehicle": _scene(vehicle),
        "Plot!track": _plot("track: north [m] against east [m]",
                            [_series("/odometry.pose.pose.position.x", "north [m]", "#1f77b4")],
                            xAxisVal="custom", xAxisPath={"value": "/odometry.pose.pose.position.y", "enabled": True}),
        "DiagnosticSummary!diagnostics": {"foxglovePanelTitle": "diagnostics", "minLevel": 0, "pinnedIds": [],
                                          "hardwareIdFilter": "", "topicToRender": TOPICS["diagnostics"],
                                          "sortByLevel": True},
    }
    panels["Plot!heading"] = _plot("heading [deg] and its set-point", [
        _series(f"/odometry{HEADING}", "heading [deg]", "#1f77b4"),
        _series(f"/setpoint{HEADING.replace('pose.pose', 'pose')}", "set-point [deg]", LIMIT_COLOUR)])
    if "heave" in vehicle.dofs:
        panels["Plot!depth"] = _plot("depth [m] (down) and its set-point", [
            _series("/odometry.pose.pose.position.z", "depth [m]", "#1f77b4"),
            _series("/setpoint.pose.position.z", "set-point [m]", LIMIT_COLOUR)])
    panels["Plot!thrust"] = _thrust(vehicle)
    if rotating:
        panels["Plot!azimuth"] = _plot("azimuth [deg]", [_series(f"{COMMANDS}.azimuth[{i}].@degrees",
                                                                 f"{names[i]} [deg]", PALETTE[i % len(PALETTE)])
                                                         for i in rotating])
    panels["StateTransitions!saturation"] = {
        "foxglovePanelTitle": "saturation: the request not met; each actuator at its thrust limit",
        "paths": [{"value": f"{STATUS}.saturated", "timestampMethod": "receiveTime", "label": "saturated"}]
        + [{"value": f"{STATUS}.at_thrust_limit[{i}]", "timestampMethod": "receiveTime", "label": f"{name} at limit"}
           for i, name in enumerate(names)],
        "isSynced": True}
    panels["Plot!unallocated"] = _plot("unallocated wrench (requested minus achieved)", [
        _series(f"{STATUS}.unallocated.{UNALLOCATED[dof][0]}", f"{dof} [{UNALLOCATED[dof][1]}]",
                PALETTE[k % len(PALETTE)]) for k, dof in enumerate(vehicle.dofs)])
    if vehicle.nominal_voltage is not None:
        panels["Plot!voltage"] = _plot("supply voltage [V] the thrust limits follow",
                                       [_series(f"{STATUS}.voltage", "voltage [V]", "#000000")])
    right = [key for key in panels if key.split("!")[0] in ("Plot", "StateTransitions") and key != "Plot!track"]
    left = {"direction": "column", "first": "3D!vehicle",
            "second": _stack("row", ["Plot!track", "DiagnosticSummary!diagnostics"]), "splitPercentage": 60}
    return {"configById": panels, "globalVariables": {}, "userNodes": {}, "playbackConfig": {"speed": 1},
            "layout": {"direction": "row", "first": left, "second": _stack("column", right), "splitPercentage": 45}}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m allocator_pkg.cli.foxglove_layout",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("vehicle", help="vehicle params file (config/*.yaml)")
    arguments = parser.parse_args(argv)
    print(json.dumps(layout(load_vehicle(arguments.vehicle)), indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
