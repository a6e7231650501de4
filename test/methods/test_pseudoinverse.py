"""The pseudoinverse method: (1.29) for fixed thrusters, (1.33)/(1.34) with azimuths."""

import math

import numpy as np
import pytest
from conftest import DATA, ROOT, vehicle_from
from reference import weighted_pseudo_inverse

from allocator_pkg import Allocator, FaultMode
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix, extended_configuration_matrix
from allocator_pkg.effectiveness.model import Model
from allocator_pkg.effectiveness.weighted_inverse import PseudoInverseGains

EIGHT = DATA / "eight_thrusters.yaml"


def test_gain_is_1_29_computed_once_per_set_of_actuators():
    vehicle = vehicle_from(EIGHT, **{f"actuators__t{i}__weight": float(i) for i in range(1, 9)})
    model = Model.build(vehicle, 0.02)
    inverse = PseudoInverseGains(model)
    none = np.zeros(8, dtype=bool)
    gain = inverse.gain(none, {})
    t = configuration_matrix(vehicle.actuators, [0.0] * 8)
    assert gain == pytest.approx(weighted_pseudo_inverse(t, np.arange(1.0, 9.0)))
    assert inverse.gain(none, {}) is gain                      # cached, not recomputed


def test_failed_actuator_is_left_out_and_the_others_compensate():
    vehicle = vehicle_from(EIGHT)
    alloc = Allocator(vehicle, method="pseudoinverse")
    alloc.set_fault("t3", FaultMode.FAILED)
    tau = np.array([10.0, 3.0, 5.0, 0.5, -0.2, 1.0])
    result = alloc.allocate(tau)
    assert result.thrust[2] == 0.0
    assert result.achieved == pytest.approx(tau, abs=1e-9)
    t = configuration_matrix(vehicle.actuators, [0.0] * 8)
    keep = [i for i in range(8) if i != 2]
    assert result.thrust[keep] == pytest.approx(weighted_pseudo_inverse(t[:, keep], np.ones(7)) @ tau)


def test_clipping_keeps_limits_and_reports_saturation_honestly():
    alloc = Allocator(vehicle_from(EIGHT), method="pseudoinverse")
    result = alloc.allocate([400.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert np.all(result.thrust <= 40.0) and np.all(result.thrust >= -30.0)
    assert result.saturated
    t = configuration_matrix(alloc.vehicle.actuators, [0.0] * 8)
    assert result.achieved == pytest.approx(t @ result.thrust)


def test_uniform_scale_down_preserves_direction():
    alloc = Allocator(vehicle_from(EIGHT, saturation="preserve_direction"), method="pseudoinverse")
    tau = np.array([300.0, 100.0, 0.0, 0.0, 0.0, 0.0])
    result = alloc.allocate(tau)
    ratio = result.achieved[0] / tau[0]
    assert 0.0 < ratio < 1.0
    assert result.achieved == pytest.approx(ratio * tau, abs=1e-9)
    assert np.max(result.thrust) == pytest.approx(40.0)


def test_azimuths_follow_1_33_1_34():
    vehicle = vehicle_from(ROOT / "config" / "example1_rov.yaml", actuators__azimuth_fwd__azimuth_rate_max=0.0,
                           actuators__azimuth_aft__azimuth_rate_max=0.0, actuators__azimuth_fwd__thrust_rate_max=0.0,
                           actuators__azimuth_aft__thrust_rate_max=0.0, actuators__main_port__thrust_rate_max=0.0,
                           actuators__main_stbd__thrust_rate_max=0.0)
    tau = np.array([60.0, 30.0, 0.0, 0.0, 0.0, 15.0])
    result = Allocator(vehicle, method="pseudoinverse").allocate(tau)
    t_e = extended_configuration_matrix(vehicle.actuators)[[0, 1, 5]]
    f_e = weighted_pseudo_inverse(t_e, np.ones(6)) @ tau[[0, 1, 5]]
    assert result.thrust[0] == pytest.approx(math.hypot(f_e[0], f_e[1]))
    assert result.azimuth[0] == pytest.approx(math.atan2(f_e[1], f_e[0]))
    assert result.thrust[1] == pytest.approx(math.hypot(f_e[2], f_e[3]))
    assert result.azimuth[1] == pytest.approx(math.atan2(f_e[3], f_e[2]))
    assert result.thrust[2:] == pytest.approx(f_e[4:])
    assert result.achieved[[0, 1, 5]] == pytest.approx(tau[[0, 1, 5]])


def test_scaling_down_leaves_a_ramped_thrust_to_the_clip():
    """preserve_direction with thrust rate limits on the mains only: after full surge ahead
    the mains can only ramp down (their lower bound is above zero), which no scaling toward
    zero reaches; the free azimuths must still give the sway (they were scaled to nothing)."""
    free_azimuths = {f"actuators__{name}__{key}": 0.0 for name in ("azimuth_fwd", "azimuth_aft")
                     for key in ("azimuth_rate_max", "thrust_rate_max")}
    vehicle = vehicle_from(ROOT / "config" / "example1_rov.yaml", saturation="preserve_direction", **free_azimuths)
    alloc = Allocator(vehicle, method="pseudoinverse")
    for _ in range(50):
        alloc.allocate([400.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    result = alloc.allocate([-50.0, 30.0, 0.0, 0.0, 0.0, 5.0])
    assert result.thrust[2:] == pytest.approx([88.0, 88.0])          # 100 N less one rate step of 12 N
    assert result.achieved[1] == pytest.approx(30.0, rel=1e-6)


def _largest_scale(force, low, high):
    """The largest lambda in [0, 1] with lambda * force within [low, high] (force from zero)."""
    ratios = [hi / f if f > 0 else lo / f for f, lo, hi in zip(force, low, high) if abs(f) > 1e-12]
    return min([1.0, *ratios])


def test_attainable_requests_with_priorities_equal_the_weighted_pseudo_inverse():
    t = configuration_matrix(vehicle_from(EIGHT).actuators, [0.0] * 8)
    alloc = Allocator(vehicle_from(EIGHT, priorities=[1, 1, 0, 0, 0, 2]), method="pseudoinverse")
    rng = np.random.default_rng(3)
    for _ in range(20):
        tau = rng.normal(size=6) * [8.0, 8.0, 10.0, 1.0, 1.0, 1.0]
        result = alloc.allocate(tau)
        expected = weighted_pseudo_inverse(t, np.ones(8)) @ tau
        if np.all((expected <= 40.0) & (expected >= -30.0)):
            assert result.thrust == pytest.approx(expected, abs=1e-9)


def test_sequential_desaturation_gives_the_top_level_its_largest_share_first():
    """Level 0 (heave, roll, pitch) gets the largest scale of its own weighted pseudo-inverse
    (computed here from its rows alone) that the limits allow; the lower levels only what is
    left in its null space; every limit holds."""
    t = configuration_matrix(vehicle_from(EIGHT).actuators, [0.0] * 8)
    low, high = np.full(8, -30.0), np.full(8, 40.0)
    alloc = Allocator(vehicle_from(EIGHT, priorities=[1, 1, 0, 0, 0, 2]), method="pseudoinverse")
    rng = np.random.default_rng(7)
    top = [2, 3, 4]
    for _ in range(40):
        tau = rng.normal(size=6) * [150.0, 150.0, 200.0, 20.0, 15.0, 20.0]
        result = alloc.allocate(tau)
        own = weighted_pseudo_inverse(t[top], np.ones(8)) @ tau[top]
        share = _largest_scale(own, low, high)
        assert result.achieved[top] == pytest.approx(share * tau[top], abs=1e-6)
        alone = alloc.allocate(np.where(np.isin(np.arange(6), top), tau, 0.0))
        assert alone.achieved[top] == pytest.approx(result.achieved[top], abs=1e-6)   # lower levels take nothing
        assert np.all(result.thrust <= high + 1e-9) and np.all(result.thrust >= low - 1e-9)


def test_a_lower_level_gets_what_the_higher_ones_leave():
    """Heave first, beyond the verticals: they saturate; surge, a lower level, is still met by
    the horizontals, which heave does not use (here in the plane of the centre, so that their
    surge needs no pitch from the saturated verticals)."""
    level = {f"actuators__t{i}__position": [0.156 if i < 3 else -0.156, 0.111 if i in (1, 3) else -0.111, 0.0]
             for i in range(1, 5)}
    alloc = Allocator(vehicle_from(EIGHT, priorities=[1, 1, 0, 0, 0, 0], **level), method="pseudoinverse")
    result = alloc.allocate([50.0, 0.0, 400.0, 0.0, 0.0, 0.0])
    assert result.achieved[2] == pytest.approx(160.0)
    assert result.achieved[0] == pytest.approx(50.0, abs=1e-6)
    assert result.saturated and result.at_thrust_limit[4:].all()
