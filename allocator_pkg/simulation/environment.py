"""A seeded environment: a current with a slowly varying speed and direction, wind with gusts
and slowly varying wave drift for the vessel; a current for the ROV.

Every slow variation is a first-order Gauss-Markov process x' = -x / T + w (the form Fossen
2021 gives the slowly varying current speed), discretised exactly: x_k+1 = a x_k + sqrt(1 - a^2) sigma e_k,
a = exp(-dt / T), e_k standard normal from one ``numpy`` generator seeded by the scenario, so
its stationary standard deviation is sigma and its correlation time T. The gusts are such a
process for the wind speed (turbulence intensity sigma / mean), not a Harris or NORSOK
spectrum; the slowly varying wave drift is the mean drift of
``analysis.environment_loads.wave_drift_load`` times (1 + such a process), not a Newman
approximation from a wave spectrum. Directions are where the environment comes from, in
degrees clockwise from north. ``scale`` (1 unless a scenario's weather ramp changes it) multiplies
the current's speed, the wind's speed and the significant wave height, variations included.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..hull.environment_loads import VesselParticulars, wave_drift_load, wind_load
from .scenario_keys import scenario_default


@dataclass(frozen=True)
class SlowVariation:
    """sigma (stationary standard deviation) and T [s] (correlation time) of a Gauss-Markov process."""

    sigma: float = scenario_default("environment.current.speed_sigma")
    time_constant: float = scenario_default("environment.current.time_constant")

    def __post_init__(self) -> None:
        if not (math.isfinite(self.sigma) and self.sigma >= 0.0):
            raise ValueError(f"variation sigma: a finite number >= 0, not {self.sigma!r}")
        if not (math.isfinite(self.time_constant) and self.time_constant > 0.0):
            raise ValueError(f"variation time_constant: a finite number > 0, not {self.time_constant!r}")


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


@dataclass(frozen=True)
class EnvironmentSpec:
    """Mean values and variations of a scenario's environment (speeds [m/s], directions [deg]);
    the defaults of a scenario file's ``environment`` keys."""

    current_speed: float = scenario_default("environment.current.speed")
    current_direction: float = scenario_default("environment.current.direction")
    current_speed_variation: SlowVariation = SlowVariation()
    current_direction_variation: SlowVariation = SlowVariation()
    current_down: float = scenario_default("environment.current.down")
    """Vertical current [m/s] (ROV)."""
    wind_speed: float = scenario_default("environment.wind.speed")
    wind_direction: float = scenario_default("environment.wind.direction")
    gusts: SlowVariation = SlowVariation()
    wave_height: float = scenario_default("environment.waves.hs")
    wave_period: float = scenario_default("environment.waves.peak_period")
    wave_direction: float = scenario_default("environment.waves.direction")
    drift_variation: SlowVariation = SlowVariation()


class Environment:
    """Current [north, east, down] and, for a hull with particulars, the wind and wave-drift
    load [X, Y, N] in the body frame; one :meth:`step` per simulation step."""

    def __init__(self, spec: EnvironmentSpec, seed: int, particulars: VesselParticulars | None = None):
        self.spec = spec
        self.particulars = particulars
        generator = np.random.default_rng(seed)
        self._speed = GaussMarkov(spec.current_speed_variation, generator)
        self._direction = GaussMarkov(spec.current_direction_variation, generator)
        self._gust = GaussMarkov(spec.gusts, generator)
        self._drift = GaussMarkov(spec.drift_variation, generator)
        self.scale = 1.0

    def step(self, dt: float) -> None:
        for process in (self._speed, self._direction, self._gust, self._drift):
            process.step(dt)

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
        return max(0.0, self.spec.wind_speed + (0.0 if mean else self._gust.value)) * self.scale

    def hull_load(self, heading: float, mean: bool = False) -> np.ndarray:
        """[X, Y, N] of wind and wave drift on the hull at ``heading`` [rad] (``mean``: without
        gusts and drift variation; none without particulars)."""
        if self.particulars is None:
            return np.zeros(3)
        spec = self.spec
        wind = wind_load(self.particulars, self.wind_speed(mean), math.radians(spec.wind_direction) - heading)
        drift = wave_drift_load(self.particulars, spec.wave_height * self.scale, spec.wave_period,
                                math.radians(spec.wave_direction) - heading)
        return wind + drift * (1.0 if mean else max(0.0, 1.0 + self._drift.value))
