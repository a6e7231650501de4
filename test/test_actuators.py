"""Force-to-command maps (1.3), (1.4), measured tables, and hydrofoil gains (1.48), (1.49)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from allocator_pkg.actuators import CommandMaps, LinearMap, QuadraticMap, TableMap, drag_gain, lift_gain
from allocator_pkg.vehicle import SurfaceConfig

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
