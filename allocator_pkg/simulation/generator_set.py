"""A diesel generator set of the simulated power plant: its rating, inertia, governor and
frequency protection, after MarPowSim (NTNU-MCS/MarPowSim,
``Example/DrillingRigMSStoolbox/initDrillingRigMSStoolbox.m``, "Generator sets parameter" and
"Governor parameters").

Per unit on the set's rating S [kVA]; f the bus frequency [pu of nominal].

- Governor with droop R: the steady-state power set-point p_ref = (f_nl - f) / R, with the
  no-load frequency f_nl = 1 + R / 2 (nominal frequency at half load; MarPowSim's
  ``wNoLoad = 1 / (1 - droop * 0.5)`` to first order in R).
- Governor and engine as one first-order lag: T p_m' = p_ref - p_m, p_m in [0, p_max].
- Load acceptance of a turbocharged diesel (MarPowSim's ``deltaU`` and ``rampMax``): p_m may
  exceed a slow level s by at most ``step_allowance``; s follows p_m down at once and up at
  ``ramp_max`` [pu/s].
- Frequency protection: the set's breaker opens once f has stayed below ``under_frequency`` or
  above ``over_frequency`` for ``trip_delay`` seconds (MarPowSim's ``wMin``, ``wMax``,
  ``wBreakerTime``). A tripped set stays off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class GeneratorSetSpec:
    """One set as a scenario's ``power_plant.generator_sets`` item gives it."""

    name: str
    switchboard: str
    rating: float
    """S [kVA]"""
    power_factor: float
    """the active share of S the set is rated for: its rated power [kW] is S times this"""
    inertia: float
    """H [s]: stored kinetic energy at nominal speed over S"""
    droop: float
    """R [pu frequency per pu power]"""
    governor_time_constant: float
    """T [s]"""
    p_max: float
    """the engine's largest power [pu of S]"""
    step_allowance: float
    """[pu of S] the engine takes at once above its slow level"""
    ramp_max: float
    """[pu of S / s] the slow level's rise"""
    under_frequency: float
    over_frequency: float
    trip_delay: float
    """[s]"""
    connected: bool = True

    @property
    def rated_power(self) -> float:
        """[kW]"""
        return self.rating * self.power_factor

    @property
    def no_load_frequency(self) -> float:
        """f_nl [pu]: nominal frequency at half of S."""
        return 1.0 + 0.5 * self.droop


class GeneratorSet:
    """The state of one set: mechanical power p_m and slow level s [pu of S], connected,
    how long the frequency has been out of its band, and when it tripped."""

    def __init__(self, spec: GeneratorSetSpec, load: float = 0.5) -> None:
        self.spec = spec
        self.connected = spec.connected
        self.p_m = load if spec.connected else 0.0
        self.slow = self.p_m
        self.out_of_band = 0.0
        self.tripped_at = math.inf

    def reference(self, frequency: float) -> float:
        """p_ref [pu] at ``frequency`` [pu] by the droop, inside [0, p_max]."""
        s = self.spec
        return min(max((s.no_load_frequency - frequency) / s.droop, 0.0), s.p_max)

    def advance(self, frequency: float, dt: float) -> None:
        """``dt`` [s] of the governor at ``frequency``: the lag toward p_ref (exact for the
        step), then the load-acceptance ceiling and the engine's limits."""
        if not self.connected:
            return
        s = self.spec
        target = self.reference(frequency)
        self.p_m = target + (self.p_m - target) * math.exp(-dt / s.governor_time_constant)
        self.slow = min(self.p_m, self.slow + s.ramp_max * dt) if self.p_m > self.slow else self.p_m
        self.p_m = min(max(self.p_m, 0.0), self.slow + s.step_allowance, s.p_max)

    def protect(self, frequency: float, dt: float, time: float) -> bool:
        """The frequency relay over ``dt`` [s] ending at ``time`` [s]; True when it trips now."""
        if not self.connected:
            return False
        s = self.spec
        outside = frequency < s.under_frequency or frequency > s.over_frequency
        self.out_of_band = self.out_of_band + dt if outside else 0.0
        if self.out_of_band >= s.trip_delay - 1e-12:
            self.disconnect(time)
            return True
        return False

    def disconnect(self, time: float) -> None:
        """The set's breaker opens at ``time`` [s] (a trip, or the scenario's loss of the set)."""
        if self.connected:
            self.connected = False
            self.p_m = self.slow = 0.0
            self.tripped_at = time
