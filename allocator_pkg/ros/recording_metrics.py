"""The metrics of an ``allocator-sim`` run again, from its ``run.mcap`` alone."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory

from ..simulation.kinematics import euler
from ..simulation.metrics import run_metrics
from ..vehicle.config import Vehicle


def metrics_from_recording(path: Path, vehicle: Vehicle, horizontal: bool) -> dict[str, float]:
    """The metrics of a run again, from its ``run.mcap`` alone (odometry, set-point, commands, status)."""
    rows: dict[str, list] = {topic: [] for topic in ("/odometry", "/setpoint", "/thruster_commands",
                                                     "/allocation_status")}
    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        for _, channel, _, message in reader.iter_decoded_messages(topics=list(rows)):
            rows[channel.topic].append(message)
    position = np.array([[m.pose.pose.position.x, m.pose.pose.position.y, m.pose.pose.position.z]
                         for m in rows["/odometry"]])
    heading = np.array([euler(m.pose.pose.orientation.x, m.pose.pose.orientation.y, m.pose.pose.orientation.z,
                              m.pose.pose.orientation.w)[2] for m in rows["/odometry"]])
    setpoint = np.array([[m.pose.position.x, m.pose.position.y, m.pose.position.z] for m in rows["/setpoint"]])
    setpoint_heading = np.array([euler(m.pose.orientation.x, m.pose.orientation.y, m.pose.orientation.z,
                                       m.pose.orientation.w)[2] for m in rows["/setpoint"]])
    commands = rows["/thruster_commands"]
    return run_metrics(position=position, position_setpoint=setpoint, heading=heading,
                       heading_setpoint=setpoint_heading, horizontal=horizontal,
                       thrust=np.array([list(m.thrust) for m in commands]),
                       angles=np.array([list(m.azimuth) for m in commands]),
                       saturated=np.array([m.saturated for m in rows["/allocation_status"]]),
                       power_coefficients=np.array([a.power_coefficient for a in vehicle.actuators]),
                       thrust_scale=np.array([max(abs(a.thrust_min), abs(a.thrust_max)) for a in vehicle.actuators]),
                       period=1.0 / vehicle.rate_hz)
