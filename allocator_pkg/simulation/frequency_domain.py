"""A fast screening estimate of the station-keeping excursion: the closed loop linearised about
the mean environment, in the frequency domain (Fossen 2021, 11.2; Sorensen 2011, the linear
low-frequency model), excited by the force spectra of the environment's slow variations.

The vessel on its set-point (heading psi0, body axes along NED turned by it) with a small motion
x = [north, east, yaw] in body axes answers a force F by

    (-w^2 M + i w D + C(i w) / (1 + i w T)) x = F,   C(s) = Kp + Kd s + Ki / s,

M the mass with added mass, D the hull's damping linearised in the mean current (the Jacobian
of :meth:`~.vessel.Vessel.derivative`), C the controller's PID (:mod:`.controller`) and T the
thrusters' first-order lag. The excursion's variance per DOF is int_0^inf (H S_F H^*)_ii dw,
H the inverse of the bracket and S_F the one-sided force spectrum [(N, N m)^2 s/rad] of:

- the gust, linearised: F_w (U + u)^2 / U^2 ~ F_w (1 + 2 u / U), so S = (2 / U)^2 F_w F_w^T S_u;
- the slowly varying drift F_d q(t): S = F_d F_d^T S_q, Newman's (:mod:`.wave_drift`);
- the current's speed and direction, each a Gauss-Markov process: S = g g^T S_x, g the
  derivative of the hull's current force at rest (central differences).

The allocator, the thrusters' limits and the controller's sampling are left out; the wave-frequency
motion does not enter the loop.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .controller import Gains
from .vessel import Vessel

SPEED_STEP = 0.01
"""[m/s] of the current speed's central difference."""
DIRECTION_STEP = 1e-3
"""[rad] of the current direction's central difference."""


@dataclass(frozen=True)
class LinearLoop:
    """M and D [SI, surge, sway, yaw], the controller's gains and the thrusters' lag [s]."""

    mass: np.ndarray
    damping: np.ndarray
    gains: Gains
    lag: float

    def receptance(self, omega: np.ndarray) -> np.ndarray:
        """(n, 3, 3) complex H(i w) at ``omega`` [rad/s] > 0."""
        kp, kd, ki = (np.diag(np.array(v, dtype=float)) for v in (self.gains.kp, self.gains.kd, self.gains.ki))
        s = 1j * np.asarray(omega, dtype=float)[:, None, None]
        dynamic = s * s * self.mass + s * self.damping + (kp + kd * s + ki / s) / (1.0 + s * self.lag)
        return np.linalg.inv(dynamic)

    def excursion_std(self, omega: np.ndarray, force_spectrum: np.ndarray) -> np.ndarray:
        """[north/surge [m], east/sway [m], yaw [rad]] standard deviations under the one-sided
        ``force_spectrum`` (n, 3, 3) at the even grid ``omega``."""
        h = self.receptance(omega)
        response = np.einsum("nij,njk,nlk->nil", h, force_spectrum, h.conj()).real
        variance = np.trapezoid(np.diagonal(response, axis1=1, axis2=2), omega, axis=0)
        return np.sqrt(np.maximum(variance, 0.0))


def rest_force(vessel: Vessel, current: np.ndarray, heading: float = 0.0) -> np.ndarray:
    """[X, Y, N] the current [north, east] puts on the hull at rest (M nu' with no other force)."""
    _, nu_dot = vessel.derivative(np.array([0.0, 0.0, heading]), np.zeros(3), np.zeros(3), np.asarray(current))
    return vessel.mass @ nu_dot


def linear_damping(vessel: Vessel, current: np.ndarray, heading: float = 0.0) -> np.ndarray:
    """D = -M d(nu')/d(nu) at rest in the ``current`` [north, east] by central differences."""
    eta = np.array([0.0, 0.0, heading])
    columns = []
    for k, scale in enumerate((1e-5, 1e-5, 1e-7)):
        step = np.zeros(3)
        step[k] = scale
        plus = vessel.derivative(eta, step, np.zeros(3), np.asarray(current))[1]
        minus = vessel.derivative(eta, -step, np.zeros(3), np.asarray(current))[1]
        columns.append(-(vessel.mass @ (plus - minus)) / (2.0 * scale))
    return np.column_stack(columns)


def current_vector(speed: float, direction: float) -> np.ndarray:
    """[north, east] [m/s] of a current of ``speed`` from ``direction`` [rad] (flowing away from it)."""
    return np.array([-speed * math.cos(direction), -speed * math.sin(direction)])


def current_gradients(vessel: Vessel, speed: float, direction: float,
                      heading: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """(dF/d speed [N per m/s], dF/d direction [N per rad]) of :func:`rest_force` at ``heading``."""
    low, high, dd = max(speed - SPEED_STEP, 0.0), speed + SPEED_STEP, DIRECTION_STEP
    by_speed = (rest_force(vessel, current_vector(high, direction), heading)
                - rest_force(vessel, current_vector(low, direction), heading)) / (high - low)
    by_direction = (rest_force(vessel, current_vector(speed, direction + dd), heading)
                    - rest_force(vessel, current_vector(speed, direction - dd), heading)) / (2.0 * dd)
    return by_speed, by_direction


def outer(vector: np.ndarray, spectrum: np.ndarray) -> np.ndarray:
    """(n, 3, 3) v v^T S(w) of a force direction ``vector`` and a scalar one-sided ``spectrum``."""
    v = np.asarray(vector, dtype=float)
    return np.asarray(spectrum, dtype=float)[:, None, None] * np.outer(v, v)[None, :, :]
