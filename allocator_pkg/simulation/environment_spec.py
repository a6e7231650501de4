"""What a scenario says of its environment: means, slow variations (:class:`SlowVariation`) and
the spectra it asks for (:class:`EnvironmentSpec`), each checked on construction."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .scenario_keys import scenario_default
from .spectra import WAVE_SPECTRA, WIND_SPECTRA
from .spreading import check_exponent


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
    wind_spectrum: str = scenario_default("environment.wind.spectrum")
    """``first_order`` (the Gauss-Markov ``gusts``), ``npd``, ``api`` or ``harris``."""
    wind_direction_variation: SlowVariation = SlowVariation(0.0)
    """The wind direction's fluctuation [deg] with a gust spectrum."""
    wave_spectrum: str = scenario_default("environment.waves.spectrum")
    """``none`` (the drift times 1 + ``drift_variation``) or ``jonswap``."""
    peak_factor: float = scenario_default("environment.waves.peak_factor")
    """JONSWAP's gamma; 0: DNV-RP-C205's from Hs and Tp."""
    wave_spreading: float = scenario_default("environment.waves.spreading")
    """n of the cos^n spreading about ``wave_direction`` (:mod:`.spreading`); 0: long-crested."""
    mean_wind_load: tuple[float, float, float] | None = None
    """[X, Y, N] of the mean wind at the set-point heading in place of the hull's model."""
    mean_drift_load: tuple[float, float, float] | None = None
    """[X, Y, N] of the mean wave drift at the set-point heading in place of the hull's model."""

    def __post_init__(self) -> None:
        if self.wind_spectrum not in WIND_SPECTRA:
            raise ValueError(f"environment.wind.spectrum: one of {', '.join(WIND_SPECTRA)}, not {self.wind_spectrum!r}")
        if self.wave_spectrum not in WAVE_SPECTRA:
            raise ValueError(f"environment.waves.spectrum: one of {', '.join(WAVE_SPECTRA)}, "
                             f"not {self.wave_spectrum!r}")
        if not (math.isfinite(self.peak_factor) and (self.peak_factor == 0.0 or self.peak_factor >= 1.0)):
            raise ValueError(f"environment.waves.peak_factor: 0 (DNV-RP-C205's) or a number >= 1, "
                             f"not {self.peak_factor!r}")
        check_exponent(self.wave_spreading, "environment.waves.spreading")
