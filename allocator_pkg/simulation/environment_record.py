"""A case's environment series, generated once before the run (:class:`~.series.Record`,
looked up per step): the wind's gust from its spectrum (:mod:`.spectra`), its direction's
fluctuation (a first-order spectrum), and from a JONSWAP sea the slowly varying drift factor
(:mod:`.wave_drift`, Newman) and the first-order wave motion (:mod:`.wave_motion`), all by the
random-phase method (:mod:`.series`) from one generator seeded by the scenario's seed.

Columns: ``gust`` [m/s] about the mean wind speed, ``wind_direction`` [deg] about the mean
direction, ``drift`` the factor on the mean wave drift (mean 1), ``north``, ``east`` [m] and
``yaw`` [rad] of the wave-frequency motion, each for the scale 1 of the weather (the environment
scales them). The vessel's heading for the wave motion's response is the set-point's. A spread
sea (``wave_spreading`` n > 0) gives each component a random direction from the cos^n spreading
(:func:`~.spreading.sample_directions`, drawn after the sea's phases, so a long-crested record is
the same draw as ever); the wave motion takes each component from its own direction. The drift
factor is Newman's with one drift coefficient for every frequency and direction: the squared
envelope of the elevation at the body origin, whose statistics a spreading leaves as they are
(the point spectrum is the same), so spreading changes the slowly varying drift only through
its mean (:meth:`~.environment.Environment.drift_load`: the spreading-weighted mean of the
long-crested drift over the directions).
"""

from __future__ import annotations

import math

import numpy as np

from ..hull.environment_loads import VesselParticulars
from . import spectra
from .environment_spec import EnvironmentSpec
from .series import Record, amplitudes, analytic_series, grid, real_series
from .spreading import sample_directions
from .wave_drift import drift_factor
from .wave_motion import body_motion, to_ned

RECORD_STEP = 0.1
"""[s] between a record's samples (waves of 2 s period are 20 samples long)."""
RECORD_MARGIN = 120.0
"""[s] a record covers beyond the run (the closed loop's warm-up)."""
SEED_STREAM = 1
"""The record's generator is ``default_rng([seed, SEED_STREAM])``, apart from the Gauss-Markov
processes' ``default_rng(seed)``."""


def wave_components(spec: EnvironmentSpec, n: int, df: float,
                    generator: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """(omega [rad/s], complex elevation amplitudes) of the spec's JONSWAP sea on the record's grid."""
    omega = 2.0 * math.pi * df * np.arange(n // 2 + 1)
    gamma = spec.peak_factor if spec.peak_factor > 0.0 else None
    per_hz = 2.0 * math.pi * spectra.jonswap(omega, spec.wave_height, spec.wave_period, gamma)
    return omega, amplitudes(per_hz, df, generator)


def build_record(spec: EnvironmentSpec, seed: int, particulars: VesselParticulars | None, duration: float,
                 heading: float) -> Record | None:
    """The spec's series over ``duration`` [s] (plus :data:`RECORD_MARGIN`), None when it asks for
    none (a first-order gust and no wave spectrum)."""
    if spec.wind_spectrum == "first_order" and spec.wave_spectrum == "none":
        return None
    n, df = grid(duration + RECORD_MARGIN, RECORD_STEP)
    f = df * np.arange(n // 2 + 1)
    generator = np.random.default_rng([seed, SEED_STREAM])
    columns = {name: np.zeros(n) for name in ("gust", "wind_direction", "drift", "north", "east", "yaw")}
    if spec.wind_spectrum != "first_order":
        gust = spectra.wind_spectrum(spec.wind_spectrum, f, spec.wind_speed)
        columns["gust"] = real_series(amplitudes(gust, df, generator), n)
        variation = spec.wind_direction_variation
        if variation.sigma > 0.0:
            turning = spectra.first_order(f, variation.sigma, variation.time_constant)
            columns["wind_direction"] = real_series(amplitudes(turning, df, generator), n)
    if spec.wave_spectrum == "jonswap":
        omega, elevation = wave_components(spec, n, df, generator)
        columns["drift"] = drift_factor(analytic_series(elevation, n))
        if particulars is not None:
            spread = sample_directions(spec.wave_spreading, omega.size, generator)
            relative = math.radians(spec.wave_direction) - heading + spread
            surge, sway, yaw = (real_series(c, n) for c in
                                body_motion(elevation, omega, relative, particulars.lpp, particulars.beam))
            columns["north"], columns["east"] = to_ned(surge, sway, heading)
            columns["yaw"] = yaw
    return Record(RECORD_STEP, columns)
