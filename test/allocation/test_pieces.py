"""Convex pieces of a rotatable thruster's forces (survey 4.2) and the planner that chooses
among them, judged against hand-derived geometry and the DP vessel's sway case."""

import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from

from allocator_pkg import Allocator, FaultMode, vehicle_from_parameters
from allocator_pkg.allocation.pieces import Piece, PiecePlanner, convex_pieces
from allocator_pkg.vehicle.config import RotationConfig

DP = ROOT / "config" / "dp_vessel.yaml"


def rotation(sectors=(), low=-math.pi, high=math.pi, reversible=False):
    return RotationConfig(azimuth_min=low, azimuth_max=high, rate_max=0.0, forbidden_sectors=tuple(sectors),
                          reversible=reversible, initial=0.0)


def test_a_free_thruster_is_one_disk():
    assert convex_pieces(rotation(), 0.0, 100.0) == [Piece(-math.inf, math.inf, 100.0)]


def test_a_forbidden_sector_leaves_cones_at_most_pi_wide_covering_the_rest():
    pieces = convex_pieces(rotation([(1.31, 1.83)]), 0.0, 420.0)       # the DP vessel's starboard unit
    assert all(p.end - p.start <= math.pi + 1e-12 and p.radius == 420.0 for p in pieces)
    assert sum(p.end - p.start for p in pieces) == pytest.approx(2 * math.pi - 0.52)
    for degrees in range(0, 360, 5):
        angle = math.radians(degrees)
        inside = any(p.contains(angle) for p in pieces)
        forbidden = 1.31 + 1e-9 < angle < 1.83 - 1e-9
        assert inside != forbidden, degrees


def test_a_reversible_thruster_adds_the_opposite_cones_with_its_reverse_range():
    forward = convex_pieces(rotation([(1.0, 2.0)], reversible=False), 0.0, 100.0)
    both = convex_pieces(rotation([(1.0, 2.0)], reversible=True), -50.0, 100.0)
    assert {p.radius for p in forward} == {100.0}
    assert {p.radius for p in both} == {100.0, 50.0}
    assert not any(p.contains(1.5) for p in forward)
    assert any(p.contains(1.5) and p.radius == 50.0 for p in both)      # pointing at 1.5 + pi, pushing back


def test_a_stuck_thruster_is_its_line_and_nothing_inside_a_sector():
    assert convex_pieces(rotation(), -10.0, 100.0, stuck=0.3) == [Piece(0.3, 0.3, 100.0, line=True)]
    assert convex_pieces(rotation([(1.0, 2.0)]), -10.0, 100.0, stuck=1.5)[0].radius == 0.0


def test_a_vessel_without_sectors_needs_no_planner():
    assert not PiecePlanner(Allocator(vehicle_from(ROOT / "config" / "example1_rov.yaml")).model).needed
    assert PiecePlanner(Allocator(vehicle_from(DP)).model).needed


def test_sway_puts_the_starboard_azimuth_past_its_sector():
    """Sway to starboard at the vessel's capability (an independent LP's, 1.2547e6 N): the
    starboard unit must not push at 75-105 degrees; parked at 75 with no thrust the request
    misses by 4 % of authority, the optimum has it past the sector, pushing aft of starboard."""
    vehicle = vehicle_from(DP)
    stbd = vehicle.names.index("azimuth_stbd")
    tau = np.array([0.0, 1.2547e6, 0.0, 0.0, 0.0, 0.0])
    for method in ("qp", "nonlinear"):
        allocator = Allocator(vehicle, method=method)
        for _ in range(400):
            result = allocator.allocate(tau)
        assert math.degrees(1.83) - 1e-6 <= math.degrees(result.azimuth[stbd]) <= 180.0, method
        assert result.thrust[stbd] > 0.5 * 420e3
        assert not result.saturated


def test_the_plan_stands_while_the_request_stands_and_follows_faults():
    allocator = Allocator(vehicle_from(DP))
    planner = allocator._limits.planner
    tau = np.array([0.0, 1.0e6, 0.0])
    low, high = allocator._limits.low, allocator._limits.high
    first = planner.targets(tau, low, high, {}, np.zeros(4))
    assert planner.targets(tau * (1 + 1e-4), low, high, {}, np.zeros(4)) is first      # kept
    allocator.set_fault("azimuth_stbd", FaultMode.FAILED)
    again = planner.targets(tau, allocator._limits.low, allocator._limits.high, {}, np.zeros(4))
    assert again is not first and math.hypot(*again[0]) == pytest.approx(0.0, abs=1e-3)   # nothing from a failed unit


def test_a_stay_is_kept_unless_crossing_pays():
    """Pure surge on a vessel whose only azimuth has sectors straight ahead and astern: both
    sides of the one ahead give the same, but reaching the other means crossing a sector; the
    thruster stays on the side it is on."""
    vehicle = vehicle_from_parameters({
        "dofs": ["surge", "sway"], "actuators.names": ["a"], "actuators.a.type": "azimuth",
        "actuators.a.position": [0.0, 0.0, 0.0], "actuators.a.thrust_max": 100.0,
        "actuators.a.forbidden_sectors": [-0.2, 0.2, 2.9, 3.4], "actuators.a.azimuth_initial": 1.0})
    planner = PiecePlanner(Allocator(vehicle).model)
    for start, side in ((1.0, 1.0), (-1.0, -1.0)):
        targets = planner.targets(np.array([150.0, 0.0]), np.zeros(1), np.full(1, 100.0), {}, np.array([start]))
        planner._key = None
        assert math.copysign(1.0, math.atan2(targets[0][1], targets[0][0])) == side
