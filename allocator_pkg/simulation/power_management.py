"""The simulated power management system (PMS) and its fast load reduction, after MarPowSim's
(NTNU-MCS/MarPowSim, ``Model/Files/PowerManagementSystem/src/``: ``PowerAvailable.cpp``,
``FastLoadReduction.cpp``, ``FaultDetector.cpp``; its parameters in
``Example/DrillingRigMSStoolbox/initDrillingRigMSStoolbox.m``, "Power Management System").

A fault is a generator set's breaker opening or a bus tie opening (MarPowSim's
``LossOfGeneratorsetDetector`` and ``CircuitBreakerOpeningDetector``); it concerns the buses
the breaker was on.

Power available (``PowerAvailable::calculatePowerAvailableBus``): per bus, the rated power of
its connected sets less its other consumers. After a fault the PMS reports what it reported
before for ``reaction_time`` (the time it takes to see the fault and compute again); from then
on it is held to at most the power its remaining sets were giving just before the fault (less the other
consumers) plus the bus's rated power times (t - t_fault - reaction_time) / ``ramp_time``; the
hold ends when it no longer binds. Per switchboard (the allocator's power source), the bus's
power in proportion to the rated power of the thrusters the switchboard feeds.

Load reduction, done here and in the thruster drives, not by the allocator: it must act within
a fifth of a second whatever the DP control system's sample does, and on a vessel it is the
PMS's blackout prevention (MarPowSim's ``FastLoadReduction`` sets each thruster's power limit).
Each thruster has a drive power limit [kW]:

- on a fault whose remaining sets gave less than the bus's load (``FaultDetector::
  powerAvailableAfterFaultThrusterFlr``), ``reaction_time`` after it, each thruster of the bus
  is limited to its power then times (what the remaining sets gave less the other consumers)
  over the bus's thruster power;
- while a bus's frequency is below ``frequency_start``, each of its thrusters is limited to
  its power when the frequency first fell below it, times (f - ``frequency_zero``) /
  (``frequency_start`` - ``frequency_zero``) (a frequency-based thrust limitation);
- a limit rises back toward the rated power at most at rated / ``restore_time`` per second.

The drive holds its thruster's power under its limit at once; the PMS reports a switchboard's
available power as the lower of its share above and the sum of its thrusters' limits, so the
allocator allocates within what the drives give."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PowerManagementSpec:
    """MarPowSim: ``reactionTimePowerAvaialble`` 1 s and ``rampTimePowerAvaialble`` 45 s."""

    reaction_time: float
    ramp_time: float


@dataclass(frozen=True)
class LoadReductionSpec:
    """MarPowSim: ``flrRestoreTime`` 0.2 s (its reaction) and ``flrRampTime`` 5 s."""

    enabled: bool
    reaction_time: float
    restore_time: float
    frequency_start: float
    frequency_zero: float


@dataclass
class Fault:
    """A fault at ``time`` on ``buses`` (switchboard tuples): the power the remaining sets of
    each gave just before [kW], less its other consumers, and each thruster's reduced limit."""

    time: float
    floor: dict[tuple[str, ...], float]
    reduced: dict[int, float]
    reported: dict[str, float]
    """[kW] what the PMS reported per switchboard of the buses just before the fault"""


class PowerAvailableReport:
    """What the PMS reports per bus after its faults (MarPowSim's ``PowerAvailable``)."""

    def __init__(self, spec: PowerManagementSpec) -> None:
        self.spec = spec
        self.faults: list[Fault] = []

    def bus(self, bus: tuple[str, ...], available: float, rated: float, time: float) -> float:
        """[kW] of ``bus``: ``available`` (rated power online less the other consumers), held
        after each of its faults to the floor plus the ramp."""
        s = self.spec
        for fault in self.faults:
            if bus in fault.floor and time >= fault.time + s.reaction_time:
                ramped = fault.floor[bus] + rated * (time - fault.time - s.reaction_time) / s.ramp_time
                available = min(available, ramped)
        return max(available, 0.0)


class LoadReduction:
    """Each thruster's drive power limit [kW] (inf: none) by the rules of the module."""

    def __init__(self, spec: LoadReductionSpec, rated: np.ndarray) -> None:
        self.spec = spec
        self.rated = np.asarray(rated, dtype=float)
        self.limit = np.full(len(self.rated), math.inf)
        self.onset: dict[tuple[str, ...], np.ndarray] = {}
        self.pending: list[Fault] = []

    def update(self, time: float, dt: float, power: np.ndarray, frequency: dict[tuple[str, ...], float],
               members: dict[tuple[str, ...], list[int]]) -> None:
        """One step of ``dt`` [s] ending at ``time``: the restore ramp, the faults whose reaction
        time is over, the frequency rule on each live bus (``frequency``: bus -> pu,
        ``members``: bus -> its thrusters' indices, ``power`` [kW] each thruster's now)."""
        s = self.spec
        if not s.enabled:
            return
        self.limit = np.minimum(self.limit + self.rated * dt / s.restore_time, math.inf)
        self.limit[self.limit >= self.rated] = math.inf
        due = [f for f in self.pending if time >= f.time + s.reaction_time - 1e-9]
        self.pending = [f for f in self.pending if f not in due]
        for fault in due:
            for index, value in fault.reduced.items():
                self.limit[index] = min(self.limit[index], value)
        for bus, f in frequency.items():
            indices = members.get(bus, [])
            if f >= s.frequency_start or f <= 0.0 or not indices:
                self.onset.pop(bus, None)
                continue
            onset = self.onset.setdefault(bus, np.asarray(power, dtype=float)[indices].copy())
            share = min(max((f - s.frequency_zero) / (s.frequency_start - s.frequency_zero), 0.0), 1.0)
            self.limit[indices] = np.minimum(self.limit[indices], onset * share)
