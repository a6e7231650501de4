"""Actuator faults, and the static force range of every actuator that faults and speed leave.

One home for both, used by the allocator every time a fault or the speed changes and by the
capability analysis for every case it draws:

- :class:`FaultSet` validates faults against a vehicle and holds them as the arrays a
  sample reads (efficiency, stuck angles, modes);
- :func:`static_ranges` gives each actuator's signed force range with those faults at a
  speed and supply voltage: thrust limits (following the voltage where a table has voltage
  rows) scaled by efficiency, a control surface's lift at full deflection
  (1.48), a stuck control surface pinned at its deflection.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from enum import IntEnum

import numpy as np

from ..vehicle.config import ActuatorConfig, Vehicle
from .actuators import command_map, lift_gain
from .sectors import in_feasible_sector


class FaultMode(IntEnum):
    """Numbered as the constants of allocator_msgs/ActuatorFault."""

    NOMINAL = 0
    DEGRADED = 1
    FAILED = 2
    STUCK = 3


@dataclass(frozen=True)
class Fault:
    """The fault state of one actuator.

    DEGRADED: the actuator still produces ``efficiency`` (0 < e <= 1) of its nominal force
    range, and its command is scaled so that it still produces the allocated force.
    FAILED: it produces nothing. STUCK: a rotatable thruster fixed at azimuth ``angle``
    [rad] (it still thrusts along it), or a control surface jammed at deflection ``angle``
    [rad].
    """

    mode: FaultMode = FaultMode.NOMINAL
    efficiency: float = 1.0
    angle: float = 0.0


class FaultSet:
    """Validated faults of one vehicle's actuators and their per-actuator arrays.

    Treated as immutable: :meth:`with_fault` and :meth:`cleared` return new sets.
    ``efficiency`` is 0 for FAILED and 1 for NOMINAL and STUCK; ``command_efficiency`` is
    what a command is divided by (1 where nothing is produced); ``stuck`` maps actuator index
    to its angle; ``modes`` holds every actuator's FaultMode.
    """

    def __init__(self, vehicle: Vehicle, faults: Mapping[str, Fault] | None = None):
        self.vehicle = vehicle
        self.faults: dict[str, Fault] = dict(faults or {})
        names = vehicle.names
        self.efficiency = np.ones(len(names))
        self.stuck: dict[int, float] = {}
        for i, name in enumerate(names):
            fault = self.faults.get(name)
            if fault is None:
                continue
            if fault.mode == FaultMode.STUCK:
                self.stuck[i] = fault.angle
            else:
                self.efficiency[i] = fault.efficiency
        self.command_efficiency = np.where(self.efficiency > 0.0, self.efficiency, 1.0)
        self.modes = np.array([self.faults[n].mode if n in self.faults else FaultMode.NOMINAL for n in names],
                              dtype=np.uint8)

    @classmethod
    def of(cls, vehicle: Vehicle, faults: Mapping[str, Fault | FaultMode] | None = None) -> FaultSet:
        """A set from faults or bare modes: a bare STUCK is stuck at angle 0; a bare DEGRADED
        lacks its efficiency and is refused."""
        result = cls(vehicle)
        for name, fault in (faults or {}).items():
            if isinstance(fault, Fault):
                result = result.with_fault(name, fault.mode, fault.efficiency, fault.angle)
            else:
                result = result.with_fault(name, fault, angle=0.0)
        return result

    def with_fault(self, name: str, mode: FaultMode | int, efficiency: float | None = None,
                   angle: float | None = None) -> FaultSet:
        """This set with one actuator's fault replaced. Raises ValueError (naming the valid
        choices) for an unknown actuator or mode, an efficiency outside (0, 1], or STUCK on
        an actuator that cannot be stuck or at an angle it cannot take."""
        if name not in self.vehicle.names:
            raise ValueError(f"unknown actuator '{name}'; actuators: {', '.join(self.vehicle.names)}")
        try:
            mode = FaultMode(mode)
        except ValueError:
            raise ValueError(f"unknown fault mode {mode!r}; modes: "
                             + ", ".join(f"{m.name}={m.value}" for m in FaultMode)) from None
        faults = dict(self.faults)
        if mode == FaultMode.NOMINAL:
            faults.pop(name, None)
        elif mode == FaultMode.DEGRADED:
            if efficiency is None or not (math.isfinite(efficiency) and 0.0 < efficiency <= 1.0):
                raise ValueError(f"DEGRADED needs an efficiency in (0, 1], got {efficiency}")
            faults[name] = Fault(mode, efficiency=float(efficiency))
        elif mode == FaultMode.STUCK:
            faults[name] = Fault(mode, angle=self._stuck_angle(self.vehicle.actuator(name), angle))
        else:
            faults[name] = Fault(mode, efficiency=0.0)
        return FaultSet(self.vehicle, faults)

    def cleared(self) -> FaultSet:
        """Every actuator back to NOMINAL."""
        return FaultSet(self.vehicle)

    def rebound(self, vehicle: Vehicle) -> FaultSet:
        """The same faults on a new configuration of the same actuators."""
        return FaultSet(vehicle, self.faults)

    def _stuck_angle(self, actuator: ActuatorConfig, angle: float | None) -> float:
        stuckable = [a.name for a in self.vehicle.actuators if a.rotatable or a.is_surface]
        if not (actuator.rotatable or actuator.is_surface):
            raise ValueError(f"STUCK applies to rotatable thrusters and control surfaces, not the {actuator.type} "
                             f"actuator '{actuator.name}'; these can be stuck: {', '.join(stuckable) or 'none'}")
        if angle is None or not math.isfinite(angle):
            raise ValueError(f"STUCK needs a finite angle, got {angle}")
        if actuator.rotatable:
            rotation = actuator.rotation
            if not in_feasible_sector(rotation, angle):
                raise ValueError(f"angle {angle:g} rad is outside the feasible sector "
                                 f"[{rotation.azimuth_min:g}, {rotation.azimuth_max:g}] of '{actuator.name}'")
        elif abs(angle) > actuator.surface.deflection_max:
            raise ValueError(f"deflection {angle:g} rad is beyond deflection_max "
                             f"{actuator.surface.deflection_max:g} of '{actuator.name}'")
        return float(angle)


def lift_gains(vehicle: Vehicle, speed: float) -> np.ndarray:
    """k_L of every actuator at a surge speed (1.48): 0 for thrusters and stalled surfaces."""
    return np.array([lift_gain(a.surface, vehicle.water_density, speed) if a.is_surface else 0.0
                     for a in vehicle.actuators])


def thrust_limits(vehicle: Vehicle, voltage: float | None) -> tuple[np.ndarray, np.ndarray]:
    """Every thruster's thrust range at a supply voltage (0 for control surfaces): thrust_min
    and thrust_max, narrowed for a table measured at several voltages to what its curve at
    ``voltage`` gives between command_min and command_max (None: the nominal voltage)."""
    if voltage is None:
        voltage = vehicle.nominal_voltage
    low = np.array([0.0 if a.is_surface else a.thrust_min for a in vehicle.actuators])
    high = np.array([0.0 if a.is_surface else a.thrust_max for a in vehicle.actuators])
    for i, actuator in enumerate(vehicle.actuators):
        if actuator.command is not None and actuator.command.table_voltage:
            curve_low, curve_high = command_map(actuator.command, voltage).force_range()
            low[i], high[i] = max(low[i], curve_low), min(high[i], curve_high)
    return low, high


def static_ranges(vehicle: Vehicle, faults: FaultSet, speed: float,
                  voltage: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Signed force range [low, high] of every actuator with its fault at a surge speed and
    supply voltage, before any rate limit: thrust limits (:func:`thrust_limits`) times
    efficiency; a control surface's lift at full deflection either way times efficiency, or
    pinned at a stuck deflection's lift."""
    low, high = thrust_limits(vehicle, voltage)
    low *= faults.efficiency
    high *= faults.efficiency
    lift = lift_gains(vehicle, speed)
    for i, actuator in enumerate(vehicle.actuators):
        if not actuator.is_surface:
            continue
        if i in faults.stuck:
            low[i] = high[i] = lift[i] * faults.stuck[i]
        else:
            high[i] = lift[i] * actuator.surface.deflection_max * faults.efficiency[i]
            low[i] = -high[i]
    return low, high
