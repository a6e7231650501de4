"""Directional spreading of a short-crested sea, DNV-RP-C205 (3.5.8.4):

    D(theta) = Gamma(1 + n/2) / (sqrt(pi) Gamma(1/2 + n/2)) cos^n(theta - theta_p),  |theta - theta_p| <= pi/2,

zero beyond, ``n`` the spreading exponent (the standard's cos^n form; n = 2s of the cos^(2s)
form; 2 to 4 for wind seas, higher for swell), integrating to 1 over directions. n = 0 here
means long-crested (every component from theta_p), not the uniform half-plane cos^0 would give.

The simulation spreads the sea by a random direction per wave component drawn from D
(:func:`sample_directions`, inverse transform sampling on a fine grid of D's distribution
function): each frequency keeps its JONSWAP energy, so the point spectrum is unchanged, and the
directions' distribution tends to D as the components grow in number. Mean values over the
directions (the mean wave drift of a spread sea) are the D-weighted integrals of
:func:`spread_mean` (composite Gauss-Legendre quadrature over [-pi/2, pi/2]).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

GRID_POINTS = 4001
"""Points of the grid of D's distribution function the directions are drawn on."""
PANELS = 12
"""Panels of 15 deg of :func:`spread_mean`'s composite quadrature (the drift's kinks in a panel
cost accuracy in that panel only)."""
PANEL_POINTS = 8
"""Gauss-Legendre points per panel."""


def check_exponent(exponent: float, key: str) -> float:
    """``exponent`` as a float when finite and >= 0, else a ValueError naming ``key``."""
    if isinstance(exponent, bool) or not isinstance(exponent, (int, float)) or not math.isfinite(exponent) \
            or exponent < 0.0:
        raise ValueError(f"{key}: the spreading exponent n of cos^n, a finite number >= 0 (0: long-crested), "
                         f"not {exponent!r}")
    return float(exponent)


def normalisation(exponent: float) -> float:
    """Gamma(1 + n/2) / (sqrt(pi) Gamma(1/2 + n/2)), by log-Gamma (finite for large n)."""
    return math.exp(math.lgamma(1.0 + exponent / 2.0) - math.lgamma(0.5 + exponent / 2.0)) / math.sqrt(math.pi)


def density(theta: np.ndarray, exponent: float) -> np.ndarray:
    """D(theta) [1/rad] about theta_p = 0 for ``exponent`` n > 0."""
    theta = np.asarray(theta, dtype=float)
    inside = np.abs(theta) <= math.pi / 2.0
    return np.where(inside, normalisation(exponent) * np.cos(np.where(inside, theta, 0.0)) ** exponent, 0.0)


def sample_directions(exponent: float, count: int, generator: np.random.Generator) -> np.ndarray:
    """``count`` directions [rad] about theta_p = 0 drawn from D (zeros when long-crested, no
    draw taken from ``generator``)."""
    if exponent == 0.0:
        return np.zeros(count)
    theta = np.linspace(-math.pi / 2.0, math.pi / 2.0, GRID_POINTS)
    weights = density(theta, exponent)
    cumulative = np.concatenate([[0.0], np.cumsum((weights[1:] + weights[:-1]) / 2.0 * np.diff(theta))])
    cumulative /= cumulative[-1]
    return np.interp(generator.uniform(0.0, 1.0, count), cumulative, theta)


def spread_mean(function: Callable[[float], np.ndarray], exponent: float) -> np.ndarray:
    """int D(theta) f(theta) dtheta of a vector function f of the direction [rad] relative to
    theta_p; f(0) when long-crested."""
    if exponent == 0.0:
        return np.asarray(function(0.0), dtype=float)
    nodes, weights = np.polynomial.legendre.leggauss(PANEL_POINTS)
    half = math.pi / (2.0 * PANELS)
    centres = -math.pi / 2.0 + half * (2.0 * np.arange(PANELS) + 1.0)
    theta = (centres[:, np.newaxis] + half * nodes[np.newaxis, :]).ravel()
    values = np.array([np.asarray(function(float(t)), dtype=float) for t in theta])
    return np.tensordot(np.tile(weights, PANELS) * half * density(theta, exponent), values, axes=1)
