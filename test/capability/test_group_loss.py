"""What a group's loss leaves (capability/group_loss.py) under the bus ties and drive limits in
force: a closed tie gives a thruster left the other switchboard's power, a drive limit bounds its
range, both by hand."""

import numpy as np
import pytest
from conftest import ROOT, vehicle_from

from allocator_pkg import Allocator
from allocator_pkg.capability.group_loss import InForce, remaining
from allocator_pkg.vehicle.config import RedundancyGroup

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
TIED = {"power__bus_ties": ["bt_ab"], "power__bus_tie__bt_ab__sources": ["swbd_a", "swbd_b"],
        "power__bus_tie__bt_ab__closed": False}
STARBOARD_AZIMUTH = RedundancyGroup("starboard_azimuth", (), ("azimuth_stbd",))


def test_the_tie_state_in_force_decides_the_power_left_to_a_thruster():
    """swbd_a at 100 kW, the starboard azimuth lost: tunnel_fwd alone on swbd_a's 100 kW gets
    300 kN (100000 / (0.0113 x 300000^1.5))^(2/3) with the tie open; closed, the bus of 7900 kW
    covers what tunnel_fwd, azimuth_port and tunnel_aft could draw (2 x 1856.8 + 3922.8 kW)."""
    vehicle = vehicle_from(DP_VESSEL, **TIED)
    allocator = Allocator(vehicle)
    allocator.set_available_power({"swbd_a": 100.0})
    opened = remaining(vehicle, InForce.of(allocator), STARBOARD_AZIMUTH)
    assert opened.high[2] == pytest.approx(300e3 * (100e3 / (0.0113 * 300e3 ** 1.5)) ** (2 / 3), rel=1e-12)
    allocator.set_bus_tie("bt_ab", True)
    closed = remaining(vehicle, InForce.of(allocator), STARBOARD_AZIMUTH)
    np.testing.assert_array_equal(closed.high, [0.0, 655e3, 300e3, 300e3])


def test_a_drive_limit_bounds_what_the_loss_leaves():
    """tunnel_fwd's drive at 900 kW: (900000 / 0.0113)^(2/3) either way."""
    vehicle = vehicle_from(DP_VESSEL, actuators__tunnel_fwd__drive_limit=900.0)
    left = remaining(vehicle, InForce.intact(vehicle), STARBOARD_AZIMUTH)
    bound = (900e3 / 0.0113) ** (2 / 3)
    assert (left.low[2], left.high[2]) == pytest.approx((-bound, bound), rel=1e-12)
