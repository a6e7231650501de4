"""allocator_pkg.simulation.thrusters: the first-order lag, the rate limits, azimuths turning
at their rate, faults, a trip, the loss factors of the dead set's case and the wrench
T(alpha) f, against hand calculations."""

import math

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg.capability.thrust_profile import ThrustProfile
from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix
from allocator_pkg.effectiveness.faults import thrust_limits
from allocator_pkg.simulation.thrust_losses import LossCase, ThrustLosses
from allocator_pkg.simulation.thrusters import Thrusters

VESSEL = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
ROV = load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml")


def run(thrusters, thrust, angle, seconds, dt=0.01):
    for _ in range(round(seconds / dt)):
        thrusters.step(np.asarray(thrust, float), np.asarray(angle, float), dt)


def test_a_small_step_follows_the_first_order_lag():
    thrusters = Thrusters(ROV, time_constant=0.2)
    command = np.full(8, 10.0)                       # 10 N: the lag never asks more than the rate (no limit here)
    run(thrusters, command, np.zeros(8), 0.2)
    assert thrusters.thrust == pytest.approx(10.0 * (1 - math.exp(-1.0)), rel=1e-9)
    run(thrusters, command, np.zeros(8), 2.0)
    assert thrusters.thrust == pytest.approx(10.0, rel=1e-4)


def test_a_large_step_is_held_to_the_rate_limit_then_lags():
    thrusters = Thrusters(VESSEL, time_constant=1.0)
    command = np.array([400e3, 0, 0, 0])
    run(thrusters, command, np.zeros(4), 1.0, dt=0.1)
    assert thrusters.thrust[0] == pytest.approx(100e3, rel=1e-9)     # 100 kN/s for one second
    run(thrusters, command, np.zeros(4), 60.0, dt=0.1)
    assert thrusters.thrust[0] == pytest.approx(400e3, rel=1e-6)


def test_thrust_stays_within_the_range_of_the_supply_voltage():
    thrusters = Thrusters(ROV, time_constant=0.05, voltage=12.0)
    run(thrusters, np.full(8, 60.0), np.zeros(8), 2.0)
    assert thrusters.thrust == pytest.approx(36.4, rel=1e-6)         # the 12 V curve's end at 1900 us
    thrusters.set_voltage(16.0)
    run(thrusters, np.full(8, 60.0), np.zeros(8), 2.0)
    assert thrusters.thrust == pytest.approx(51.5, rel=1e-6)


def test_azimuths_turn_at_their_rate_the_short_way_round():
    thrusters = Thrusters(VESSEL, time_constant=1.0)
    start = thrusters.angle.copy()
    run(thrusters, np.zeros(4), start + np.array([1.0, -3.0, 0, 0]), 2.0, dt=0.1)
    assert thrusters.angle[0] == pytest.approx(start[0] + 0.42)
    assert thrusters.angle[1] == pytest.approx(start[1] - 0.42)
    run(thrusters, np.zeros(4), start + np.array([1.0, -3.0, 0, 0]), 30.0, dt=0.1)
    assert thrusters.angle[:2] == pytest.approx(start[:2] + np.array([1.0, -3.0]))


def test_faults_as_the_water_sees_them():
    thrusters = Thrusters(VESSEL, time_constant=0.5)
    thrusters.set_fault("azimuth_stbd", "stuck", 0.5)
    thrusters.set_fault("tunnel_fwd", "failed")
    thrusters.set_fault("tunnel_aft", "degraded", 0.5)
    run(thrusters, np.array([50e3, 50e3, 50e3, 50e3]), np.array([1.5, 0.3, 0, 0]), 20.0, dt=0.1)
    assert thrusters.angle[0] == 0.5
    assert thrusters.angle[1] == pytest.approx(0.3)
    assert thrusters.thrust == pytest.approx([50e3, 50e3, 0.0, 25e3], rel=1e-6)
    with pytest.raises(ValueError, match=r"fault\.actuator"):
        thrusters.set_fault("nope", "failed")
    with pytest.raises(ValueError, match=r"fault\.mode"):
        thrusters.set_fault("tunnel_fwd", "melted")
    thrusters.clear_faults()
    assert thrusters.efficiency == pytest.approx(1.0) and not thrusters.stuck.any()


def test_the_wrench_is_the_configuration_matrix_times_the_thrust():
    thrusters = Thrusters(VESSEL, time_constant=1.0)
    thrusters.thrust = np.array([100e3, 0.0, 50e3, 0.0])
    thrusters.angle = np.array([math.pi / 2, 0.0, 0.0, 0.0])
    wrench = thrusters.wrench()
    # 100 kN to starboard at (-41.5, 7.0, 4.5), 50 kN to starboard at (37, 0, 3.5)
    assert wrench[1] == pytest.approx(150e3, rel=1e-9)
    assert wrench[5] == pytest.approx(-41.5 * 100e3 + 37.0 * 50e3, rel=1e-9)
    assert wrench[3] == pytest.approx(-(4.5 * 100e3 + 3.5 * 50e3), rel=1e-9)     # K = y Fz - z Fy
    with pytest.raises(ValueError, match="thruster_time_constant"):
        Thrusters(VESSEL, time_constant=0.0)


def test_the_thrusters_start_where_the_commands_hold_them():
    thrusters = Thrusters(VESSEL, time_constant=2.0)
    thrusters.set_fault("tunnel_aft", "degraded", 0.5)
    angles = np.array([0.3, -0.2, 1.0, 1.0])                          # the tunnels do not turn
    thrusters.start_at(np.array([1e5, 2e5, 5e4, 9e9]), angles)
    assert thrusters.thrust == pytest.approx([1e5, 2e5, 5e4, 0.5 * thrusters.high[3]])   # in range, degraded
    assert thrusters.angle == pytest.approx([0.3, -0.2, 0.0, 0.0])
    before = thrusters.wrench()
    run(thrusters, [1e5, 2e5, 5e4, 9e9], angles, 1.0)                # held by the same commands: nothing moves
    assert thrusters.wrench() == pytest.approx(before)


def test_the_wrench_follows_every_change_of_angle_and_the_ranges_every_change_of_voltage():
    thrusters = Thrusters(VESSEL, time_constant=2.0)
    rng = np.random.default_rng(7)
    for k in range(60):
        if k == 20:
            thrusters.set_fault("azimuth_stbd", "stuck", 0.7)
        if k == 40:
            thrusters.start_at(rng.uniform(-1e5, 1e5, 4), rng.uniform(-3.0, 3.0, 4))
        thrusters.step(rng.uniform(-3e5, 3e5, 4), rng.uniform(-3.0, 3.0, 4), 0.05)
        expected = configuration_matrix(VESSEL.actuators, thrusters.angle) @ thrusters.thrust
        assert np.array_equal(thrusters.wrench(), expected), k
    rov = Thrusters(ROV, time_constant=0.1, voltage=16.0)
    for voltage in (16.0, 12.0, 12.0, None, 14.5):
        rov.set_voltage(voltage)
        low, high = thrust_limits(ROV, voltage)
        assert np.array_equal(rov.low, low) and np.array_equal(rov.high, high), voltage


@pytest.mark.parametrize("name", VESSEL.names)
@pytest.mark.parametrize("held", [40e3, 150e3, 290e3])
def test_a_trip_takes_the_thrust_to_zero_in_one_step_and_a_failure_without_it_at_the_rate_limit(name, held):
    index = VESSEL.names.index(name)
    command = np.full(4, held)
    tripped, ramped = Thrusters(VESSEL, time_constant=1.0, trip=True), Thrusters(VESSEL, time_constant=1.0)
    for thrusters in (tripped, ramped):
        thrusters.start_at(command, np.zeros(4))
        thrusters.set_fault(name, "failed")
        thrusters.step(command, np.zeros(4), 0.1)
    assert tripped.thrust[index] == 0.0
    assert ramped.thrust[index] == pytest.approx(held - min(held * (1 - math.exp(-0.1)), 100e3 * 0.1))
    others = [i for i in range(4) if i != index]
    assert tripped.thrust[others] == pytest.approx(held) and ramped.thrust[others] == pytest.approx(held)


def loss_cases(factor: float) -> ThrustLosses:
    """Intact: azimuth_port 0.9 forward; tunnels 0.8 forward, 0.7 reversed. With azimuth_stbd
    dead: azimuth_port's profile a notch down to ``factor`` at 90 deg (toward starboard)."""
    notch = ThrustProfile(((math.radians(60.0), 1.0), (math.radians(90.0), factor), (math.radians(120.0), 1.0)))
    tunnels = {"tunnel_fwd": 0.8, "tunnel_aft": 0.8}
    return ThrustLosses((LossCase(frozenset(), {"azimuth_port": 0.9, **tunnels}, {"tunnel_fwd": 0.7,
                                                                                    "tunnel_aft": 0.7}),
                         LossCase(frozenset({"azimuth_stbd"}), {"azimuth_port": 0.9, **tunnels},
                                  {"tunnel_fwd": 0.7, "tunnel_aft": 0.7}, {"azimuth_port": notch})))


@given(st.floats(0.0, 1.0), st.floats(-180.0, 180.0), st.floats(1e3, 300e3), st.sampled_from([1.0, -1.0]))
@settings(max_examples=60, deadline=None)
def test_a_thruster_delivers_its_command_times_the_loss_factors_of_the_case(factor, degrees, command, sign):
    losses = loss_cases(factor)
    thrusters = Thrusters(VESSEL, time_constant=0.5, losses=losses)
    angle = math.radians(degrees)
    commands = np.array([command, command, sign * command, sign * command])
    thrusters.start_at(commands, np.array([0.0, angle, 0.0, 0.0]))
    tunnel = 0.8 if sign > 0 else 0.7
    assert thrusters.thrust == pytest.approx([command, 0.9 * command, tunnel * sign * command,
                                              tunnel * sign * command], rel=1e-12)
    thrusters.set_fault("azimuth_stbd", "failed")
    run(thrusters, commands, np.array([0.0, angle, 0.0, 0.0]), 40.0, dt=0.1)
    onto_dead = losses.cases[1].profiles["azimuth_port"].factor(angle)
    assert thrusters.thrust[1] == pytest.approx(0.9 * onto_dead * command, rel=1e-9)
    assert thrusters.thrust[2:] == pytest.approx(tunnel * sign * command, rel=1e-9)
    if abs(degrees - 90.0) < 30.0:
        assert onto_dead < 1.0 or factor == 1.0


def test_a_dead_set_without_a_case_of_its_own_takes_the_largest_within_it_and_bad_losses_are_refused():
    losses = loss_cases(0.5)
    assert losses.case(frozenset({"azimuth_stbd", "tunnel_fwd"})).dead == {"azimuth_stbd"}
    assert losses.case(frozenset({"tunnel_fwd"})).dead == frozenset()
    with pytest.raises(ValueError, match="thrust_losses: no loss case"):
        ThrustLosses((losses.cases[1],)).case(frozenset())
    with pytest.raises(ValueError, match="thrust_losses: nope not actuators"):
        Thrusters(VESSEL, 1.0, losses=ThrustLosses((LossCase(frozenset(), {"nope": 0.5}),)))
    with pytest.raises(ValueError, match=r"thrust_losses\.forward\.tunnel_fwd"):
        LossCase(frozenset(), {"tunnel_fwd": 1.5})


@pytest.mark.parametrize("cap", [0.0, 50e3, 150e3])
def test_a_drive_limit_holds_the_thrust_under_it_at_once_whatever_the_rate(cap):
    thrusters = Thrusters(VESSEL, time_constant=2.0)
    thrusters.start_at(np.array([300e3, 200e3, 200e3, 100e3]), thrusters.angle.copy())
    high = np.array([cap, cap, np.inf, cap])
    thrusters.cap = (-high, high)
    thrusters.step(np.array([300e3, 200e3, 200e3, 100e3]), thrusters.angle.copy(), 0.01)
    assert thrusters.thrust[[0, 1, 3]] == pytest.approx([min(cap, 300e3), min(cap, 200e3), min(cap, 100e3)])
    assert thrusters.thrust[2] == pytest.approx(200e3)
