"""From a rotatable thruster's extended force to its thrust and angle, inside a sample's limits."""

import dataclasses
import math

import pytest

from allocator_pkg.effectiveness.model import AzimuthLimits
from allocator_pkg.effectiveness.resolve import pointing, resolve
from allocator_pkg.vehicle.angles import wrap


def test_an_idle_thruster_turns_toward_a_methods_turn_instead_of_its_goal():
    """`turn` (a method's direction for an idle thruster) wins over the limits' goal, the short
    way round and within the sample's window; a thruster that pushes, or may not push, ignores it."""
    window = AzimuthLimits(3.0 - 0.2, 3.0 + 0.2, 1, 0.0, 25.0, goal=2.9)
    assert resolve(window, 3.0, (0.0, 0.0), 0.01, continuous=True, turn=-2.9) == (0.0, pytest.approx(wrap(3.2)))
    assert resolve(window, 3.0, (0.0, 0.0), 0.01, continuous=True, turn=3.05) == (0.0, pytest.approx(3.05))
    assert resolve(window, 3.0, (0.0, 0.0), 0.01, continuous=True)[1] == pytest.approx(2.9)
    pushing = resolve(window, 3.0, (-10.0, 0.0), 0.01, continuous=True, turn=2.0)
    assert pushing[1] == pytest.approx(math.pi)
    failed = dataclasses.replace(window, thrust_high=0.0)
    assert resolve(failed, 3.0, (0.0, 0.0), 0.01, continuous=True, turn=3.1)[1] == pytest.approx(2.9)


def test_the_angle_points_the_push_along_the_force_nearest_the_present_angle_on_its_side():
    """(1.23) within a turn of the present angle (wrapped only for a continuous thruster), and a
    thruster pushing in reverse points away from the force with a negative thrust."""
    forward = AzimuthLimits(-math.inf, math.inf, 1, 0.0, 100.0)
    assert pointing(forward, 6.0, 0.0, 10.0, 0.01) == pytest.approx(2.5 * math.pi)
    assert resolve(forward, 6.0, (0.0, 10.0), 0.01, continuous=False) == pytest.approx((10.0, 2.5 * math.pi))
    assert resolve(forward, 6.0, (0.0, 10.0), 0.01, continuous=True) == pytest.approx((10.0, 0.5 * math.pi))
    reverse = AzimuthLimits(-math.inf, math.inf, -1, -100.0, 0.0)
    assert resolve(reverse, 0.0, (0.0, 10.0), 0.01, continuous=False) == pytest.approx((-10.0, -0.5 * math.pi))
    stuck = AzimuthLimits(0.3, 0.3, 1, -50.0, 50.0, line=True)
    assert resolve(stuck, 0.3, (0.0, 10.0), 0.01, continuous=False) == pytest.approx((10.0 * math.sin(0.3), 0.3))
