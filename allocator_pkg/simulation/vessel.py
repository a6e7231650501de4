"""The DP vessel in surge, sway and yaw, after the offshore supply vessel ``osv`` of Fossen's
MSS toolbox (``CRAFT/SHIP/models/osv.m``), reduced to the horizontal plane:

    M nu_r' + C(nu_r) nu_r + D nu_r - tau_surge(u_r) - tau_crossflow(nu_r) = tau + tau_env
    nu = nu_r + nu_c,   eta' = R(psi) nu

(Fossen 2021, (6.111)-(6.116) with an irrotational current, Property 10.1), where nu_r is the
velocity through the water. Values from osv.m: L 83 m, B 18 m, T 5 m, Cb 0.65, rho 1025,
m = rho Cb L B T, the centre of gravity 4.5 m aft of the body origin (midships), radius of
gyration in yaw 0.25 L, linear damping M_ii / T_i with T1 = T2 = 100 s and T6 = 1 s, surge
damping blended from linear to quadratic with 1 - tanh(|u_r| / 2 m/s), and cross-flow drag
over 20 strips. The added mass, MA11 1e6 kg, MA22 3e6 kg, MA26 -6e6 kg m, MA66 1.156e9 kg m^2
(supply.mat at its lowest frequency), is that of osv.m as MSS published it under
``VESSELS/models/`` before its 2025-03 release; the release that moved it to ``CRAFT/SHIP/``
recomputed it as 6e5 kg, 2e6 kg, -9.1e6 kg m and 1.2416e9 kg m^2.

The quadratic drag coefficients are those of ``analysis.environment_loads`` (current_surge
over B T, current_sway as the 2-D cross-flow coefficient), which the DP capability analysis
uses; the linear damping comes on top and the analysis leaves it out. So a current loads
this hull more than the capability balance says: at rest in a 0.75 m/s beam current it feels
143.6 kN of sway force against the balance's 83.8 kN, the difference being M_22 / T2 times
the current (59.8 kN).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..hull.environment_loads import LoadCoefficients

STRIPS = 20
"""Hull strips of the cross-flow drag integral."""
_sum = np.add.reduce
"""``ndarray.sum`` of a vector without its method's overhead (the same pairwise sum)."""


@dataclass(frozen=True)
class VesselParameters:
    """A ship-shaped hull in the horizontal plane (osv.m values by default)."""

    length: float = 83.0
    beam: float = 18.0
    draught: float = 5.0
    block_coefficient: float = 0.65
    water_density: float = 1025.0
    x_g: float = -4.5
    """x [m] of the centre of gravity from the body origin."""
    yaw_gyration: float = 0.25
    """Radius of gyration in yaw as a share of the length."""
    added_mass: tuple[float, float, float, float] = (1.0e6, 3.0e6, -6.0e6, 1.156e9)
    """MA11 [kg], MA22 [kg], MA26 [kg m], MA66 [kg m^2]."""
    time_constants: tuple[float, float, float] = (100.0, 100.0, 1.0)
    """T1, T2, T6 [s] of the linear damping."""
    crossover_speed: float = 2.0
    """[m/s] where surge damping turns from linear to quadratic."""
    coefficients: LoadCoefficients = field(default_factory=LoadCoefficients)

    @property
    def mass(self) -> float:
        return self.water_density * self.block_coefficient * self.length * self.beam * self.draught

    def mass_matrix(self) -> np.ndarray:
        """M = M_RB + M_A in surge, sway, yaw about the body origin."""
        m, xg = self.mass, self.x_g
        inertia = m * (self.yaw_gyration * self.length) ** 2 + m * xg ** 2
        a11, a22, a26, a66 = self.added_mass
        return np.array([[m + a11, 0.0, 0.0], [0.0, m + a22, m * xg + a26], [0.0, m * xg + a26, inertia + a66]])

    @property
    def surge_quadratic(self) -> float:
        """X_|u|u [N s^2/m^2] (negative): -1/2 rho C B T."""
        return -0.5 * self.water_density * self.coefficients.current_surge * self.beam * self.draught


class Vessel:
    """State eta = [north, east, psi], nu = [u, v, r]; :meth:`derivative` of the pair."""

    dofs = 3

    def __init__(self, parameters: VesselParameters | None = None):
        self.parameters = p = parameters or VesselParameters()
        self.mass = p.mass_matrix()
        self.mass_inverse = np.linalg.inv(self.mass)
        self._mass_rows = (self.mass[0].tolist(), self.mass[1].tolist())
        t1, t2, t6 = p.time_constants
        self.linear_damping = np.diag([self.mass[0, 0] / t1, self.mass[1, 1] / t2, self.mass[2, 2] / t6])
        self._sway_yaw_linear = (-np.diag(self.linear_damping)).tolist()
        self._surge_linear = float(self.linear_damping[0, 0])
        self._surge_quadratic, self._crossover = p.surge_quadratic, p.crossover_speed
        dx = p.length / STRIPS
        self._strips = -p.length / 2.0 + (np.arange(STRIPS) + 0.5) * dx
        self._strip_factor = 0.5 * p.water_density * p.draught * p.coefficients.current_sway * dx

    def _coriolis(self, u: float, v: float, r: float) -> np.ndarray:
        """:func:`~.kinematics.coriolis_planar` of the mass matrix at [u, v, r], its rows as floats kept."""
        (m11, m12, m16), (m21, m22, m26) = self._mass_rows
        sway = m21 * u + m22 * v + m26 * r
        surge = m11 * u + m12 * v + m16 * r
        return np.array([[0.0, 0.0, -sway], [0.0, 0.0, surge], [sway, -surge, 0.0]])

    def surge_damping(self, u_r: float) -> float:
        """X [N] of the hull moving at u_r through the water: sigma Xu u_r + (1 - sigma) X_|u|u
        |u_r| u_r, sigma = 1 - tanh(|u_r| / crossover)."""
        sigma = 1.0 - math.tanh(abs(u_r) / self._crossover)
        return -sigma * self._surge_linear * u_r + (1.0 - sigma) * self._surge_quadratic * abs(u_r) * u_r

    def crossflow(self, v_r: float, r: float) -> np.ndarray:
        """[0, Y, N] of the cross-flow drag: -1/2 rho T Cd |v_r + x r| (v_r + x r) dx over the strips."""
        return np.array([0.0, *self._crossflow(v_r, r)])

    def _crossflow(self, v_r: float, r: float) -> tuple[float, float]:
        """(Y, N) of :meth:`crossflow` as floats."""
        local = v_r + self._strips * r
        drag = -self._strip_factor * np.abs(local) * local
        return float(_sum(drag)), float(_sum(drag * self._strips))

    def derivative(self, eta: np.ndarray, nu: np.ndarray, tau: np.ndarray,
                   current: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(eta', nu') under the body force ``tau`` [X, Y, N] and a current [north, east] [m/s]
        (:meth:`rates` on arrays)."""
        rates = self.rates((*eta.tolist(), *nu.tolist()), tau.tolist(), current.tolist())
        return np.array(rates[:3]), np.array(rates[3:])

    def rates(self, state: tuple[float, ...], tau: list[float], current: list[float]) -> tuple[float, ...]:
        """(eta', nu') as six floats of the state (north, east, psi, u, v, r) under the body force
        ``tau`` [X, Y, N] and a current [north, east] [m/s]: M nu_r' = tau - C(nu_r) nu_r +
        d(nu_r), d the linear damping -D nu_r (D diagonal) with the blended surge damping in
        surge, plus the cross-flow drag; nu' = nu_r' + [r v_c, -r u_c, 0] (Fossen 2021, (6.111)-(6.116)).
        Written on floats where that does each operation as the vector form would; the products
        with M^-1 and C stay numpy's matrix products (their sums the same as every run's)."""
        _, _, psi, u, v, r = state
        c, s = math.cos(psi), math.sin(psi)
        north, east = current
        nu_c = (c * north + s * east, -s * north + c * east)
        u_r, v_r = u - nu_c[0], v - nu_c[1]
        nu_r = np.array([u_r, v_r, r])
        coriolis = (self._coriolis(u_r, v_r, r) @ nu_r).tolist()
        cross_y, cross_n = self._crossflow(v_r, r)
        _, sway, yaw = self._sway_yaw_linear
        x, y, n = tau
        force = np.array([x - coriolis[0] + (self.surge_damping(u_r) + 0.0),
                          y - coriolis[1] + (sway * v_r + cross_y),
                          n - coriolis[2] + (yaw * r + cross_n)])
        accel = (self.mass_inverse @ force).tolist()
        return (c * u - s * v, s * u + c * v, r,
                r * nu_c[1] + accel[0], -r * nu_c[0] + accel[1], 0.0 + accel[2])
