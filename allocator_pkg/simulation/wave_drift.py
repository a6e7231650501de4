"""The slowly varying wave drift by Newman's approximation (Newman 1974; Faltinsen 1990, 5.4;
Fossen 2021, 10.2.2): of a sea of components a_k cos(w_k t + phi_k), the difference-frequency
drift is

    F_sv(t) = 2 (sum_k a_k sqrt(T(w_k)) cos(w_k t + phi_k))^2 less its sum-frequency terms
            = |sum_k a_k sqrt(T(w_k)) exp(i (w_k t + phi_k))|^2,

T(w) the mean drift per squared amplitude in regular waves. Here T is one constant over the sea's
spectrum, the one that makes the mean of F_sv the mean drift ``F`` the caller gives (the
standard's wave formula at the condition): F_sv(t) = F q(t), q = |zeta(t)|^2 / sum_k a_k^2 with
zeta the analytic wave elevation (:func:`~.series.analytic_series`), mean 1. Its spectrum is
Newman's (Faltinsen 1990, eq. 5.47, T constant):

    S_q(mu) = 2 int S(w) S(w + mu) dw / m0^2,   mu > 0,   int S_q = 1,

so the slowly varying drift's standard deviation equals its mean (:func:`newman_spectrum`).
"""

from __future__ import annotations

import numpy as np


def drift_factor(zeta: np.ndarray) -> np.ndarray:
    """q(t) = |zeta|^2 / mean |zeta|^2 of the analytic elevation ``zeta`` (mean 1; zeros in calm)."""
    power = np.abs(zeta) ** 2
    mean = float(np.mean(power))
    return power / mean if mean > 0.0 else np.zeros_like(power)


def newman_spectrum(mu: np.ndarray, omega: np.ndarray, spectrum: np.ndarray) -> np.ndarray:
    """S_q(mu) [1/(rad/s)] of the drift factor for a wave ``spectrum`` given on the even grid
    ``omega`` [rad/s]: 2 int S(w) S(w + mu) dw / m0^2 by the trapezoidal rule."""
    omega = np.asarray(omega, dtype=float)
    spectrum = np.asarray(spectrum, dtype=float)
    m0 = np.trapezoid(spectrum, omega)
    shifted = [np.interp(omega + m, omega, spectrum, right=0.0) for m in np.atleast_1d(mu)]
    return np.array([2.0 * np.trapezoid(spectrum * s, omega) for s in shifted]) / (m0 * m0)
