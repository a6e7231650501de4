"""The BlueROV2 Heavy in six DOF, as Fossen (2021) writes an underwater vehicle:

    M nu_r' + C(nu_r) nu_r + (D_l + D_q |nu_r|) nu_r + g(eta) = tau,   nu = nu_r + nu_c
    eta' = J(eta) nu

with the parameters identified by von Benzon et al., "An Open-Source Benchmark Simulator:
Control of a BlueROV2 Underwater Robot", J. Mar. Sci. Eng. 2022, Table A1: m 13.5 kg,
V 0.0134 m^3, I = diag(0.26, 0.23, 0.37) kg m^2, added mass (6.36, 7.12, 18.68, 0.189,
0.135, 0.222), linear damping (13.7, 0, 33.0, 0, 0.8, 0), quadratic damping (141, 217, 190,
1.19, 0.47, 1.5), the centre of gravity at the body origin and the centre of buoyancy
0.01 m above it, fresh water 1000 kg/m^3, g = 9.82 m/s^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .kinematics import coriolis, euler_rates, rotation


@dataclass(frozen=True)
class RovParameters:
    """A neutrally ballasted underwater vehicle (von Benzon et al. 2022 by default)."""

    mass: float = 13.5
    volume: float = 0.0134
    inertia: tuple[float, float, float] = (0.26, 0.23, 0.37)
    added_mass: tuple[float, ...] = (6.36, 7.12, 18.68, 0.189, 0.135, 0.222)
    linear_damping: tuple[float, ...] = (13.7, 0.0, 33.0, 0.0, 0.8, 0.0)
    quadratic_damping: tuple[float, ...] = (141.0, 217.0, 190.0, 1.19, 0.47, 1.5)
    centre_of_gravity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    centre_of_buoyancy: tuple[float, float, float] = (0.0, 0.0, -0.01)
    water_density: float = 1000.0
    gravity: float = 9.82

    @property
    def weight(self) -> float:
        return self.mass * self.gravity

    @property
    def buoyancy(self) -> float:
        return self.water_density * self.gravity * self.volume


class Rov:
    """State eta = [north, east, down, roll, pitch, yaw], nu = [u, v, w, p, q, r]."""

    dofs = 6

    def __init__(self, parameters: RovParameters | None = None):
        self.parameters = p = parameters or RovParameters()
        rigid = np.diag([p.mass] * 3 + list(p.inertia))
        self.mass = rigid + np.diag(p.added_mass)
        self.mass_inverse = np.linalg.inv(self.mass)
        self.linear_damping = np.array(p.linear_damping)
        self.quadratic_damping = np.array(p.quadratic_damping)

    def restoring(self, eta: np.ndarray) -> np.ndarray:
        """g(eta) (Fossen 2021, (4.6)): gravity and buoyancy as seen in the body frame, on the
        left-hand side."""
        p = self.parameters
        w, b = p.weight, p.buoyancy
        xg, yg, zg = p.centre_of_gravity
        xb, yb, zb = p.centre_of_buoyancy
        sr, cr = math.sin(eta[3]), math.cos(eta[3])
        sp, cp = math.sin(eta[4]), math.cos(eta[4])
        return np.array([(w - b) * sp,
                         -(w - b) * cp * sr,
                         -(w - b) * cp * cr,
                         -(yg * w - yb * b) * cp * cr + (zg * w - zb * b) * cp * sr,
                         (zg * w - zb * b) * sp + (xg * w - xb * b) * cp * cr,
                         -(xg * w - xb * b) * cp * sr - (yg * w - yb * b) * sp])

    def derivative(self, eta: np.ndarray, nu: np.ndarray, tau: np.ndarray,
                   current: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(eta', nu') under the body wrench ``tau`` (6) and a current [north, east, down] [m/s]."""
        r = rotation(eta[3], eta[4], eta[5])
        nu_c = np.concatenate([r.T @ current, np.zeros(3)])
        nu_r = nu - nu_c
        nu_c_dot = np.concatenate([-np.cross(nu[3:], nu_c[:3]), np.zeros(3)])
        damping = (self.linear_damping + self.quadratic_damping * np.abs(nu_r)) * nu_r
        force = tau - coriolis(self.mass, nu_r) @ nu_r - damping - self.restoring(eta)
        eta_dot = np.concatenate([r @ nu[:3], euler_rates(eta[3], eta[4]) @ nu[3:]])
        return eta_dot, nu_c_dot + self.mass_inverse @ force
