"""The one-sided spectra [(N, N m)^2 s/rad] of the slowly varying environmental forces on a
vessel held at a heading, as :mod:`.frequency_domain` takes them: the gust's (linearised about
the mean wind load), the slowly varying wave drift's (Newman's, or the drift factor's first-order
process without a wave spectrum) and the current's speed and direction variations (through the
hull's current force at rest). The wind direction's fluctuation is left out.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..hull.environment_loads import VesselParticulars
from . import spectra
from .environment import Environment, EnvironmentSpec
from .frequency_domain import current_gradients, outer
from .vessel import Vessel
from .wave_drift import newman_spectrum

WAVE_GRID = np.linspace(0.02, 4.0, 2000)
"""[rad/s] where a JONSWAP sea is sampled for Newman's spectrum."""


def per_rad(per_hz: np.ndarray) -> np.ndarray:
    """A one-sided spectrum per Hz as one per rad/s: S(w) = S(f) / (2 pi)."""
    return np.asarray(per_hz) / (2.0 * math.pi)


def gust_spectrum(spec: EnvironmentSpec, omega: np.ndarray) -> np.ndarray:
    """S_u(w) [m^2/s^2 s/rad] of the spec's gust."""
    f = np.asarray(omega) / (2.0 * math.pi)
    if spec.wind_spectrum == "first_order":
        return per_rad(spectra.first_order(f, spec.gusts.sigma, spec.gusts.time_constant))
    return per_rad(spectra.wind_spectrum(spec.wind_spectrum, f, spec.wind_speed))


def drift_spectrum(spec: EnvironmentSpec, omega: np.ndarray) -> np.ndarray:
    """S [1/(rad/s)] of the factor on the mean drift: Newman's of the JONSWAP sea, or the
    first-order drift variation's."""
    if spec.wave_spectrum == "none":
        f = np.asarray(omega) / (2.0 * math.pi)
        return per_rad(spectra.first_order(f, spec.drift_variation.sigma, spec.drift_variation.time_constant))
    gamma = spec.peak_factor if spec.peak_factor > 0.0 else None
    sea = spectra.jonswap(WAVE_GRID, spec.wave_height, spec.wave_period, gamma)
    if not np.any(sea > 0.0):
        return np.zeros_like(np.asarray(omega, dtype=float))
    return newman_spectrum(omega, WAVE_GRID, sea)


def gust_force_spectrum(spec: EnvironmentSpec, particulars: VesselParticulars | None, omega: np.ndarray,
                        heading: float = 0.0) -> np.ndarray:
    """(n, 3, 3) one-sided spectrum of the gust's force on the hull at ``heading`` [rad], linearised
    about the mean wind load: (2 / U)^2 F_w F_w^T S_u (zeros without wind)."""
    omega = np.asarray(omega, dtype=float)
    if spec.wind_speed <= 0.0:
        return np.zeros((omega.size, 3, 3))
    means = Environment(replace(spec, wind_spectrum="first_order", wave_spectrum="none"), 0, particulars)
    return outer(2.0 * means.wind_load(heading, mean=True) / spec.wind_speed, gust_spectrum(spec, omega))


def force_spectrum(spec: EnvironmentSpec, particulars: VesselParticulars | None, vessel: Vessel,
                   omega: np.ndarray, heading: float = 0.0) -> np.ndarray:
    """(n, 3, 3) one-sided force spectrum on the hull at ``heading`` [rad] at ``omega`` [rad/s]."""
    omega = np.asarray(omega, dtype=float)
    means = Environment(replace(spec, wind_spectrum="first_order", wave_spectrum="none"), 0, particulars)
    total = gust_force_spectrum(spec, particulars, omega, heading)
    total += outer(means.drift_load(heading, mean=True), drift_spectrum(spec, omega))
    f = omega / (2.0 * math.pi)
    by_speed, by_direction = current_gradients(vessel, spec.current_speed, math.radians(spec.current_direction),
                                                  heading)
    speed, direction = spec.current_speed_variation, spec.current_direction_variation
    total += outer(by_speed, per_rad(spectra.first_order(f, speed.sigma, speed.time_constant)))
    total += outer(by_direction, per_rad(spectra.first_order(f, math.radians(direction.sigma),
                                                             direction.time_constant)))
    return total
