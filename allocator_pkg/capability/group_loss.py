"""What a redundancy group's loss leaves the allocator, by the allocator's own rules: what
:meth:`~allocator_pkg.allocation.allocator.Allocator.set_group_fault` would put in force on top
of what is in force now.

- the group's actuators FAILED, on top of the faults in force, at the surge speed and supply
  voltage in force (:class:`~allocator_pkg.allocation.conditions.Conditions`): the static force
  ranges (:func:`~allocator_pkg.effectiveness.faults.static_ranges`) and the flushing zones that
  follow the working thrusters (:func:`~allocator_pkg.effectiveness.zones.zones_in_force`): the
  zones protecting the group's thrusters lift, the sides of fixed thrusters a zone closes stay
  closed, and the DNV-ST-0111 [3.11.4] losses of the thrusters pushing onto the dead ones apply;
  every range inside its drive limit (:mod:`~allocator_pkg.allocation.drive_power`);
- the bus ties in the state in force (:mod:`~allocator_pkg.allocation.bus_ties`), the group's
  sources at 0 kW and every other source at its available power in force (0 for a source
  already lost: a failed group's, or one reported at 0 kW), and the power rule of
  :meth:`~allocator_pkg.allocation.power_budget.PowerBudget.limit` as the allocator's method has
  it: for a method with power rows, the rows after the loss (the same pooled weights, available
  power, coefficients and chords the allocator would solve with) and the derating of a
  split-fed thruster's lost feed in the ranges; for one without, the proportional bounds in
  the ranges.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..allocation.allocator import Allocator
from ..allocation.conditions import Conditions
from ..allocation.drive_power import within_drive_limits
from ..allocation.power_budget import PowerBudget, narrowed
from ..effectiveness.faults import FaultMode, FaultSet
from ..effectiveness.flushing import DeadFlushing
from ..effectiveness.power_rows import PowerRows
from ..vehicle.config import RedundancyGroup, RotationConfig, Vehicle


@dataclass(frozen=True)
class InForce:
    """What the allocator has in force, that a group's loss comes on top of: the ``faults``, the
    surge ``speed`` [m/s], the supply ``voltage`` [V] (None: the configuration has no
    nominal_voltage), the ``available`` power [kW] of every source, ``power.sources`` order
    (0 for a lost one), and the state of every bus tie by name (``ties``: True closed; a tie not
    named keeps the configured state)."""

    faults: FaultSet
    speed: float
    voltage: float | None
    available: np.ndarray
    ties: Mapping[str, bool] = field(default_factory=dict)

    @classmethod
    def of(cls, allocator: Allocator) -> InForce:
        """A copy of what ``allocator`` has in force (its faults are never changed in place)."""
        return cls(allocator.fault_set, allocator.speed, allocator.voltage, allocator.power.available.copy(),
                   dict(allocator.power.ties.closed))

    @classmethod
    def intact(cls, vehicle: Vehicle) -> InForce:
        """A new allocator's: no faults, at rest, the nominal voltage, every source at its capacity."""
        return cls(FaultSet(vehicle), 0.0, vehicle.nominal_voltage,
                   np.array([source.capacity for source in vehicle.power_sources], dtype=float))

    def lost_sources(self, vehicle: Vehicle) -> tuple[str, ...]:
        """The sources already lost: at 0 kW (a failed group's, or reported so)."""
        return tuple(source.name for source, kilowatts in zip(vehicle.power_sources, self.available)
                     if kilowatts <= 0.0)


@dataclass(frozen=True)
class Remaining:
    """What the allocator would have after a group's loss, per actuator (configuration order):
    the signed force ranges ``low``/``high`` [N], each rotatable thruster's ``rotations`` with the
    zones in force (None for other actuators), the [3.11.4] ``losses`` by actuator index, and the
    ``stuck`` angles by actuator index; the ``power`` rows after the loss (None: no sources, or
    a method without rows)."""

    low: np.ndarray
    high: np.ndarray
    rotations: tuple[RotationConfig | None, ...]
    losses: Mapping[int, tuple[DeadFlushing, ...]]
    stuck: Mapping[int, float]
    power: PowerRows | None = None


def remaining(vehicle: Vehicle, in_force: InForce, group: RedundancyGroup, rows: bool = False) -> Remaining:
    """What ``group``'s loss leaves on top of ``in_force`` (module docstring); ``rows``: the
    allocator's method solves with the power rows."""
    faults = in_force.faults
    for name in group.actuators:
        faults = faults.with_fault(name, FaultMode.FAILED)
    budget = PowerBudget(vehicle)
    budget.ties.closed.update({name: closed for name, closed in in_force.ties.items() if name in budget.ties.closed})
    budget.efficiency = faults.command_efficiency
    conditions = within_drive_limits(Conditions.of(vehicle, faults, in_force.speed, in_force.voltage), budget.in_force)
    low, high = conditions.low, conditions.high
    power = None
    if budget.active:
        budget.reported = np.asarray(in_force.available, dtype=float).copy()
        budget.lost = frozenset(group.sources)
        limit = budget.limit(low, high, rows)
        power = limit.rows
        if limit.limited.any():
            low, high = narrowed(low, high, limit)
    return Remaining(low, high, conditions.rotations, conditions.losses, faults.stuck, power)
