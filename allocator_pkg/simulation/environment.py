"""A seeded environment: a current with a slowly varying speed and direction, wind with gusts
and slowly varying wave drift for the vessel, and with a wave spectrum the first-order wave motion
the position measurement sees; a current for the ROV.

Every slow variation is a first-order Gauss-Markov process x' = -x / T + w (the form Fossen
2021 gives the slowly varying current speed), discretised exactly: x_k+1 = a x_k + sqrt(1 - a^2) sigma e_k,
a = exp(-dt / T), e_k standard normal from one ``numpy`` generator seeded by the scenario, so
its stationary standard deviation is sigma and its correlation time T. The gusts are such a
process for the wind speed (turbulence intensity sigma / mean) unless the scenario names a gust
spectrum (``environment.wind.spectrum``: NPD, API or Harris); the slowly varying wave drift is
the mean drift of ``hull.environment_loads.wave_drift_load`` times (1 + such a process) unless the
scenario names a wave spectrum (``environment.waves.spectrum: jonswap``: Newman's drift and the
wave motion), in a spread sea (``environment.waves.spreading``, :mod:`.spreading`) the mean drift
the long-crested drift averaged over the directions weighted by the spreading. A spectrum's
series are generated once per run (:mod:`.environment_record`) and
looked up per step. The mean wind load and the mean drift may come from the caller
(``mean_wind_load``, ``mean_drift_load``: the Level 3 case passes the standard's), the gusts then
scaling the mean wind load by (U / U_mean)^2 and the drift factor the mean drift. Directions are
where the environment comes from, in degrees clockwise from north. ``scale`` (1 unless a
scenario's weather ramp changes it) multiplies the current's speed, the wind's speed and the
significant wave height, variations included.
"""

from __future__ import annotations

import math

import numpy as np

from ..hull.environment_loads import VesselParticulars, wave_drift_load, wind_load
from .environment_record import build_record
from .environment_spec import EnvironmentSpec, SlowVariation
from .spreading import spread_mean


class GaussMarkov:
    """x_k+1 = a x_k + sqrt(1 - a^2) sigma e_k, starting at 0."""

    def __init__(self, variation: SlowVariation, generator: np.random.Generator):
        self.variation = variation
        self.generator = generator
        self.value = 0.0

    def step(self, dt: float) -> float:
        a = math.exp(-dt / self.variation.time_constant)
        self.value = a * self.value + math.sqrt(1.0 - a * a) * self.variation.sigma * self.generator.standard_normal()
        return self.value


class Environment:
    """Current [north, east, down] and, for a hull with particulars, the wind and wave-drift
    load [X, Y, N] in the body frame and the wave motion; one :meth:`step` per simulation step.
    ``duration`` [s]: how long the spectra's series run before they repeat; ``heading`` [rad]:
    the set-point heading the wave motion's response is taken at."""

    def __init__(self, spec: EnvironmentSpec, seed: int, particulars: VesselParticulars | None = None,
                 duration: float = 3600.0, heading: float = 0.0):
        self.spec = spec
        self.particulars = particulars
        generator = np.random.default_rng(seed)
        self._speed = GaussMarkov(spec.current_speed_variation, generator)
        self._direction = GaussMarkov(spec.current_direction_variation, generator)
        self._gust = GaussMarkov(spec.gusts, generator)
        self._drift = GaussMarkov(spec.drift_variation, generator)
        self._processes = [self._speed, self._direction]
        self._processes += [self._gust] if spec.wind_spectrum == "first_order" else []
        self._processes += [self._drift] if spec.wave_spectrum == "none" else []
        self.record = build_record(spec, seed, particulars, duration, heading)
        self._row = self.record.at(0.0) if self.record is not None else None
        self.time = 0.0
        self.scale = 1.0

    def step(self, dt: float) -> None:
        for process in self._processes:
            process.step(dt)
        self.time += dt
        if self.record is not None:
            self._row = self.record.at(self.time)

    def _series(self, name: str) -> float:
        return float(self._row[self.record.index[name]])

    def current(self, mean: bool = False) -> np.ndarray:
        """[north, east, down] [m/s] of the water (``mean``: without its slow variation), flowing
        away from where it comes from."""
        speed = self.spec.current_speed + (0.0 if mean else self._speed.value)
        direction = math.radians(self.spec.current_direction + (0.0 if mean else self._direction.value))
        speed = max(0.0, speed) * self.scale
        return np.array([-speed * math.cos(direction), -speed * math.sin(direction), self.spec.current_down])

    def mean_current(self) -> np.ndarray:
        return self.current(mean=True)

    def wind_speed(self, mean: bool = False) -> float:
        """[m/s] now (``mean``: without the gust), scaled."""
        if mean:
            return self.spec.wind_speed * self.scale
        gust = self._gust.value if self.spec.wind_spectrum == "first_order" else self._series("gust")
        return max(0.0, self.spec.wind_speed + gust) * self.scale

    def wind_direction(self, mean: bool = False) -> float:
        """[deg] where the wind comes from now (``mean``: without its fluctuation)."""
        if mean or self.spec.wind_spectrum == "first_order":
            return self.spec.wind_direction
        return self.spec.wind_direction + self._series("wind_direction")

    def wind_load(self, heading: float, mean: bool = False) -> np.ndarray:
        """[X, Y, N] of the wind at ``heading`` [rad] (``mean``: of the mean wind); the caller's mean
        load times (U / U_mean)^2 when it gave one, else the hull's (zeros without particulars)."""
        given = self.spec.mean_wind_load
        if given is not None:
            ratio = self.scale ** 2 if mean or self.spec.wind_speed == 0.0 else \
                (self.wind_speed() / self.spec.wind_speed) ** 2
            return np.array(given) * ratio
        if self.particulars is None:
            return np.zeros(3)
        relative = math.radians(self.wind_direction(mean)) - heading
        return wind_load(self.particulars, self.wind_speed(mean), relative)

    def wind_feedforward(self, heading: float) -> np.ndarray:
        """[X, Y, N] of the wind an anemometer measures now (speed with its gust, direction with
        its fluctuation) on the hull at the measured ``heading`` [rad], by the plant's own wind
        model: what a controller's wind feed-forward computes (it would filter it itself)."""
        return self.wind_load(heading)

    def drift_factor(self) -> float:
        """The slowly varying factor on the mean wave drift now (mean 1)."""
        if self.spec.wave_spectrum == "none":
            return max(0.0, 1.0 + self._drift.value)
        return self._series("drift")

    def drift_load(self, heading: float, mean: bool = False) -> np.ndarray:
        """[X, Y, N] of the wave drift at ``heading`` [rad] (``mean``: its mean), the caller's mean
        drift when it gave one, else the hull's (zeros without particulars); in a spread sea the
        hull's long-crested drift averaged over the directions weighted by the spreading
        (:func:`~.spreading.spread_mean`), the one drift coefficient of Newman's approximation."""
        spec = self.spec
        if spec.mean_drift_load is not None:
            load = np.array(spec.mean_drift_load) * self.scale ** 2
        elif self.particulars is None:
            return np.zeros(3)
        else:
            relative = math.radians(spec.wave_direction) - heading
            load = spread_mean(lambda theta: wave_drift_load(self.particulars, spec.wave_height * self.scale,
                                                             spec.wave_period, relative + theta),
                               spec.wave_spreading)
        return load if mean else load * self.drift_factor()

    def hull_load(self, heading: float, mean: bool = False) -> np.ndarray:
        """[X, Y, N] of wind and wave drift on the hull at ``heading`` [rad] (``mean``: without
        gusts and drift variation)."""
        return self.wind_load(heading, mean) + self.drift_load(heading, mean)

    def wave_motion(self) -> np.ndarray:
        """[north [m], east [m], yaw [rad]] of the first-order wave-frequency motion now, which the
        position measurement adds to the vessel's slow motion (zeros without a wave spectrum)."""
        if self.spec.wave_spectrum == "none":
            return np.zeros(3)
        row = self._row
        index = self.record.index
        return np.array([row[index["north"]], row[index["east"]], row[index["yaw"]]]) * self.scale
