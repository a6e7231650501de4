"""Columns of T and T_e against hand-derived r x d, per (1.5) and the errata of docs/theory.md."""

import math

import numpy as np
import pytest

from allocator_pkg import load_vehicle
from allocator_pkg.effectiveness.configuration_matrix import (
    configuration_matrix,
    extended_configuration_matrix,
    force_column,
)
from allocator_pkg.vehicle.config import ActuatorConfig


def fixed(position, direction, name="t"):
    return ActuatorConfig(name=name, type="fixed", position=tuple(position), direction=tuple(direction),
                          weight=1.0, power_coefficient=1.0)


def rotatable(position, kind="azimuth", name="a"):
    return ActuatorConfig(name=name, type=kind, position=tuple(position), direction=(0.0, 0.0, 0.0),
                          weight=1.0, power_coefficient=1.0)


def test_errata_check_value():
    # docs/theory.md, Errata: r = (2, 0.5, 0.3), d = (1, 0, 0) gives (1, 0, 0, 0, 0.3, -0.5).
    assert force_column([2.0, 0.5, 0.3], [1.0, 0.0, 0.0]) == pytest.approx([1, 0, 0, 0, 0.3, -0.5])


@pytest.mark.parametrize(
    ("direction", "expected_moment"),
    [
        # K = Fz ly - Fy lz, M = Fx lz - Fz lx, N = Fy lx - Fx ly with r = (1.5, -0.4, 0.2)
        ((1, 0, 0), (0.0, 0.2, 0.4)),          # main propeller: yaw -ly (the (1.10) typo printed +ly)
        ((0, 1, 0), (-0.2, 0.0, 1.5)),         # tunnel thruster / rudder
        ((0, 0, 1), (-0.4, -1.5, 0.0)),        # fin
    ],
)
def test_axis_aligned_columns(direction, expected_moment):
    column = force_column([1.5, -0.4, 0.2], direction)
    assert column[:3] == pytest.approx(direction)
    assert column[3:] == pytest.approx(expected_moment)


def test_oblique_column():
    # BlueROV-style vectored thruster at 45 degrees: d = (1, -1, 0)/sqrt2 at r = (0.156, 0.111, 0.085)
    s = 1 / math.sqrt(2)
    lx, ly, lz = 0.156, 0.111, 0.085
    fx, fy, fz = s, -s, 0.0
    expected = [fx, fy, fz, fz * ly - fy * lz, fx * lz - fz * lx, fy * lx - fx * ly]
    assert force_column([lx, ly, lz], [fx, fy, fz]) == pytest.approx(expected)


def test_horizontal_azimuth_column_matches_corrected_1_13():
    lx, ly, lz, a = 2.0, -1.0, 0.5, 0.7
    t = configuration_matrix([rotatable((lx, ly, lz))], [a])[:, 0]
    # (1.13) with the corrected pitch row l_z cos(alpha) (docs/theory.md, Errata)
    expected = [math.cos(a), math.sin(a), 0.0, -lz * math.sin(a), lz * math.cos(a), lx * math.sin(a) - ly * math.cos(a)]
    assert t == pytest.approx(expected)


def test_vertical_azimuth_column_matches_1_13():
    lx, ly, lz, a = -1.2, 0.3, 0.1, -0.4
    t = configuration_matrix([rotatable((lx, ly, lz), "azimuth_vertical")], [a])[:, 0]
    expected = [math.sin(a), 0.0, math.cos(a), ly * math.cos(a), lz * math.sin(a) - lx * math.cos(a), -ly * math.sin(a)]
    assert t == pytest.approx(expected)


def test_extended_matrix_reproduces_t_of_alpha():
    actuators = [rotatable((3.0, 1.0, 0.5)), fixed((-2.0, 0.4, 0.0), (1.0, 0.0, 0.0)),
                 rotatable((1.0, 0.0, -0.2), "azimuth_vertical")]
    angles = [0.3, 0.0, 1.1]
    t_e = extended_configuration_matrix(actuators)
    # (1.18): u_x = u cos a, u_y = u sin a for each rotatable thruster
    f = np.array([2.0, 5.0, -3.0])
    extended = np.array([f[0] * math.cos(0.3), f[0] * math.sin(0.3), f[1], f[2] * math.cos(1.1), f[2] * math.sin(1.1)])
    assert t_e @ extended == pytest.approx(configuration_matrix(actuators, angles) @ f)


def test_example1_extended_matrix_with_explicit_coordinates():
    # (1.22): rows X, Y, N; columns u1x, u1y, u2x, u2y, u3, u4. Coordinates from the shipped file:
    # azimuths at x = 1.2 and x = -1.0 on the centre line, mains at (-1.3, -+0.45).
    vehicle = load_vehicle("config/example1_rov.yaml")
    t_e = extended_configuration_matrix(vehicle.actuators)[[0, 1, 5]]
    expected = np.array([
        [1, 0, 1, 0, 1, 1],
        [0, 1, 0, 1, 0, 0],
        # N = lx Fy - ly Fx: l_x1 = 1.2, l_x2 = -1.0 (printed -l_x2), -l_y3 = 0.45, -l_y4 = -0.45
        [0, 1.2, 0, -1.0, 0.45, -0.45],
    ])
    assert t_e == pytest.approx(expected)


def test_example1_t_of_alpha_matches_1_20():
    vehicle = load_vehicle("config/example1_rov.yaml")
    a1, a2 = 0.4, -1.2
    t = configuration_matrix(vehicle.actuators, [a1, a2, 0.0, 0.0])[[0, 1, 5]]
    lx1, lx2, ly3, ly4 = 1.2, -1.0, -0.45, 0.45
    # (1.20) rows, written out for azimuths on the centre line (l_y1 = l_y2 = 0)
    expected = np.array([
        [math.cos(a1), math.cos(a2), 1, 1],
        [math.sin(a1), math.sin(a2), 0, 0],
        [lx1 * math.sin(a1), lx2 * math.sin(a2), -ly3, -ly4],
    ])
    assert t == pytest.approx(expected)


def test_infante_fin_matrix_1_51():
    # Fin columns on the heave, roll and pitch rows, times k_L, against (1.51) written out for
    # the test vehicle's coordinates: bow fins at x = 1.2, stern fins at x = -1.6, y = -+0.4,
    # lift per positive deflection up (-z) for port fins and down (+z) for starboard fins
    # (Table 2: port "forward edge down", starboard "forward edge up").
    vehicle = load_vehicle("config/infante_auv.yaml")
    fins = [a for a in vehicle.actuators if a.type == "fin"]
    k_b, k_s = 3.0, 4.0
    gains = np.array([k_b, k_b, k_s, k_s])
    t = configuration_matrix(fins, [0.0] * 4)[[2, 3, 4]] * gains
    x_b, x_s, y = 1.2, -1.6, 0.4
    expected = np.array([
        [-k_b, k_b, -k_s, k_s],                                   # heave Z
        [y * k_b, y * k_b, y * k_s, y * k_s],                     # roll K = Fz ly: (-1)(-y), (+1)(+y)
        [x_b * k_b, -x_b * k_b, x_s * k_s, -x_s * k_s],           # pitch M = -Fz lx
    ])
    assert t == pytest.approx(expected)
