"""``~/thrust_markers``: the sample as RViz markers (visualization_msgs/MarkerArray).

Per actuator, an arrow from the point where its force acts along that force (its direction at
the current azimuth times its thrust) and a sphere at the point, both coloured by fault mode:
green NOMINAL (orange when at its limit in force), yellow DEGRADED, magenta STUCK, red FAILED.
Lengths are proportional to force, the same scale for every actuator: the largest thrust of the
vehicle draws as half the vehicle's extent (the largest distance of an actuator from the
origin). Points and directions are in the node's body frame convention, in ``base_frame``.
"""

from __future__ import annotations

import numpy as np
from geometry_msgs.msg import Point, Vector3
from std_msgs.msg import ColorRGBA, Header
from visualization_msgs.msg import Marker, MarkerArray

from ..allocation.allocator import AllocationResult
from ..effectiveness.configuration_matrix import actuator_direction
from ..effectiveness.faults import FaultMode
from ..effectiveness.model import AT_LIMIT
from ..vehicle.config import Vehicle
from ..vehicle.frames import vector_between

COLOURS = {
    FaultMode.NOMINAL: (0.1, 0.75, 0.2),
    FaultMode.DEGRADED: (0.95, 0.8, 0.0),
    FaultMode.STUCK: (0.75, 0.2, 0.75),
    FaultMode.FAILED: (0.85, 0.1, 0.1),
}
AT_LIMIT_COLOUR = (1.0, 0.5, 0.0)
MIN_LENGTH = 0.1                 # m: the reference length of a vehicle with every actuator at its origin


def scale(vehicle: Vehicle) -> tuple[float, float]:
    """(reference length [m], reference force [N]): the force drawn as that length."""
    extent = max((float(np.linalg.norm(a.position)) for a in vehicle.actuators), default=0.0)
    force = max((max(a.thrust_max, -a.thrust_min) for a in vehicle.actuators if not a.is_surface), default=1.0)
    return max(0.5 * extent, MIN_LENGTH), force


def colour(mode: FaultMode, thrust: float, limits: tuple[float, float]) -> tuple[float, float, float]:
    """The colour of an actuator's mode; a NOMINAL one at its limit in force is orange."""
    limit = limits[1] if thrust >= 0.0 else limits[0]
    if mode == FaultMode.NOMINAL and limit != 0.0 and abs(thrust / limit) >= 1.0 - AT_LIMIT:
        return AT_LIMIT_COLOUR
    return COLOURS[mode]


def thrust_markers(vehicle: Vehicle, result: AllocationResult, limits: tuple[np.ndarray, np.ndarray],
                   header: Header, frame: str) -> MarkerArray:
    """Arrows (namespace ``thrust``) and spheres (``actuators``), id = actuator index.
    ``limits`` are the force ranges in force (:func:`allocator_pkg.effectiveness.faults.static_ranges`)."""
    length, force = scale(vehicle)
    markers = []
    for i, actuator in enumerate(vehicle.actuators):
        thrust = float(result.thrust[i])
        start = vector_between(actuator.position, frame)
        along = vector_between(actuator_direction(actuator, float(result.azimuth[i])), frame)
        end = start + along * thrust / force * length
        red, green, blue = colour(FaultMode(int(result.mode[i])), thrust, (limits[0][i], limits[1][i]))
        rgba = ColorRGBA(r=red, g=green, b=blue, a=1.0)
        arrow = Marker(header=header, ns="thrust", id=i, type=Marker.ARROW, action=Marker.ADD, color=rgba,
                       points=[Point(x=float(p[0]), y=float(p[1]), z=float(p[2])) for p in (start, end)],
                       scale=Vector3(x=0.04 * length, y=0.08 * length, z=0.1 * length))
        arrow.pose.orientation.w = 1.0
        sphere = Marker(header=header, ns="actuators", id=i, type=Marker.SPHERE, action=Marker.ADD, color=rgba,
                        scale=Vector3(x=0.1 * length, y=0.1 * length, z=0.1 * length))
        sphere.pose.position = Point(x=float(start[0]), y=float(start[1]), z=float(start[2]))
        sphere.pose.orientation.w = 1.0
        markers += [arrow, sphere]
    return MarkerArray(markers=markers)
