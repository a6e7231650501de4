"""One-sided spectra of the wind's gusts (per Hz) and of the waves' elevation (per rad/s).

Wind, ``u`` the gust about the mean speed ``speed`` [m/s] at 10 m, frequencies ``f`` [Hz]:

- :func:`npd`, the NPD (Froya) spectrum of ISO 19901-1 and DNV-RP-C205 (2.3.4.9), for the
  1-hour mean speed U0 at z = 10 m: S(f) = 320 (U0/10)^2 (z/10)^0.45 / (1 + f~^n)^(5/(3n)),
  f~ = 172 f (z/10)^(2/3) (U0/10)^(-3/4), n = 0.468 [m^2/s^2/Hz]; its variance follows from U0;
- :func:`api`, the API RP 2A-WSD (2.3.2c) gust spectrum S(f) = sigma^2 / (fp (1 + 1.5 f / fp)^(5/3)),
  fp 0.025 Hz, sigma = I U with I = 0.15 (z / 20 m)^(-0.125) at 10 m; integrates to sigma^2;
- :func:`harris`, the Harris spectrum of DNV-RP-C205 (2.3.4.7): f S(f) = 4 kappa U^2 x / (2 + x^2)^(5/6),
  x = L f / U, L 1800 m, kappa the surface drag coefficient (0.0025, open sea).

Waves, ``omega`` [rad/s]: :func:`jonswap`, DNV-RP-C205 (3.5.5): S(w) = A_g S_PM(w)
gamma^exp(-((w - wp) / (s wp))^2 / 2), S_PM(w) = 5/16 Hs^2 wp^4 w^-5 exp(-5/4 (w / wp)^-4),
A_g = 1 - 0.287 ln gamma, s 0.07 below wp and 0.09 above, the peak factor from
:func:`peak_factor` unless given. :func:`first_order` is the Lorentzian spectrum of a first-order
Gauss-Markov process (the wind's direction fluctuation).
"""

from __future__ import annotations

import math

import numpy as np

NPD_EXPONENT = 0.468
"""n of the NPD spectrum."""
API_PEAK = 0.025
"""fp [Hz] of the API spectrum (API RP 2A: 0.01 to 0.1 Hz)."""
API_INTENSITY = 0.15 * 0.5 ** -0.125
"""API RP 2A's turbulence intensity at 10 m: 0.15 (10 / 20)^(-0.125)."""
HARRIS_LENGTH = 1800.0
"""L [m] of the Harris spectrum."""
HARRIS_DRAG = 0.0025
"""kappa, the sea surface drag coefficient of the Harris spectrum."""
WIND_SPECTRA = ("first_order", "npd", "api", "harris")
"""The scenario's ``environment.wind.spectrum`` choices (``first_order``: the Gauss-Markov gust)."""
WAVE_SPECTRA = ("none", "jonswap")
"""The scenario's ``environment.waves.spectrum`` choices (``none``: the drift's Gauss-Markov factor)."""


def npd(f: np.ndarray, speed: float, height: float = 10.0) -> np.ndarray:
    """The NPD gust spectrum [m^2/s^2/Hz] at ``f`` [Hz] for the 1-hour mean ``speed`` [m/s] at 10 m."""
    u, z = speed / 10.0, height / 10.0
    if u == 0.0:
        return np.zeros_like(np.asarray(f, dtype=float))
    reduced = 172.0 * np.asarray(f, dtype=float) * z ** (2.0 / 3.0) * u ** -0.75
    return 320.0 * u * u * z ** 0.45 / (1.0 + reduced ** NPD_EXPONENT) ** (5.0 / (3.0 * NPD_EXPONENT))


def api(f: np.ndarray, speed: float, intensity: float = API_INTENSITY, peak: float = API_PEAK) -> np.ndarray:
    """The API RP 2A gust spectrum [m^2/s^2/Hz]; its variance (intensity speed)^2."""
    sigma = intensity * speed
    return sigma * sigma / (peak * (1.0 + 1.5 * np.asarray(f, dtype=float) / peak) ** (5.0 / 3.0))


def harris(f: np.ndarray, speed: float, drag: float = HARRIS_DRAG, length: float = HARRIS_LENGTH) -> np.ndarray:
    """The Harris gust spectrum [m^2/s^2/Hz] (finite at f = 0: 4 kappa U L / 2^(5/6))."""
    if speed == 0.0:
        return np.zeros_like(np.asarray(f, dtype=float))
    x = length * np.asarray(f, dtype=float) / speed
    return 4.0 * drag * speed * length / (2.0 + x * x) ** (5.0 / 6.0)


def wind_spectrum(name: str, f: np.ndarray, speed: float) -> np.ndarray:
    """The gust spectrum ``name`` of :data:`WIND_SPECTRA` but ``first_order``."""
    spectra = {"npd": npd, "api": api, "harris": harris}
    if name not in spectra:
        raise ValueError(f"environment.wind.spectrum: one of {', '.join(spectra)} here, not {name!r}")
    return spectra[name](f, speed)


def peak_factor(hs: float, tp: float) -> float:
    """DNV-RP-C205 (3.5.5.5): gamma 5 for Tp / sqrt(Hs) <= 3.6, exp(5.75 - 1.15 Tp / sqrt(Hs)) up
    to 5, 1 above."""
    if hs <= 0.0:
        return 1.0
    ratio = tp / math.sqrt(hs)
    if ratio <= 3.6:
        return 5.0
    return 1.0 if ratio >= 5.0 else math.exp(5.75 - 1.15 * ratio)


def jonswap(omega: np.ndarray, hs: float, tp: float, gamma: float | None = None) -> np.ndarray:
    """The JONSWAP spectrum [m^2 s/rad] at ``omega`` [rad/s] (zero at omega 0)."""
    w = np.asarray(omega, dtype=float)
    if hs <= 0.0 or tp <= 0.0:
        return np.zeros_like(w)
    gamma = peak_factor(hs, tp) if gamma is None else gamma
    wp = 2.0 * math.pi / tp
    out = np.zeros_like(w)
    live = w > 0.0
    x = w[live]
    pm = 5.0 / 16.0 * hs * hs * wp ** 4 * x ** -5 * np.exp(-1.25 * (x / wp) ** -4)
    width = np.where(x <= wp, 0.07, 0.09)
    out[live] = (1.0 - 0.287 * math.log(gamma)) * pm * gamma ** np.exp(-0.5 * ((x - wp) / (width * wp)) ** 2)
    return out


def first_order(f: np.ndarray, sigma: float, time_constant: float) -> np.ndarray:
    """The one-sided spectrum [unit^2/Hz] of x' = -x / T + w with stationary deviation ``sigma``:
    4 sigma^2 T / (1 + (2 pi f T)^2)."""
    return 4.0 * sigma * sigma * time_constant / (1.0 + (2.0 * math.pi * np.asarray(f, dtype=float)
                                                          * time_constant) ** 2)
