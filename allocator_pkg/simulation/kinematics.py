"""Rotations and kinematics in NED / body FRD (Fossen 2021, ch. 2): the zyx Euler angles
roll, pitch, yaw, R(Theta) from body to NED, T(Theta) for the Euler-angle rates, the skew
matrix S(a) with S(a) b = a x b, and the unit quaternion of an attitude."""

from __future__ import annotations

import math

import numpy as np


def skew(a: np.ndarray) -> np.ndarray:
    """S(a): the matrix with S(a) b = a x b."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """R(Theta), body to NED, zyx convention."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch),
                              math.cos(yaw), math.sin(yaw))
    return np.array([[cy * cp, -sy * cr + cy * sp * sr, sy * sr + cy * cr * sp],
                     [sy * cp, cy * cr + sr * sp * sy, -cy * sr + sp * sy * cr],
                     [-sp, cp * sr, cp * cr]])


def euler_rates(roll: float, pitch: float) -> np.ndarray:
    """T(Theta): Euler-angle rates from the body angular velocity [p, q, r] (singular at
    pitch = +-90 deg, far from anything a station-keeping vehicle does)."""
    cr, sr, cp, tp = math.cos(roll), math.sin(roll), math.cos(pitch), math.tan(pitch)
    return np.array([[1.0, sr * tp, cr * tp], [0.0, cr, -sr], [0.0, sr / cp, cr / cp]])


def quaternion(roll: float, pitch: float, yaw: float) -> tuple[float, float, float, float]:
    """(x, y, z, w) of the zyx Euler angles."""
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def euler(x: float, y: float, z: float, w: float) -> tuple[float, float, float]:
    """Roll, pitch, yaw of a unit quaternion (x, y, z, w)."""
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2.0 * (w * y - z * x))))
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return roll, pitch, yaw


def coriolis(mass: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """C(nu) of a symmetric 6 x 6 mass matrix, skew-symmetric (Fossen 2021, (3.46) and (6.43)):
    [[0, -S(M11 v1 + M12 v2)], [-S(M11 v1 + M12 v2), -S(M21 v1 + M22 v2)]]."""
    linear = mass[:3, :3] @ nu[:3] + mass[:3, 3:] @ nu[3:]
    angular = mass[3:, :3] @ nu[:3] + mass[3:, 3:] @ nu[3:]
    result = np.zeros((6, 6))
    result[:3, 3:] = -skew(linear)
    result[3:, :3] = -skew(linear)
    result[3:, 3:] = -skew(angular)
    return result


def coriolis_planar(mass: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """C(nu) of a symmetric 3 x 3 mass matrix in surge, sway, yaw (Fossen 2021, (6.46))."""
    u, v, r = nu.tolist()
    (m11, m12, m16), (m21, m22, m26) = mass[0].tolist(), mass[1].tolist()
    sway = m21 * u + m22 * v + m26 * r
    surge = m11 * u + m12 * v + m16 * r
    return np.array([[0.0, 0.0, -sway], [0.0, 0.0, surge], [sway, -surge, 0.0]])
