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
from bisect import bisect_left
from dataclasses import dataclass, field

import numpy as np

from ..hull.environment_loads import LoadCoefficients

STRIPS = 20
"""Hull strips of the cross-flow drag integral."""


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
        self._inverse_rows = tuple(self.mass_inverse.tolist())
        t1, t2, t6 = p.time_constants
        self.linear_damping = np.diag([self.mass[0, 0] / t1, self.mass[1, 1] / t2, self.mass[2, 2] / t6])
        self._sway_yaw_linear = (-np.diag(self.linear_damping)).tolist()
        self._surge_linear = float(self.linear_damping[0, 0])
        self._surge_quadratic, self._crossover = p.surge_quadratic, p.crossover_speed
        dx = p.length / STRIPS
        self._strips = (-p.length / 2.0 + (np.arange(STRIPS) + 0.5) * dx).tolist()
        self._strip_factor = 0.5 * p.water_density * p.draught * p.coefficients.current_sway * dx
        self._power_sums = [[0.0] * (STRIPS + 1) for _ in range(4)]
        for k, x in enumerate(self._strips):
            for j, sums in enumerate(self._power_sums):
                sums[k + 1] = sums[k] + x ** j

    def surge_damping(self, u_r: float) -> float:
        """X [N] of the hull moving at u_r through the water: sigma Xu u_r + (1 - sigma) X_|u|u
        |u_r| u_r, sigma = 1 - tanh(|u_r| / crossover)."""
        sigma = 1.0 - math.tanh(abs(u_r) / self._crossover)
        return -sigma * self._surge_linear * u_r + (1.0 - sigma) * self._surge_quadratic * abs(u_r) * u_r

    def crossflow(self, v_r: float, r: float) -> np.ndarray:
        """[0, Y, N] of the cross-flow drag: -1/2 rho T Cd |v_r + x r| (v_r + x r) dx over the strips."""
        return np.array([0.0, *self._crossflow(v_r, r)])

    def _crossflow(self, v_r: float, r: float) -> tuple[float, float]:
        """(Y, N) of :meth:`crossflow` as floats, the strip sum in closed form: the local flow
        w_k = v_r + x_k r changes sign once along the hull, so with s_k its sign
        sum s_k w_k^2 = v_r^2 S_0 + 2 v_r r S_1 + r^2 S_2 and sum s_k w_k^2 x_k = v_r^2 S_1 +
        2 v_r r S_2 + r^2 S_3, S_j = sum s_k x_k^j from the strips' running power sums."""
        if r > 0.0:
            first, last = bisect_left(self._strips, -v_r / r), STRIPS      # w >= 0 from x = -v_r / r to the bow
        elif r < 0.0:
            first, last = 0, bisect_left(self._strips, -v_r / r)           # w > 0 from the stern to x = -v_r / r
        else:
            first, last = 0, (STRIPS if v_r >= 0.0 else 0)
        s0, s1, s2, s3 = (2.0 * (sums[last] - sums[first]) - sums[STRIPS] for sums in self._power_sums)
        k, vv, vr, rr = self._strip_factor, v_r * v_r, 2.0 * v_r * r, r * r
        return -k * (vv * s0 + vr * s1 + rr * s2), -k * (vv * s1 + vr * s2 + rr * s3)

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
        surge, plus the cross-flow drag; nu' = nu_r' + [r v_c, -r u_c, 0] (Fossen 2021,
        (6.111)-(6.116)), C(nu_r) nu_r = [-a_2 r, a_1 r, a_2 u_r - a_1 v_r] with a = M nu_r
        (:func:`~.kinematics.coriolis_planar`)."""
        _, _, psi, u, v, r = state
        c, s = math.cos(psi), math.sin(psi)
        north, east = current
        u_c, v_c = c * north + s * east, -s * north + c * east
        u_r, v_r = u - u_c, v - v_c
        (m11, m12, m16), (m21, m22, m26) = self._mass_rows
        surge = m11 * u_r + m12 * v_r + m16 * r
        sway = m21 * u_r + m22 * v_r + m26 * r
        cross_y, cross_n = self._crossflow(v_r, r)
        _, sway_linear, yaw_linear = self._sway_yaw_linear
        x, y, n = tau
        fx = x + sway * r + self.surge_damping(u_r)
        fy = y - surge * r + sway_linear * v_r + cross_y
        fn = n - (sway * u_r - surge * v_r) + yaw_linear * r + cross_n
        (i11, i12, i16), (i21, i22, i26), (i61, i62, i66) = self._inverse_rows
        return (c * u - s * v, s * u + c * v, r,
                r * v_c + i11 * fx + i12 * fy + i16 * fn,
                -r * u_c + i21 * fx + i22 * fy + i26 * fn,
                i61 * fx + i62 * fy + i66 * fn)
