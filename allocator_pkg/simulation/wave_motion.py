"""The first-order (wave-frequency) motion the position measurement sees, from the wave
components: a documented simple response model, a hull that moves with the water in long waves.

Waves from ``direction`` beta [rad] relative to the bow (clockwise) run along p = (-cos beta,
-sin beta) in the body frame. A component of complex amplitude c (elevation Re c exp(i w t) at
the body origin, deep water, k = w^2 / g) moves the surface water along p by Re(-i c exp(i (w t -
k p.r))) (linear theory, Faltinsen 1990 ch. 2). The hull's surge and sway are that displacement
averaged over the waterplane L x B (a factor sinc(k p_x L / 2) sinc(k p_y B / 2)), its yaw the
least-squares slope along the length of the sway displacement, (12 / L^3) int x y(x) dx, which is
i kappa (12 / L^3) 2 (sin u - u cos u) / kappa^3 per unit sway at the origin, kappa = k cos beta,
u = kappa L / 2 (k cos beta itself in long waves). Short waves against a long hull average out;
long waves move it as the water. No inertia, no resonance: a response model for the measurement,
not a seakeeping analysis.
"""

from __future__ import annotations

import math

import numpy as np

from ..hull.environment_loads import GRAVITY


def _sinc(u: np.ndarray) -> np.ndarray:
    return np.sinc(u / math.pi)


def _slope(kappa: np.ndarray, length: float) -> np.ndarray:
    """(12 / L^3) int_{-L/2}^{L/2} x exp(i kappa x) dx / i, finite at kappa 0."""
    u = kappa * length / 2.0
    small = np.abs(u) < 1e-4
    safe = np.where(small, 1.0, u)
    exact = 12.0 / length ** 3 * 2.0 * (np.sin(safe) - safe * np.cos(safe)) / np.where(small, 1.0, kappa) ** 2
    return np.where(small, kappa, exact)


def transfer(omega: np.ndarray, direction: float | np.ndarray, length: float, beam: float) -> np.ndarray:
    """(3, n) complex body-frame [surge [m], sway [m], yaw [rad]] per unit complex elevation
    amplitude at ``omega`` [rad/s], from ``direction`` [rad] (one, or one per component: a spread sea)."""
    k = np.asarray(omega, dtype=float) ** 2 / GRAVITY
    px, py = -np.cos(direction), -np.sin(direction)
    displacement = -1j * _sinc(k * px * length / 2.0) * _sinc(k * py * beam / 2.0)
    yaw = py * (-1j) * 1j * _slope(-k * px, length) * _sinc(k * py * beam / 2.0)
    return np.vstack([px * displacement, py * displacement, yaw])


def body_motion(coefficients: np.ndarray, omega: np.ndarray, direction: float | np.ndarray, length: float,
                beam: float) -> np.ndarray:
    """(3, n) complex amplitudes of the body-frame motion of elevation ``coefficients`` at ``omega``."""
    return transfer(omega, direction, length, beam) * np.asarray(coefficients)[np.newaxis, :]


def to_ned(surge: np.ndarray, sway: np.ndarray, heading: float) -> tuple[np.ndarray, np.ndarray]:
    """(north, east) of body-frame displacements at ``heading`` [rad]."""
    c, s = math.cos(heading), math.sin(heading)
    return c * surge - s * sway, s * surge + c * sway
