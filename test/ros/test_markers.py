"""~/thrust_markers as a pure function of a sample: arrows along each force, colours by fault
mode and limit, points in the node's body frame convention."""

import numpy as np
import pytest
from conftest import ROOT
from std_msgs.msg import Header
from visualization_msgs.msg import Marker

from allocator_pkg import Allocator, FaultMode, load_vehicle
from allocator_pkg.effectiveness.faults import static_ranges
from allocator_pkg.ros.markers import AT_LIMIT_COLOUR, COLOURS, scale, thrust_markers

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


def sample(faults=(), wrench=(100.0, 0.0, 0.0, 0.0, 0.0, 0.0), samples=100):
    vehicle = load_vehicle(EXAMPLE)
    allocator = Allocator(vehicle)
    for name, mode in faults:
        allocator.set_fault(name, mode, efficiency=0.5)
    for _ in range(samples):
        result = allocator.allocate(list(wrench))
    return vehicle, result, static_ranges(vehicle, allocator.fault_set, allocator.speed)


def test_an_arrow_and_a_sphere_per_actuator_along_its_force():
    vehicle, result, limits = sample()
    markers = thrust_markers(vehicle, result, limits, Header(frame_id="base_link"), "frd").markers
    arrows = [m for m in markers if m.ns == "thrust"]
    spheres = [m for m in markers if m.ns == "actuators"]
    assert [m.id for m in arrows] == [m.id for m in spheres] == [0, 1, 2, 3]
    assert {m.type for m in arrows} == {Marker.ARROW} and {m.type for m in spheres} == {Marker.SPHERE}
    length, force = scale(vehicle)
    assert (length, force) == pytest.approx((0.5 * np.hypot(1.3, 0.45), 300.0))   # main_port is farthest
    for i, actuator in enumerate(vehicle.actuators):
        start, end = arrows[i].points
        angle = result.azimuth[i]
        direction = [np.cos(angle), np.sin(angle), 0.0] if actuator.rotatable else actuator.direction
        expected = np.array(actuator.position) + np.array(direction) * result.thrust[i] / force * length
        assert (start.x, start.y, start.z) == pytest.approx(actuator.position)
        assert (end.x, end.y, end.z) == pytest.approx(expected)
        assert spheres[i].pose.position.x == pytest.approx(actuator.position[0])


def test_flu_flips_y_and_z_of_points():
    vehicle, result, limits = sample()
    frd = thrust_markers(vehicle, result, limits, Header(), "frd").markers
    flu = thrust_markers(vehicle, result, limits, Header(), "flu").markers
    for a, b in zip(frd, flu):
        for p, q in zip(a.points, b.points):
            assert (q.x, q.y, q.z) == pytest.approx((p.x, -p.y, -p.z))


def test_colours_by_mode_and_limit():
    vehicle, result, limits = sample(faults=[("main_port", FaultMode.FAILED), ("main_stbd", FaultMode.DEGRADED)],
                                     wrench=(1e6, 0.0, 0.0, 0.0, 0.0, 0.0))
    markers = thrust_markers(vehicle, result, limits, Header(), "frd").markers
    colours = {m.id: (m.color.r, m.color.g, m.color.b) for m in markers if m.ns == "actuators"}
    assert colours[2] == pytest.approx(COLOURS[FaultMode.FAILED])
    assert colours[3] == pytest.approx(COLOURS[FaultMode.DEGRADED])
    for i in (0, 1):                                              # the azimuths: orange at their limit
        limit = limits[1][i] if result.thrust[i] >= 0 else limits[0][i]
        at_limit = abs(result.thrust[i] / limit) >= 0.999
        assert colours[i] == pytest.approx(AT_LIMIT_COLOUR if at_limit else COLOURS[FaultMode.NOMINAL])
    assert AT_LIMIT_COLOUR in [tuple(c) for c in colours.values()]


def test_the_docs_picture_exists():
    assert (ROOT / "docs" / "thrust_markers.png").stat().st_size > 10_000
