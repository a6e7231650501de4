"""Actuator fault modes, numbered as the constants of allocator_msgs/ActuatorFault."""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum


class FaultMode(IntEnum):
    NOMINAL = 0
    DEGRADED = 1
    FAILED = 2
    STUCK = 3


@dataclass(frozen=True)
class Fault:
    """The fault state of one actuator.

    DEGRADED: the actuator still produces ``efficiency`` (0 < e <= 1) of its nominal force
    range, and its command is scaled so that it still produces the allocated force.
    FAILED: it produces nothing. STUCK: a rotatable thruster fixed at ``azimuth`` [rad]
    (it still thrusts along that angle), or a control surface jammed at deflection
    ``azimuth`` [rad].
    """

    mode: FaultMode = FaultMode.NOMINAL
    efficiency: float = 1.0
    azimuth: float = 0.0


NOMINAL = Fault()
