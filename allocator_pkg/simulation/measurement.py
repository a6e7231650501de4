"""What the DP vessel's position reference and gyro compass give the control system each step:
the vessel's position and heading plus the first-order wave-frequency motion the environment
adds (:meth:`~.environment.Environment.wave_motion`) plus white noise, Gaussian with the
configured standard deviations, from a generator of its own (seeded by the scenario, so that
the environment's random numbers do not change with it)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .scenario_keys import scenario_default

NOISE_SEED_OFFSET = 7919
"""Added to the scenario's seed for the measurement's generator."""


@dataclass(frozen=True)
class MeasurementNoise:
    """Standard deviations of the white measurement noise: position [m] (north and east each),
    heading [rad]."""

    position_sigma: float = scenario_default("measurement.position_sigma")
    heading_sigma: float = math.radians(scenario_default("measurement.heading_sigma"))

    def __post_init__(self) -> None:
        for name in ("position_sigma", "heading_sigma"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"measurement.{name}: a finite number >= 0, not {value!r}")


class Measurement:
    """[north, east, heading] as measured, one sample per step."""

    def __init__(self, noise: MeasurementNoise, seed: int):
        self.sigma = np.array([noise.position_sigma, noise.position_sigma, noise.heading_sigma])
        self.generator = np.random.default_rng(seed + NOISE_SEED_OFFSET)
        self.noisy = bool(np.any(self.sigma > 0.0))

    def sample(self, eta: np.ndarray, wave: np.ndarray) -> np.ndarray:
        """The measurement of the low-frequency pose ``eta`` [north, east, heading] with the wave
        motion ``wave`` (same units) on it; the heading wrapped to (-pi, pi]."""
        measured = np.asarray(eta, dtype=float) + wave
        if self.noisy:
            measured = measured + self.sigma * self.generator.standard_normal(3)
        measured[2] = math.remainder(measured[2], 2.0 * math.pi)
        return measured
