"""Flushing geometry, DNV-ST-0111 [3.11.3] and [3.11.4]: half-angles, loss factors and Figure 3-6's
straight notch against numbers worked by hand and the transcription's round cases."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from allocator_pkg.effectiveness.flushing import (
    DeadFlushing,
    Unit,
    dead_flushing,
    dead_flushing_factor,
    flushing_zones,
    half_angle,
)


def unit(name="t", x=0.0, y=0.0, diameter=2.0, tunnel=False, ducted=False):
    return Unit(name, x, y, diameter, tunnel, ducted)


def test_zone_half_angle_by_hand():
    # D 3.4 m, s 14 m: 0.1 + 3.4 / 14 = 0.342857..., arctan = 18.9246 deg.
    assert math.degrees(half_angle(3.4, 14.0)) == pytest.approx(18.9246, abs=1e-4)
    zones = flushing_zones([unit("stbd", -41.5, 7.0, 3.4), unit("port", -41.5, -7.0, 3.4)])
    assert [(z.thruster, z.flushed) for z in zones] == [("stbd", "port"), ("port", "stbd")]
    assert math.degrees(zones[0].centre) == pytest.approx(90.0)
    assert [math.degrees(a) for a in zones[0].sector] == pytest.approx([71.0754, 108.9246], abs=1e-4)


def test_dead_flushing_by_hand():
    # D 3.4 m open, s 14 m (s/D 4.1176 < 8): phi = arctan(0.6 * 3.4 / 14) = 8.2905 deg,
    # beta = 1 - 1 / (0.02 * 16.955 + 0.25 * 4.1176 + 1.2) = 1 - 1 / 2.5685 = 0.61067.
    loss = dead_flushing(unit("stbd", 0.0, 7.0, 3.4), unit("port", 0.0, -7.0, 3.4))
    assert math.degrees(loss.centre) == pytest.approx(90.0)
    assert math.degrees(loss.half_angle) == pytest.approx(8.2905, abs=1e-4)
    assert loss.beta == pytest.approx(0.61067, abs=1e-5)


@pytest.mark.parametrize(("ratio", "beta", "open_deg", "ducted_deg"), [
    (1.0, 0.320, 31.0, 19.3), (2.0, 0.438, 16.7, 9.9), (3.0, 0.531, 11.3, 6.7)])
def test_the_transcriptions_table(ratio, beta, open_deg, ducted_deg):
    assert dead_flushing_factor(ratio * 2.0, 2.0) == pytest.approx(beta, abs=5e-4)
    for ducted, degrees in ((False, open_deg), (True, ducted_deg)):
        loss = dead_flushing(unit("a", diameter=2.0, ducted=ducted), unit("b", y=ratio * 2.0))
        assert math.degrees(loss.half_angle) == pytest.approx(degrees, abs=0.05)


def test_dead_flushing_reach():
    # Open: closer than 8 D; ducted: closer than 4 D; a dead tunnel may be flushed freely.
    assert dead_flushing(unit("a"), unit("b", y=15.9)) is not None
    assert dead_flushing(unit("a"), unit("b", y=16.0)) is None
    assert dead_flushing(unit("a", ducted=True), unit("b", y=7.9)) is not None
    assert dead_flushing(unit("a", ducted=True), unit("b", y=8.0)) is None
    assert dead_flushing(unit("a"), unit("b", y=4.0, tunnel=True)) is None


def test_figure_3_6_is_straight_in_cartesian_coordinates():
    # The transcription's round case: D 2 m open, a dead unit 10 m aft: phi = arctan(0.12),
    # beta 0.661; the midpoint of the line from beta (1, 0) to the sector's edge on the unit
    # circle lies at 4.120 deg and radius 0.829 (0.865 were it linear in the angle).
    loss = dead_flushing(unit("a", x=0.0), unit("dead", x=-10.0))
    assert math.degrees(loss.half_angle) == pytest.approx(6.843, abs=1e-3)
    assert loss.beta == pytest.approx(0.661, abs=1e-3)
    assert loss.factor(math.radians(4.120)) == pytest.approx(0.829, abs=1e-3)
    assert loss.factor(0.0) == pytest.approx(loss.beta)
    assert loss.factor(loss.half_angle) == pytest.approx(1.0) and loss.factor(math.pi) == 1.0
    # Every point of the notch is on that line: (r cos d, r sin d) collinear with its ends.
    a = np.array([loss.beta, 0.0])
    b = np.array([math.cos(loss.half_angle), math.sin(loss.half_angle)])
    for delta in np.linspace(0.0, loss.half_angle, 9):
        point = loss.factor(delta) * np.array([math.cos(delta), math.sin(delta)])
        cross = (b - a)[0] * (point - a)[1] - (b - a)[1] * (point - a)[0]
        assert cross == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize(("phi", "beta"), [(0.12, 0.661), (1.4, 0.184), (0.5, 0.32)])
def test_lowest_factor_over_an_arc_is_the_dense_minimum(phi, beta):
    # (1.4, 0.184): s = 0.1 D, where beta > cos(phi) and the least radius lies off the centre.
    loss = DeadFlushing("a", "b", 0.3, phi, beta)
    rng = np.random.default_rng(7)
    for _ in range(200):
        low = rng.uniform(-math.pi, math.pi)
        high = low + rng.uniform(0.0, 1.5)
        least = _least(loss, low, high)
        assert least - 1e-7 <= loss.lowest(low, high) <= least + 1e-12
    assert loss.lowest(-math.inf, math.inf) == pytest.approx(_least(loss, -math.pi, math.pi), abs=1e-7)


def _least(loss, low, high):
    """The least factor over [low, high]: a dense grid, refined by scipy's bounded minimiser
    around the grid's least point."""
    grid = np.linspace(low, high, 4001)
    values = [loss.factor(a) for a in grid]
    k = int(np.argmin(values))
    step = grid[1] - grid[0]
    refined = minimize_scalar(loss.factor, bounds=(max(low, grid[k] - step), min(high, grid[k] + step)),
                              method="bounded", options={"xatol": 1e-12})
    return min(values[k], float(refined.fun))
