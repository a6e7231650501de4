"""The power the drives draw (allocation/drive_power.py, docs/power.md): a DEGRADED thruster's
power from its set-point (dp_vessel's port azimuth at 0.5 and 200 rpm: swbd_b draws 5774 kW, not
the 3238 kW its delivered force would count), the reverse coefficient for negative thrust, and
over random requests, faults and drive limits: no drive above its limit and no source above its
available power, each counted on the set-point."""

import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg import Allocator, FaultMode
from allocator_pkg.allocation.drive_power import DrivePower

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
OVER = 0.01
"""A source may be asked for at most 1 % more than it has (rounding)."""
P_AZIMUTH, P_TUNNEL = 0.0074, 0.0113
"""dp_vessel's power coefficients [W/N^1.5]."""
GAIN_PORT = 16.375
"""azimuth_port's quadratic map F = k n |n| [N/rpm^2]: 655 kN at 200 rpm."""


def test_a_degraded_thruster_draws_the_power_of_its_set_point():
    """azimuth_port DEGRADED to 0.5, surge asked beyond reach: it runs at its 200 rpm. The set-point
    gives a sound thruster f_c = 16.375 x 200^2 = 655 kN; it delivers 0.5 f_c = 327.5 kN. Its drive
    draws P f_c^1.5 = 0.0074 x 655000^1.5 = 3922.8 kW, not P (327.5 kN)^1.5 = 1386.9 kW: with
    tunnel_aft's P_t |t|^1.5 swbd_b draws 5774 kW, where the delivered force would count 3238 kW."""
    allocator = Allocator(vehicle_from(DP_VESSEL))
    allocator.set_fault("azimuth_port", FaultMode.DEGRADED, efficiency=0.5)
    for _ in range(150):
        result = allocator.allocate([1000e3, 0, 0, 0, 0, 0])
    rpm = result.command[1]
    assert rpm == pytest.approx(200.0, abs=1e-4)
    set_point_force = GAIN_PORT * rpm ** 2
    assert result.thrust[1] == pytest.approx(0.5 * set_point_force, rel=1e-9)
    tunnel = P_TUNNEL * abs(result.thrust[3]) ** 1.5
    by_set_point = (P_AZIMUTH * set_point_force ** 1.5 + tunnel) / 1e3
    by_delivered = (P_AZIMUTH * abs(result.thrust[1]) ** 1.5 + tunnel) / 1e3
    reading = allocator.power.reading(result.thrust, allocator.power_limit)
    assert reading.power[1] == pytest.approx(by_set_point, rel=1e-9)
    assert result.power / 1e3 == pytest.approx(reading.power.sum(), rel=1e-9)          # the status's estimate too
    assert by_set_point == pytest.approx(5774.0, abs=1.0) and by_delivered == pytest.approx(3238.0, abs=1.0)
    azimuth = P_AZIMUTH * set_point_force ** 1.5 / 1e3
    assert azimuth == pytest.approx(3922.8, abs=0.05)
    rows = allocator.power_limit.rows                  # the power rows qp solves with count it so
    assert rows.forward[1] == pytest.approx(P_AZIMUTH * 0.5 ** -1.5, rel=1e-12) and rows.forward[0] == P_AZIMUTH


def test_the_degraded_coefficient_is_p_over_eta_to_the_three_halves():
    drive = DrivePower(np.array([2.0, 2.0]), np.array([3.0, 3.0]), np.array([np.inf, np.inf]))
    degraded = drive.degraded(np.array([1.0, 0.25]))
    np.testing.assert_allclose(degraded.forward, [2.0, 2.0 * 0.25 ** -1.5])
    np.testing.assert_allclose(degraded.reverse, [3.0, 3.0 * 8.0])
    np.testing.assert_allclose(degraded.power(np.array([-4.0, 4.0])), [3.0 * 8.0, 16.0 * 8.0])


REVERSE = {"actuators__tunnel_fwd__reverse_power_coefficient": 0.015}


@pytest.mark.parametrize("thrust", [-250e3, -200e3, -1e3, 1e3, 200e3, 250e3])
def test_negative_thrust_is_counted_with_the_reverse_coefficient(thrust):
    """tunnel_fwd with 0.015 W/N^1.5 astern, 0.0113 ahead: swbd_a's draw is P |f|^1.5 with the P
    of the thrust's sign."""
    allocator = Allocator(vehicle_from(DP_VESSEL, **REVERSE))
    thrusts = np.array([0.0, 0.0, thrust, 0.0])
    coefficient = 0.015 if thrust < 0 else P_TUNNEL
    reading = allocator.power.reading(thrusts, allocator.power_limit)
    assert reading.power[0] == pytest.approx(coefficient * abs(thrust) ** 1.5 / 1e3, rel=1e-12)


def test_a_power_limited_bound_takes_the_dearer_coefficient():
    """swbd_a at 1000 kW, tunnel_fwd dearer astern: its consumers could draw 0.0074 x 420000^1.5 +
    0.015 x 300000^1.5 [W] together; each thrust scales by rho^(2/3), rho = 1000 kW over that."""
    allocator = Allocator(vehicle_from(DP_VESSEL, **REVERSE))
    allocator.set_available_power({"swbd_a": 1000.0})
    demand = P_AZIMUTH * 420e3 ** 1.5 + 0.015 * 300e3 ** 1.5
    scale = (1000e3 / demand) ** (2.0 / 3.0)
    np.testing.assert_allclose(allocator.power_limit.proportional[[0, 2]], [420e3 * scale, 300e3 * scale],
                               rtol=1e-12)
    rows = allocator.power.rows()
    assert rows.forward[2] == P_TUNNEL and rows.reverse[2] == 0.015


LIMITS = {"actuators__azimuth_stbd__drive_limit": 1500.0, "actuators__azimuth_port__drive_limit": 2500.0,
          "actuators__tunnel_fwd__drive_limit": 900.0, "actuators__tunnel_aft__drive_limit": 700.0,
          "actuators__tunnel_fwd__reverse_power_coefficient": 0.015,
          "actuators__tunnel_aft__reverse_power_coefficient": 0.013}
FORWARD = np.array([P_AZIMUTH, P_AZIMUTH, P_TUNNEL, P_TUNNEL])
REVERSE_P = np.array([P_AZIMUTH, P_AZIMUTH, 0.015, 0.013])
DRIVE = np.array([1500.0, 2500.0, 900.0, 700.0])


def test_a_drive_limit_is_a_thrust_range_by_hand():
    """tunnel_fwd: 900 kW ahead at 0.0113 is (900000 / 0.0113)^(2/3) = 185.1 kN, astern at 0.015
    (900000 / 0.015)^(2/3) = 153.3 kN; DEGRADED to 0.6 both times 0.6."""
    allocator = Allocator(vehicle_from(DP_VESSEL, **LIMITS))
    low, high = allocator.ranges
    assert high[2] == pytest.approx((900e3 / P_TUNNEL) ** (2 / 3), rel=1e-12)
    assert low[2] == pytest.approx(-((900e3 / 0.015) ** (2 / 3)), rel=1e-12)
    assert high[2] == pytest.approx(185.1e3, abs=50) and low[2] == pytest.approx(-153.3e3, abs=50)
    allocator.set_fault("tunnel_fwd", FaultMode.DEGRADED, efficiency=0.6)
    low_degraded, high_degraded = allocator.ranges
    assert (low_degraded[2], high_degraded[2]) == pytest.approx((0.6 * low[2], 0.6 * high[2]), rel=1e-12)
    assert high[0] == pytest.approx(min(420e3, (1500e3 / P_AZIMUTH) ** (2 / 3)), rel=1e-12)


@settings(deadline=None, max_examples=25)        # 40 allocations per example: no timing asserted
@given(direction=st.tuples(*[st.floats(-1.0, 1.0)] * 3).filter(lambda d: max(map(abs, d)) > 0.05),
       magnitude=st.sampled_from([0.3, 1.0, 2.0]), degraded=st.sampled_from([None, 0, 1, 2, 3]),
       efficiency=st.floats(0.2, 1.0), swbd_a=st.sampled_from([300.0, 1500.0, 5600.0]))
def test_no_drive_above_its_limit_and_no_source_above_its_power(direction, magnitude, degraded, efficiency, swbd_a):
    """Requests of every direction (surge, sway, yaw) and size, one thruster DEGRADED or none,
    swbd_a's power: each drive's power on its set-point, P_sign |f / eta|^1.5, within its drive
    limit, and each source's draw so counted within its available power."""
    vehicle = vehicle_from(DP_VESSEL, **LIMITS)
    allocator = Allocator(vehicle)
    allocator.set_available_power({"swbd_a": swbd_a})
    eta = np.ones(4)
    if degraded is not None:
        allocator.set_fault(vehicle.names[degraded], FaultMode.DEGRADED, efficiency=efficiency)
        eta[degraded] = efficiency
    tau = magnitude * np.array([600e3 * direction[0], 400e3 * direction[1], 0, 0, 0, 20e6 * direction[2]])
    on_a = np.array([True, False, True, False])
    for _ in range(40):
        thrust = allocator.allocate(tau).thrust
        set_point = np.abs(thrust / eta)
        power = np.where(thrust < 0, REVERSE_P, FORWARD) * set_point ** 1.5 / 1e3
        assert np.all(power <= DRIVE * (1.0 + 1e-9)), (power, DRIVE)
        assert power[on_a].sum() <= swbd_a * (1.0 + OVER)
        assert power[~on_a].sum() <= 7800.0 * (1.0 + OVER)
        assert math.isfinite(power.sum())
