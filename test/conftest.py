"""Shared fixtures. DDS stays on this machine: discovery on loopback and a domain of our
own unless the caller chose them (set before any rclpy import starts a participant)."""

import os
from pathlib import Path

os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
os.environ.setdefault("ROS_DOMAIN_ID", "42")

import pytest

from allocator_pkg.vehicle import Vehicle, read_parameters

ROOT = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"


def vehicle_from(path, **overrides) -> Vehicle:
    """A vehicle from a params file with some parameters replaced (dots in names as '__')."""
    parameters = read_parameters(path)
    parameters.update({key.replace("__", "."): value for key, value in overrides.items()})
    return Vehicle.from_parameters(parameters)


@pytest.fixture
def eight_thrusters():
    return DATA / "eight_thrusters.yaml"
