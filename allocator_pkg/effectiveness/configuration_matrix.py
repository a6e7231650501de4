"""Thrust configuration matrices: geometry to the map from actuator forces to tau.

Every column comes from (1.5), tau = [d ; r x d] for a unit force direction d applied at
r, for any direction (not only the axis-aligned cases of Table 1; the printed columns of
(1.10) and (1.13) carry sign typos, see the errata in docs/theory.md).

- :func:`configuration_matrix` is T(alpha) of (1.9)/(1.13): one column per actuator, along
  its current direction.
- :func:`extended_configuration_matrix` is T_e of (1.17)/(1.22): a rotatable thruster
  contributes two constant columns, one per component of its force in its plane of
  rotation (1.14), (1.15), (1.18).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..vehicle.config import AZIMUTH, AZIMUTH_VERTICAL, ActuatorConfig

_X = np.array([1.0, 0.0, 0.0])
_Y = np.array([0.0, 1.0, 0.0])
_Z = np.array([0.0, 0.0, 1.0])


NEGLIGIBLE = 1e-12
"""Entries below this (a lever of a picometre, or cos(pi/2) rounded) are exactly zero: a
denormal lever would otherwise overflow the solver's row scaling and the pseudo-inverse."""


def force_column(position: Sequence[float], direction: Sequence[float]) -> np.ndarray:
    """(1.5): the generalised force [d ; r x d] of a unit force along d applied at r."""
    (rx, ry, rz), (dx, dy, dz) = map(float, position), map(float, direction)
    column = (dx, dy, dz, ry * dz - rz * dy, rz * dx - rx * dz, rx * dy - ry * dx)
    return np.array([value if abs(value) >= NEGLIGIBLE else 0.0 for value in column])


def rotation_basis(actuator_type: str) -> tuple[np.ndarray, np.ndarray]:
    """(e1, e2) with direction(alpha) = cos(alpha) e1 + sin(alpha) e2, as in Table 1.

    ``azimuth`` turns about z: [cos a, sin a, 0]. ``azimuth_vertical`` turns in the x-z plane:
    [sin a, 0, cos a], so alpha = 0 points along +z.
    """
    if actuator_type == AZIMUTH:
        return _X, _Y
    if actuator_type == AZIMUTH_VERTICAL:
        return _Z, _X
    raise ValueError(f"'{actuator_type}' actuators do not rotate")


def actuator_direction(actuator: ActuatorConfig, angle: float = 0.0) -> np.ndarray:
    """Unit force direction of an actuator; rotatable ones at the given angle."""
    if actuator.rotatable:
        e1, e2 = rotation_basis(actuator.type)
        return np.cos(angle) * e1 + np.sin(angle) * e2
    return np.asarray(actuator.direction, dtype=float)


def configuration_matrix(actuators: Sequence[ActuatorConfig], angles: Sequence[float]) -> np.ndarray:
    """T(alpha), 6 x r (1.9), (1.13); ``angles`` has one entry per actuator (ignored for
    actuators that do not rotate)."""
    return np.column_stack([
        force_column(a.position, actuator_direction(a, angle)) for a, angle in zip(actuators, angles)
    ])


def extended_columns(actuators: Sequence[ActuatorConfig]) -> list[int]:
    """Index of each actuator's first column in T_e; rotatable thrusters take two."""
    starts, column = [], 0
    for actuator in actuators:
        starts.append(column)
        column += 2 if actuator.rotatable else 1
    return starts


def extended_configuration_matrix(actuators: Sequence[ActuatorConfig]) -> np.ndarray:
    """T_e, 6 x m (1.17), (1.22): constant; a rotatable thruster's two columns are the
    (1.5) columns of its basis directions e1 and e2."""
    columns = []
    for actuator in actuators:
        if actuator.rotatable:
            columns.extend(force_column(actuator.position, e) for e in rotation_basis(actuator.type))
        else:
            columns.append(force_column(actuator.position, actuator.direction))
    return np.column_stack(columns)
