"""Force-to-command maps (1.3), (1.4), measured tables, and hydrofoil gains (1.48), (1.49)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from allocator_pkg.effectiveness.actuators import CommandMaps, LinearMap, QuadraticMap, TableMap, drag_gain, lift_gain
from allocator_pkg.vehicle.config import SurfaceConfig

TABLE = TableMap(command=[1100, 1300, 1475, 1525, 1700, 1900], thrust=[-30.0, -12.0, 0.0, 0.0, 15.0, 40.0],
                 command_min=-math.inf, command_max=math.inf)
forces = st.floats(min_value=-30.0, max_value=40.0, allow_nan=False)


def test_linear_map_uses_its_reverse_gain():
    m = LinearMap(gain=2.0, gain_reverse=1.0, command_min=-math.inf, command_max=math.inf)
    assert m.command(10.0) == 5.0 and m.command(-10.0) == -10.0
    assert m.force(5.0) == 10.0 and m.force(-10.0) == -10.0


def test_quadratic_map_is_1_4():
    m = QuadraticMap(gain=0.5, gain_reverse=0.25, command_min=-math.inf, command_max=math.inf)
    # F = k |u| u  =>  u = sign(F) sqrt(|F| / k)
    assert m.command(8.0) == pytest.approx(4.0)
    assert m.command(-4.0) == pytest.approx(-4.0)
    assert m.force(-4.0) == pytest.approx(-4.0)


def test_table_dead_band_inverts_to_neutral():
    assert TABLE.command(0.0) == pytest.approx(1500.0)
    assert TABLE.command(15.0) == pytest.approx(1700.0)
    assert TABLE.command(-6.0) == pytest.approx(1300 + (1475 - 1300) * 0.5)   # halfway on a linear piece


def test_command_limits_limit_force_range():
    m = LinearMap(gain=2.0, gain_reverse=1.0, command_min=-5.0, command_max=10.0)
    assert m.force_range() == (-5.0, 20.0)
    table = TableMap([0.0, 1.0, 2.0], [-1.0, 0.0, 3.0], command_min=0.5, command_max=5.0)
    assert table.force_range() == (-0.5, 3.0)


@given(forces)
def test_every_map_inverts(force):
    maps = [LinearMap(2.0, 1.5, -math.inf, math.inf), QuadraticMap(0.01, 0.008, -math.inf, math.inf), TABLE]
    for m in maps:
        assert m.force(m.command(force)) == pytest.approx(force, abs=1e-9)


@given(st.lists(forces, min_size=3, max_size=3), st.floats(min_value=0.05, max_value=1.0))
def test_vectorised_commands_match_each_map_and_degradation(values, efficiency):
    maps = [LinearMap(2.0, 1.5, -math.inf, math.inf), QuadraticMap(0.01, 0.008, -math.inf, math.inf), TABLE]
    force = np.array(values) * efficiency                 # within the degraded range
    commands = CommandMaps(maps).commands(force, np.full(3, efficiency), np.zeros(3))
    for m, f, u in zip(maps, force, commands):
        # a degraded actuator makes efficiency * nominal force for a set-point
        assert efficiency * m.force(u) == pytest.approx(f, abs=1e-9)


def test_surface_commands_are_deflections():
    commands = CommandMaps([None, None]).commands(np.array([30.0, 5.0]), np.ones(2), np.array([100.0, 0.0]))
    assert commands == pytest.approx([0.3, 0.0])


SURFACE = SurfaceConfig(area=0.1, lift_coefficient=3.0, drag_coefficient=0.8, deflection_max=0.4,
                        deflection_rate_max=0.0, flow="free", wake_speed_factor=1.0, min_control_speed=0.5)


def test_lift_and_drag_gains_1_48_1_49():
    # k_L = 1/2 rho A u^2 C_L = 0.5 * 1000 * 0.1 * 4 * 3 = 600 N/rad at 2 m/s
    assert lift_gain(SURFACE, 1000.0, 2.0) == pytest.approx(600.0)
    assert drag_gain(SURFACE, 1000.0, 2.0) == pytest.approx(160.0)
    # gains scale with u_f^2
    assert lift_gain(SURFACE, 1000.0, 4.0) == pytest.approx(4 * 600.0)
    # below the minimum control speed the surface gives nothing
    assert lift_gain(SURFACE, 1000.0, 0.4) == 0.0
    assert lift_gain(SURFACE, 1000.0, -2.0) == 0.0


def test_propeller_wake_flow():
    wake = SurfaceConfig(**{**SURFACE.__dict__, "flow": "propeller_wake", "wake_speed_factor": 1.5})
    assert lift_gain(wake, 1000.0, 2.0) == pytest.approx(600.0 * 1.5 ** 2)


def _table(voltages, rows, command=(1100.0, 1500.0, 1900.0)):
    from allocator_pkg.vehicle.config import CommandMapConfig
    return CommandMapConfig(kind="table", gain=1.0, gain_reverse=1.0, command_min=-math.inf, command_max=math.inf,
                            deadband=0.0, reversed=False, table_command=tuple(command),
                            table_thrust=tuple(v for row in rows for v in row), table_voltage=tuple(voltages))


def test_a_voltage_table_interpolates_between_its_rows():
    from allocator_pkg.effectiveness.actuators import command_map, thrust_row
    config = _table((12.0, 16.0, 20.0), ((-30.0, 0.0, 40.0), (-40.0, 0.0, 50.0), (-50.0, 0.0, 70.0)))
    assert thrust_row(config, 12.0) == pytest.approx([-30.0, 0.0, 40.0])
    assert thrust_row(config, 14.0) == pytest.approx([-35.0, 0.0, 45.0])          # halfway
    assert thrust_row(config, 19.0) == pytest.approx([-47.5, 0.0, 65.0])          # three quarters of 16-20 V
    assert thrust_row(config, 20.0) == pytest.approx([-50.0, 0.0, 70.0])
    at_14 = command_map(config, 14.0)
    assert at_14.force_range() == pytest.approx((-35.0, 45.0))
    assert at_14.command(22.5) == pytest.approx(1700.0)                          # 45 N at 1900, 0 at 1500


def test_thrust_limits_follow_a_voltage_table_and_only_narrow_thrust_min_max():
    from dataclasses import replace

    from allocator_pkg.effectiveness.faults import thrust_limits
    from allocator_pkg.vehicle.config import ActuatorConfig
    config = _table((12.0, 16.0), ((-30.0, 0.0, 40.0), (-40.0, 0.0, 50.0)))
    actuator = ActuatorConfig(name="t", type="fixed", position=(0.0, 0.0, 0.0), direction=(1.0, 0.0, 0.0),
                              weight=1.0, power_coefficient=1.0, thrust_min=-45.0, thrust_max=48.0, command=config)

    class Vehicle:
        actuators = (actuator, replace(actuator, name="u", command=replace(config, table_voltage=(),
                                                                             table_thrust=config.table_thrust[:3])))
        nominal_voltage = 16.0

    low, high = thrust_limits(Vehicle, 12.0)
    assert low.tolist() == [-30.0, -45.0] and high.tolist() == [40.0, 48.0]     # one curve: thrust limits only
    low, high = thrust_limits(Vehicle, None)                                   # nominal: 16 V
    assert low.tolist() == [-40.0, -45.0] and high.tolist() == [48.0, 48.0]


@pytest.mark.parametrize("kind, edge", [("linear", 2.0 * 0.3), ("quadratic", 2.0 * 0.3 * 0.3)])
def test_a_dead_band_gives_no_force_inside_and_its_edges_forces(kind, edge):
    from allocator_pkg.effectiveness.actuators import command_map, deadband_forces
    from allocator_pkg.vehicle.config import CommandMapConfig
    config = CommandMapConfig(kind=kind, gain=2.0, gain_reverse=1.0, command_min=-5.0, command_max=5.0, deadband=0.3,
                              reversed=False)
    low, high = deadband_forces(config)
    assert high == pytest.approx(edge) and low == pytest.approx(-edge / 2.0)      # reverse gain is half
    m = command_map(config)
    assert m.force(0.29) == 0.0 and m.force(-0.29) == 0.0
    assert m.force(0.3) == pytest.approx(high) and m.force(-0.3) == pytest.approx(low)
    assert m.command(high) == pytest.approx(0.3)                                  # the edge's force: the edge
    assert deadband_forces(CommandMapConfig(kind=kind, gain=2.0, gain_reverse=1.0, command_min=-5.0,
                                            command_max=5.0, deadband=0.0, reversed=False)) == (0.0, 0.0)


def test_a_reversed_thruster_mirrors_its_command_about_zero_force():
    forward = np.array([10.0, -6.0, 10.0, -6.0, 0.0, 0.0])
    linear = LinearMap(gain=2.0, gain_reverse=1.0, command_min=-math.inf, command_max=math.inf)
    table = TableMap([1100.0, 1400.0, 1600.0, 1900.0], [-30.0, 0.0, 0.0, 40.0], -math.inf, math.inf)
    maps = [linear, linear, table, table, linear, table]
    plain = CommandMaps(maps).commands(forward, None, np.zeros(6))
    mirrored = CommandMaps(maps, [True, False, True, False, True, True]).commands(forward, None, np.zeros(6))
    assert plain.tolist() == pytest.approx([5.0, -6.0, 1600.0 + 300.0 / 4.0, 1400.0 - 300.0 / 5.0, 0.0, 1500.0])
    assert mirrored.tolist() == pytest.approx([-5.0, -6.0, 1500.0 - 175.0, 1340.0, 0.0, 1500.0])
