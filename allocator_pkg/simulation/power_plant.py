"""The simulated power plant of a vessel with power sources (docs/power.md): the power each
source can give [kW] at each step of a run. It starts at the vehicle's capacities; a scenario's
``power`` event sets one source's available power (a generator trips, or comes back), and a
``group_fault`` trips the group's sources (0 kW) until the faults are cleared, when they give
what they gave before. ``reported`` is what the plant's power management system reports on
``power_available``: the sources the ``power`` events have named, at their values (nothing
before the first such event, so that the allocator runs on its capacities)."""

from __future__ import annotations

import numpy as np

from ..vehicle.config import Vehicle


class PowerPlant:
    """The available power of ``vehicle``'s sources, in their configuration order."""

    def __init__(self, vehicle: Vehicle):
        self.sources = tuple(source.name for source in vehicle.power_sources)
        self._given = {source.name: float(source.capacity) for source in vehicle.power_sources}
        self._tripped: set[str] = set()
        self.reported: dict[str, float] = {}
        self.groups = {group.name: group for group in vehicle.redundancy_groups}

    def set_available(self, source: str, kilowatts: float) -> None:
        """A ``power`` event: the source gives ``kilowatts`` from now, reported from now."""
        self._given[source] = float(kilowatts)
        self.reported[source] = float(kilowatts)

    def trip_group(self, group: str) -> tuple[str, ...]:
        """A ``group_fault``: the group's sources give nothing until :meth:`restore`; the group's
        actuators, for the simulated thrusters to fail."""
        members = self.groups[group]
        self._tripped |= set(members.sources)
        return members.actuators

    def restore(self) -> None:
        """The faults cleared: every tripped source gives what it gave before."""
        self._tripped.clear()

    def available(self) -> np.ndarray:
        """[kW] of every source now."""
        return np.array([0.0 if name in self._tripped else self._given[name] for name in self.sources])
