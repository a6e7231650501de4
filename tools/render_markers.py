"""docs/thrust_markers.png: what ~/thrust_markers shows, drawn with matplotlib from the same
MarkerArray the node publishes (allocator_pkg.ros.markers), for the BlueROV2 Heavy in base_link
(FLU) with one thruster failed and one degraded, asked for more surge than it has."""

import sys
from pathlib import Path

from std_msgs.msg import Header

from allocator_pkg import Allocator, FaultMode, load_vehicle
from allocator_pkg.capability.report.plotting import pyplot
from allocator_pkg.effectiveness.faults import static_ranges
from allocator_pkg.ros.markers import thrust_markers
from allocator_pkg.vehicle.frames import wrench_between

plt = pyplot()

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "thrust_markers.png"
WRENCH_FLU = [160.0, 0.0, 60.0, 0.0, 0.0, 4.0]      # surge beyond reach, up, yaw to port


def markers():
    vehicle = load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml")
    allocator = Allocator(vehicle)
    allocator.set_fault("thruster_4", FaultMode.FAILED)
    allocator.set_fault("thruster_6", FaultMode.DEGRADED, efficiency=0.5)
    result = allocator.allocate(wrench_between(WRENCH_FLU, "flu"))
    limits = static_ranges(vehicle, allocator.fault_set, allocator.speed)
    return thrust_markers(vehicle, result, limits, Header(frame_id="base_link"), "flu").markers


def main() -> int:
    figure = plt.figure(figsize=(7, 6))
    axes = figure.add_subplot(projection="3d")
    for marker in markers():
        colour = (marker.color.r, marker.color.g, marker.color.b)
        if marker.ns == "actuators":
            p = marker.pose.position
            axes.scatter([p.x], [p.y], [p.z], color=colour, s=40)
            axes.text(p.x, p.y, p.z + 0.02, f"{marker.id + 1}", fontsize=8)
        else:
            start, end = marker.points
            axes.quiver(start.x, start.y, start.z, end.x - start.x, end.y - start.y, end.z - start.z,
                        color=colour, linewidth=2, arrow_length_ratio=0.2)
    axes.quiver(0, 0, 0, 0.1, 0, 0, color="black", linewidth=1)
    axes.text(0.11, 0, 0, "x", fontsize=8)
    axes.set_xlabel("x forward [m]")
    axes.set_ylabel("y left [m]")
    axes.set_zlabel("z up [m]")
    limit = 0.35
    axes.set_xlim(-limit, limit)
    axes.set_ylim(-limit, limit)
    axes.set_zlim(-limit, limit)
    axes.set_box_aspect((1, 1, 1))
    axes.view_init(elev=25, azim=-60)
    axes.set_title("~/thrust_markers, BlueROV2 Heavy in base_link (FLU)\n"
                   "thruster 4 FAILED (red), 6 DEGRADED (yellow), at their limit (orange), nominal (green)",
                   fontsize=9)
    figure.tight_layout()
    figure.savefig(OUT, dpi=110, metadata={"Software": None})
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
