"""Angle sets of rotatable thrusters."""

import math

import pytest

from allocator_pkg.effectiveness.sectors import (
    allowed_piece,
    forbidden_offsets,
    in_feasible_sector,
    in_forbidden_sector,
    target_offsets,
    wrap,
)
from allocator_pkg.vehicle.config import RotationConfig


def rotation(low=-math.pi, high=math.pi, forbidden=(), initial=0.0):
    return RotationConfig(azimuth_min=low, azimuth_max=high, rate_max=0.0, forbidden_sectors=tuple(forbidden),
                          reversible=False, initial=initial)


def test_wrap():
    assert wrap(3 * math.pi) == pytest.approx(math.pi)
    assert wrap(-math.pi) == pytest.approx(math.pi)
    assert wrap(-0.5) == -0.5


def test_forbidden_sector_is_counter_clockwise_and_edges_are_allowed():
    free = rotation(forbidden=[(3.0, -3.0)])                 # across +-pi
    assert in_forbidden_sector(free, math.pi)
    assert not in_forbidden_sector(free, 0.0)
    assert not in_forbidden_sector(free, 3.0)
    assert in_forbidden_sector(free, -3.1)


def test_feasible_sector():
    limited = rotation(-1.0, 1.0)
    assert in_feasible_sector(limited, 0.9) and not in_feasible_sector(limited, 1.1)
    assert in_feasible_sector(rotation(), 100.0)             # free rotation


def test_offsets_and_pieces():
    free = rotation(forbidden=[(1.0, 1.5)])
    forbidden = forbidden_offsets(free, 0.2)
    assert any(lo == pytest.approx(0.8) and hi == pytest.approx(1.3) for lo, hi in forbidden)
    low, high = allowed_piece((-2 * math.pi, 2 * math.pi), forbidden)
    assert high == pytest.approx(0.8) and low == pytest.approx(1.3 - 2 * math.pi)
    assert allowed_piece((-1.0, 1.0), [(-0.1, 0.1)]) is None


def test_target_offsets():
    free = rotation()
    assert sorted(target_offsets(free, 0.0, 1.0)) == pytest.approx([1.0 - 2 * math.pi, 1.0])
    limited = rotation(-1.0, 2.0, initial=1.5)
    assert target_offsets(limited, 1.5, -0.5) == pytest.approx([-2.0])
    assert target_offsets(limited, 1.5, math.pi) == []
