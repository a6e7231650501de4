"""The simulated electric power plant of a scenario with ``power_plant`` (docs/power.md, "The
drilling-rig benchmark"): generator sets on the vehicle's switchboards (its power sources),
bus ties, the other consumers (a base load and pulsing loads such as a drawworks), the
thrusters' power from the simulated thrusters' thrust by the allocator's drive model
(:mod:`~allocator_pkg.allocation.drive_power`: survey (1.44), P_i |f_i|^(3/2) with the forward or
reverse coefficient, a DEGRADED thruster's at its set-point), split over its live feeds as the
allocator splits it (a dead switchboard's share on the live feeds), the buses' frequency
(:mod:`.bus_frequency`), the power management system and the fast load reduction
(:mod:`.power_management`). It answers the closed loop as :class:`~.power_plant.PowerPlant`
does (``sources``, ``reported``, ``available``) and records each step for the metrics and
figures."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..allocation.drive_power import KW, DrivePower
from ..effectiveness.power_rows import feed_shares
from ..vehicle.config import Vehicle
from .bus_frequency import Bus, BusTieSpec, buses
from .generator_set import GeneratorSet, GeneratorSetSpec
from .power_management import Fault, LoadReduction, LoadReductionSpec, PowerAvailableReport, PowerManagementSpec

RELAY = "frequency relay"
"""Why a set went off when its frequency relay tripped it."""
SUBSTEP = 0.005
"""[s] the swing equation's integration step (about a fiftieth of the fastest governor period)."""


@dataclass(frozen=True)
class Consumer:
    """A consumer of ``power`` [kW] on ``switchboard``: always on when ``on`` is 0, else on for
    ``on`` seconds every ``on`` + ``off`` seconds from ``start`` (MarPowSim's ``makePulseTrain``)."""

    switchboard: str
    power: float
    start: float
    on: float
    off: float

    def at(self, time: float) -> float:
        if self.on == 0.0:
            return self.power
        if time < self.start:
            return 0.0
        return self.power if (time - self.start) % (self.on + self.off) < self.on else 0.0


@dataclass(frozen=True)
class PlantSpec:
    """A scenario's ``power_plant`` section."""

    generator_sets: tuple[GeneratorSetSpec, ...]
    bus_ties: tuple[BusTieSpec, ...]
    consumers: tuple[Consumer, ...]
    management: PowerManagementSpec
    load_reduction: LoadReductionSpec


@dataclass
class PlantRecord:
    """Per step of the closed loop: time [s], and per switchboard its bus's frequency [pu], its
    load [kW] (0 once dead) and what its sets generate [kW]."""

    time: list[float] = field(default_factory=list)
    frequency: list[list[float]] = field(default_factory=list)
    load: list[list[float]] = field(default_factory=list)
    generation: list[list[float]] = field(default_factory=list)
    trips: list[tuple[float, str, str]] = field(default_factory=list)
    """(time, generator set, why): the sets that went off in the run."""


class ElectricPlant:
    """The plant of ``spec`` feeding ``vehicle``'s thrusters."""

    def __init__(self, spec: PlantSpec, vehicle: Vehicle) -> None:
        self.spec = spec
        self.sources = tuple(source.name for source in vehicle.power_sources)
        self.vehicle = vehicle
        self.sets = [GeneratorSet(s) for s in spec.generator_sets]
        self.ties = {tie.name: tie for tie in spec.bus_ties}
        self.closed = {tie.name: tie.closed for tie in spec.bus_ties}
        self.drive = DrivePower.of(vehicle)
        self.efficiency = np.ones(len(vehicle.actuators))
        largest = np.array([max(abs(a.thrust_min), abs(a.thrust_max)) for a in vehicle.actuators], dtype=float)
        self.rated = np.maximum(self.drive.forward, self.drive.reverse) * largest ** 1.5 / KW
        self.shares = feed_shares(vehicle)
        self.report = PowerAvailableReport(spec.management)
        self.reduction = LoadReduction(spec.load_reduction, self.rated)
        self.buses = self._buses({}, 1.0)
        self.thruster_power = np.zeros(len(vehicle.actuators))
        self.record = PlantRecord()
        self.reported: dict[str, float] = {}
        self.dead: set[str] = set()
        self.time = 0.0
        self.start(np.zeros(len(vehicle.actuators)))

    # -- topology -------------------------------------------------------------------------

    def _buses(self, old: dict[str, float], default: float) -> list[Bus]:
        """The buses of the ties in force; a bus's frequency the highest of its switchboards' before."""
        found = []
        for group in buses(self.sources, self.ties, self.closed):
            sets = [g for g in self.sets if g.spec.switchboard in group]
            found.append(Bus(group, sets, max(old.get(name, default) for name in group)))
        return found

    def _frequencies(self) -> dict[str, float]:
        """[pu] per switchboard: the frequency of the bus it is on."""
        return {name: bus.frequency for bus in self.buses for name in bus.switchboards}

    def _members(self, bus: Bus) -> list[int]:
        """The indices of the thrusters ``bus`` feeds (any share of their power from its switchboards)."""
        columns = [self.sources.index(name) for name in bus.switchboards]
        return [i for i in range(len(self.rated)) if self.shares[i, columns].sum() > 0.0]

    def _other_load(self, switchboard: str, time: float) -> float:
        """[kW] at ``time`` [s] of the consumers on ``switchboard`` other than the thrusters."""
        return sum(c.at(time) for c in self.spec.consumers if c.switchboard == switchboard)

    def _live_shares(self) -> np.ndarray:
        """(thrusters x switchboards) the share of each thruster's power on each switchboard:
        the configured shares over its live feeds (a dead one's share on the others; the
        configured shares when every feed is dead)."""
        live = self.shares * np.array([name not in self.dead for name in self.sources])
        total = live.sum(axis=1, keepdims=True)
        return np.where(total > 0.0, live / np.where(total > 0.0, total, 1.0), self.shares)

    def _drawn(self, thrust: np.ndarray, efficiency: np.ndarray) -> None:
        """The thrusters' power [kW] at the delivered ``thrust`` [N] and the faults' ``efficiency``
        (the share of force a DEGRADED one delivers; a failed one's 0 counts as 1, its thrust 0)."""
        self.efficiency = np.where(np.asarray(efficiency, dtype=float) > 0.0, efficiency, 1.0)
        self.thruster_power = self.drive.degraded(self.efficiency).power(thrust) / KW

    def _loads(self, time: float) -> dict[str, float]:
        """[kW] per switchboard: its other consumers and its share of its thrusters' power."""
        thrusters = self.thruster_power @ self._live_shares()
        return {name: self._other_load(name, time) + float(thrusters[j]) for j, name in enumerate(self.sources)}

    # -- events ---------------------------------------------------------------------------

    def set_bus_tie(self, name: str, closed: bool) -> str:
        """The tie ``name`` opens or closes now; opening is a fault of the buses it splits."""
        if self.closed[name] == closed:
            return f"power plant: bus tie {name} already {'closed' if closed else 'open'}"
        before = [b for b in self.buses if set(self.ties[name].between) <= set(b.switchboards)]
        self.closed[name] = closed
        self.buses = self._buses(self._frequencies(), 1.0)
        if not closed and before:
            after = [b for b in self.buses if set(b.switchboards) <= set(before[0].switchboards)]
            self._fault(after, lost=())
        return f"power plant: bus tie {name} {'closed' if closed else 'open'}"

    def lose_set(self, name: str) -> str:
        """The generator set ``name`` is lost now (its breaker opens): a fault of its bus."""
        found = next(g for g in self.sets if g.spec.name == name)
        if not found.connected:
            return f"power plant: generator set {name} was already off"
        bus = next(b for b in self.buses if found in b.sets)
        before = self._before(bus)
        found.disconnect(self.time)
        self.record.trips.append((self.time, name, "lost (scenario event)"))
        self._fault([bus], lost=(name,), before=before)
        return f"power plant: generator set {name} lost"

    def _before(self, bus: Bus) -> dict[str, float]:
        return bus.electrical(sum(self._loads(self.time)[name] for name in bus.switchboards))

    def _fault(self, affected: list[Bus], lost: tuple[str, ...], before: dict[str, float] | None = None) -> None:
        """A fault on ``affected``: what its remaining sets gave before, for the PMS's hold and
        the load reduction's limits (MarPowSim's ``FaultDetector``)."""
        loads = self._loads(self.time)
        floor, reduced = {}, {}
        for bus in affected:
            given = before if before is not None else self._before(bus)
            remaining = sum(p for name, p in given.items() if name not in lost)
            other = sum(self._other_load(name, self.time) for name in bus.switchboards)
            floor[bus.switchboards] = remaining - other
            demand = sum(loads[name] for name in bus.switchboards)
            members = self._members(bus)
            thrusters = float(self.thruster_power[members].sum())
            if remaining < demand and thrusters > 0.0:
                ratio = max(remaining - other, 0.0) / thrusters
                reduced |= {i: float(self.thruster_power[i]) * ratio for i in members}
        before = {name: self.reported[name] for bus in affected for name in bus.switchboards}
        fault = Fault(self.time, floor, reduced, before)
        self.report.faults.append(fault)
        self.reduction.pending.append(fault)

    # -- stepping -------------------------------------------------------------------------

    def start(self, thrust: np.ndarray, efficiency: np.ndarray | None = None) -> None:
        """Every set's power at the droop share of the load of its bus at ``thrust`` [N] (the
        faults' ``efficiency``: :meth:`_drawn`; None: none)."""
        self._drawn(thrust, np.ones(len(self.rated)) if efficiency is None else efficiency)
        loads = self._loads(self.time)
        for bus in self.buses:
            live = [g for g in bus.sets if g.connected]
            weights = [g.spec.rating / g.spec.droop for g in live]
            load = sum(loads[name] for name in bus.switchboards)
            bus.frequency = (sum(w * g.spec.no_load_frequency for w, g in zip(weights, live)) - load) / sum(weights)
            for g in live:
                g.p_m = g.slow = g.reference(bus.frequency)
        self.reported = self._reported(self.time)

    def drive_limits(self) -> np.ndarray:
        """[kW] per thruster: the drive's power limit (inf: none; 0 on a dead bus)."""
        limits = self.reduction.limit.copy()
        for i in range(len(limits)):
            live = [self.sources[j] for j in np.flatnonzero(self.shares[i]) if self.sources[j] not in self.dead]
            if not live and self.shares[i].any():
                limits[i] = 0.0
        return limits

    def advance(self, thrust: np.ndarray, dt: float, efficiency: np.ndarray | None = None) -> list[str]:
        """``dt`` [s] with the thrusters at ``thrust`` [N] (the faults' ``efficiency``:
        :meth:`_drawn`; None: none): the buses, relays, PMS and load reduction; the switchboards
        that went dead in it."""
        self._drawn(thrust, np.ones(len(self.rated)) if efficiency is None else efficiency)
        steps = max(1, math.ceil(dt / SUBSTEP - 1e-9))
        h = dt / steps
        for _ in range(steps):
            self.time += h
            loads = self._loads(self.time)
            for bus in self.buses:
                load = sum(loads[name] for name in bus.switchboards)
                before = bus.electrical(load)
                for g in bus.advance(load, h, self.time):
                    self.record.trips.append((self.time, g.spec.name, RELAY))
                    self._fault([bus], lost=(g.spec.name,), before=before)
        newly = [name for bus in self.buses if not bus.live for name in bus.switchboards if name not in self.dead]
        self.dead |= set(newly)
        frequency = {bus.switchboards: bus.frequency for bus in self.buses}
        members = {bus.switchboards: self._members(bus) for bus in self.buses}
        self.reduction.update(self.time, dt, self.thruster_power, frequency, members)
        self.reported = self._reported(self.time)
        self._keep()
        return newly

    def _reported(self, time: float) -> dict[str, float]:
        """[kW] the PMS reports per switchboard (see :mod:`.power_management`): its share of its
        bus's power available, what it reported before a fault for the reaction time after it
        (a dead switchboard at once 0), never more than its thrusters' drive limits."""
        shares = {}
        for bus in self.buses:
            rated = sum(g.spec.rated_power for g in bus.sets if g.connected)
            other = sum(self._other_load(name, time) for name in bus.switchboards)
            available = self.report.bus(bus.switchboards, rated - other, rated, time) if bus.live else 0.0
            weight = self.rated @ self.shares[:, [self.sources.index(name) for name in bus.switchboards]]
            total = float(weight.sum())
            shares |= {name: available * w / total if total > 0.0 else 0.0 for name, w in zip(bus.switchboards, weight)}
        for fault in self.report.faults:
            if time < fault.time + self.spec.management.reaction_time:
                shares |= {name: value for name, value in fault.reported.items() if name not in self.dead}
        limits = self.drive_limits()
        found = {}
        for j, name in enumerate(self.sources):
            fed = self.shares[:, j] > 0.0
            found[name] = min(shares[name], float(limits[fed] @ self.shares[fed, j]))
        return found

    def _keep(self) -> None:
        loads = self._loads(self.time)
        frequency = self._frequencies()
        generation = dict.fromkeys(self.sources, 0.0)
        for bus in self.buses:
            given = bus.electrical(sum(loads[name] for name in bus.switchboards))
            for g in bus.sets:
                generation[g.spec.switchboard] += given.get(g.spec.name, 0.0)
        r = self.record
        r.time.append(self.time)
        r.frequency.append([frequency[name] for name in self.sources])
        r.load.append([0.0 if name in self.dead else loads[name] for name in self.sources])
        r.generation.append([generation[name] for name in self.sources])

    # -- what the closed loop asks of a power plant -----------------------------------------

    def available(self) -> np.ndarray:
        """[kW] per source: what the PMS reports."""
        return np.array([self.reported[name] for name in self.sources])

    def thrust_caps(self) -> tuple[np.ndarray, np.ndarray]:
        """([N] astern, [N] ahead) per thruster: the delivered thrust range its drive's power limit
        leaves at the faults in force (:meth:`DrivePower.ranges`; -inf, inf: none)."""
        drive = replace(self.drive.degraded(self.efficiency), limit=self.drive_limits())
        count = len(self.rated)
        with np.errstate(invalid="ignore"):
            return drive.ranges(np.full(count, -np.inf), np.full(count, np.inf))
