"""Power per source in the allocation (docs/power.md): the thrust each actuator may have so
that no power source is asked for more than it has.

Actuator i draws p_i = P_i |f_i|^(3/2) (1.44); its rated power is R_i = P_i F_i^(3/2), F_i the
largest magnitude of its configured thrust range. A feed is live while its source has power
(available > 0); S_i is the sum of the shares of actuator i's live feeds. The actuator's power
comes from its live feeds in proportion to their shares (feed j gives p_i s_ij / S_i), and no
feed gives more than s_ij R_i, so p_i <= S_i R_i: with every feed live the power splits by
the shares and the limit is the rated power; a split-fed actuator that loses a feed runs on the
rest, derated.

A source j whose consumers could together draw more than it has (D_j > A_j, each consumer at
the largest thrust faults, voltage and the derating leave it, m_i) is shared in proportion to
those largest draws: each consumer's power is scaled by rho_j = A_j / D_j, an actuator by the
smallest rho of its live feeds. That bounds |f_i| <= m_i rho^(2/3), a thrust range for every
stage of the sample (the optimiser moves the rest to other sources' actuators), and the draw
on source j is at most rho_j D_j = A_j by construction.

A sample that leaves a short source's power unused while some of its consumers sit at their
bound shares it again (:meth:`PowerBudget.shared`): every consumer of the source may grow by
the factor that scales the sample's own draw on it up to A_j, and the sample is solved again
inside those bounds; the draw on the source is again at most A_j.

The sources are taken by row: a closed bus tie pools the sources of a bus into its first
source's row (:mod:`.bus_ties`), and each drive's power has its forward and reverse
coefficients, a DEGRADED thruster's counted on its set-point (:mod:`.drive_power`); the bound's
coefficient is the larger of the two its range allows. The available power in use follows the
restore ramp (:mod:`.restore_ramp`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..effectiveness.model import AT_LIMIT
from ..vehicle.config import RedundancyGroup, Vehicle
from .bus_ties import BusTies
from .drive_power import DrivePower
from .restore_ramp import RestoreRamp

KW = 1000.0
"""Watts in a kilowatt: the configuration and the topic speak kW, the model W (1.44)."""

SPARE = 1e-3
"""A short source whose draw falls below its available power by more than this share has power
to share again."""

PATTERN = 1e-9
"""A short source drawn below this share of its available power has no thrust pattern to scale
up: its consumers keep their bounds."""


@dataclass(frozen=True)
class PowerLimit:
    """The power rule at one set of available powers: ``bound`` [N], the largest thrust
    magnitude of every actuator (inf: the power sets none); ``weights`` (r x m), the share of
    actuator i's power drawn from row j (0 from a lost feed); ``limited``, the actuators
    whose range the bound narrows; ``available``, the available power [kW] of every source
    the rule took; ``largest`` [N], the largest thrust magnitude faults, speed, voltage and the
    feed limit leave every actuator (m_i; inf for one without feeds); ``rho``, every row's
    share of its consumers' largest draws (1: it limits nothing); ``rows``, every row's
    available power [kW] (a bus's sum on its first source, inf on its others)."""

    bound: np.ndarray
    weights: np.ndarray
    limited: np.ndarray
    available: np.ndarray
    largest: np.ndarray
    rho: np.ndarray
    rows: np.ndarray

    def holds(self, thrust: np.ndarray) -> bool:
        """Whether the power holds some actuator back at ``thrust``: one whose range a bound
        narrows sits at that bound."""
        return bool(np.any(self.limited & (np.abs(thrust) >= self.bound * (1.0 - AT_LIMIT))))


@dataclass(frozen=True)
class SourcePower:
    """One sample's power per source: ``source`` names, ``power`` drawn and ``available`` [kW],
    and whether the power held some actuator back (``limited``)."""

    source: tuple[str, ...]
    power: np.ndarray
    available: np.ndarray
    limited: bool


class PowerBudget:
    """The sources, feeds and power coefficients of one configuration, and the available
    power [kW] in force: the topic's (or the capacity), zero for a source a group fault took."""

    def __init__(self, vehicle: Vehicle):
        actuators = vehicle.actuators
        self.sources = tuple(s.name for s in vehicle.power_sources)
        self.capacity = np.array([s.capacity for s in vehicle.power_sources], dtype=float)
        index = {name: j for j, name in enumerate(self.sources)}
        self.shares = np.zeros((len(actuators), len(self.sources)))
        for i, actuator in enumerate(actuators):
            for feed, share in zip(actuator.feeds, actuator.feed_shares or (1.0,) * len(actuator.feeds)):
                self.shares[i, index[feed]] = share
        self.drive = DrivePower.of(vehicle)
        self.efficiency = np.ones(len(actuators))
        self._in_force: tuple[np.ndarray, DrivePower] | None = None
        self.ties = BusTies.of(self.sources, vehicle.bus_ties)
        self.ramp = RestoreRamp(self.capacity, vehicle.power_restore_ramp)
        self.rated_thrust = np.array([max(abs(a.thrust_min), abs(a.thrust_max)) for a in actuators], dtype=float)
        self.fed = self.shares.any(axis=1)
        self.reported = self.capacity.copy()
        self.lost: frozenset[str] = frozenset()
        self.groups: dict[str, RedundancyGroup] = {g.name: g for g in vehicle.redundancy_groups}

    def rebound(self, vehicle: Vehicle) -> PowerBudget:
        """The budget of a new configuration, the available power reported for the sources it
        keeps and the losses of the groups it keeps carried over."""
        budget = PowerBudget(vehicle)
        for j, source in enumerate(budget.sources):
            if source in self.sources:
                budget.reported[j] = self.reported[self.sources.index(source)]
        budget.lost = self.lost & set(budget.sources)
        budget.ties = budget.ties.carried(self.ties)
        budget.ramp.carried(budget.sources, self.ramp, self.sources)
        budget.efficiency = self.efficiency
        return budget

    @property
    def in_force(self) -> DrivePower:
        """The drives' coefficients on the delivered force at the faults in force (made again
        when :attr:`efficiency` is another array; it is replaced, never changed in place)."""
        if self._in_force is None or self._in_force[0] is not self.efficiency:
            self._in_force = (self.efficiency, self.drive.degraded(self.efficiency))
        return self._in_force[1]

    @property
    def coefficient(self) -> np.ndarray:
        """P_i of every actuator's forward thrust on its delivered force (a DEGRADED one's
        P_i / eta^(3/2)) [W/N^1.5]."""
        return self.in_force.forward

    @property
    def reverse_coefficient(self) -> np.ndarray:
        """P_i of every actuator's negative thrust on its delivered force [W/N^1.5]."""
        return self.in_force.reverse

    @property
    def target(self) -> np.ndarray:
        """Available power [kW] reported (or the capacity) of every source, 0 for a lost one."""
        return np.array([0.0 if s in self.lost else a for s, a in zip(self.sources, self.reported)])

    def settle(self, efficiency: np.ndarray) -> None:
        """Take the faults' command ``efficiency`` (the drives' coefficients follow it) and the
        available power in force (a drop holds at once on the restore ramp)."""
        self.efficiency = np.asarray(efficiency, dtype=float).copy()
        self.ramp.follow(self.target)

    def advance(self, seconds: float) -> bool:
        """The restore ramp ``seconds`` on; whether the available power in force changed."""
        return self.ramp.advance(self.target, seconds)

    def rows(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The power rows of the ties in force: (weights w (m x r), the share of thruster i's
        power on row j, s_ij / S_i over its live rows and 0 on a dead one; available power A of
        every row [kW], a bus's sum on its first source and inf on its others; S, every
        thruster's live share, whose feed limit is p_i <= S_i R_i)."""
        rows = self.ties.pool_available(self.available)
        live = self.ties.pool_shares(self.shares) * (rows > 0.0)
        live_share = live.sum(axis=1)
        weights = np.divide(live, live_share[:, None], out=np.zeros_like(live), where=live_share[:, None] > 0.0)
        return weights.T, rows, live_share

    @property
    def pattern(self) -> np.ndarray:
        """(m x r) every (row, thruster) that some state of the ties makes non-zero."""
        return self.ties.pattern(self.shares)

    @property
    def active(self) -> bool:
        """Whether the configuration has power sources at all."""
        return bool(self.sources)

    @property
    def available(self) -> np.ndarray:
        """Available power [kW] of every source in force (a lost source's is 0; on the restore
        ramp, at most its power in use)."""
        return self.ramp.in_use(self.target)

    def checked(self, available: Mapping[str, float]) -> dict[str, float]:
        """``available`` [kW] by source as floats; ValueError naming the source for an unknown
        one or a value that is not a finite number >= 0."""
        values = {}
        for source, kilowatts in available.items():
            if source not in self.sources:
                raise ValueError(f"unknown power source '{source}'; sources: {', '.join(self.sources) or 'none'}")
            kilowatts = float(kilowatts)
            if not (np.isfinite(kilowatts) and kilowatts >= 0.0):
                raise ValueError(f"available power of {source} must be finite and >= 0 kW, got {kilowatts}")
            values[source] = kilowatts
        return values

    def report(self, available: Mapping[str, float]) -> bool:
        """Take the available power [kW] of the sources named (:meth:`checked` first); whether
        any changed."""
        before = self.reported.copy()
        for source, kilowatts in self.checked(available).items():
            self.reported[self.sources.index(source)] = kilowatts
        return not np.array_equal(before, self.reported)

    def group(self, name: str) -> RedundancyGroup:
        """The redundancy group ``name``; ValueError naming the groups for another name."""
        if name not in self.groups:
            raise ValueError(f"unknown redundancy group '{name}'; groups: {', '.join(self.groups) or 'none'}")
        return self.groups[name]

    def limit(self, low: np.ndarray, high: np.ndarray) -> PowerLimit:
        """The power rule's bounds given the static force ranges ``low``/``high`` that faults,
        speed and voltage leave (module docstring)."""
        kilowatts = self.available
        row_weights, rows, live_share = self.rows()
        weights, available = row_weights.T, rows * KW
        derated = np.where(self.fed, live_share ** (2.0 / 3.0) * self.rated_thrust, np.inf)
        largest = np.minimum(np.maximum(np.abs(low), np.abs(high)), derated)
        coefficient = self.in_force.bound_coefficient(low, high)
        drawing = self.fed & (coefficient > 0.0)
        demand = (coefficient * np.where(drawing, largest, 0.0) ** 1.5) @ weights
        rho = np.minimum(1.0, np.divide(available, demand, out=np.ones_like(demand), where=demand > 0.0))
        scale = np.where((weights > 0.0) & drawing[:, None], rho, 1.0).min(axis=1, initial=1.0)
        bound = np.where(self.fed, np.minimum(derated, largest * scale ** (2.0 / 3.0)), np.inf)
        limited = bound < np.maximum(np.abs(low), np.abs(high))
        return PowerLimit(bound=bound, weights=weights, limited=limited, available=kilowatts,
                          largest=np.where(self.fed, largest, np.inf), rho=rho, rows=rows)

    def shared(self, limit: PowerLimit, bound: np.ndarray, thrust: np.ndarray,
               movable: np.ndarray) -> np.ndarray | None:
        """Bounds [N] that give a short source's unused power to its consumers (module
        docstring), from a sample's ``thrust`` inside the bounds ``bound`` under ``limit``; None
        when no short source has power to spare and a consumer at its bound that could take it
        (``movable``: those whose window this sample may open).

        Source j shares again when its draw W_j is below A_j (1 - SPARE) and a consumer sits at
        its bound: each of its consumers may grow to g_j |f_i|, g_j = (A_j / W_j)^(2/3), so
        that the draw on j is at most g_j^(3/2) W_j = A_j, the sample's own thrust pattern
        scaled up until the source is full. An actuator fed by several sources takes the
        smallest g of those sharing and keeps its bound if another of its sources is short."""
        available = limit.rows * KW
        drive = self.in_force
        drawing = self.fed & ((drive.forward > 0.0) | (drive.reverse > 0.0))
        consumers = (limit.weights > 0.0) & drawing[:, None]
        magnitude = np.abs(thrust)
        draw = np.where(drawing, drive.power(thrust), 0.0) @ limit.weights
        at_bound = limit.limited & movable & (magnitude >= bound * (1.0 - AT_LIMIT))
        short = limit.rho < 1.0
        sharing = (short & (draw < available * (1.0 - SPARE)) & (draw > available * PATTERN)
                   & (consumers & at_bound[:, None]).any(axis=0))
        if not sharing.any():
            return None
        growth = np.divide(available, draw, out=np.ones_like(draw), where=sharing) ** (2.0 / 3.0)
        grown = np.where(consumers & sharing, growth * magnitude[:, None], np.inf).min(axis=1, initial=np.inf)
        held = (consumers & short & ~sharing).any(axis=1)
        new = np.minimum(np.where(held, np.minimum(grown, bound), grown), limit.largest)
        return np.where(consumers[:, sharing].any(axis=1), new, bound)

    def draw(self, thrust: np.ndarray, limit: PowerLimit) -> np.ndarray:
        """Power [kW] each source gives at ``thrust``: p_i = P_i |f_i|^(3/2) (1.44), P_i the
        forward or reverse coefficient (:mod:`.drive_power`), split over the live feeds' rows, a
        bus's draw over its sources by their available power (:meth:`.BusTies.split`)."""
        rows = self.in_force.power(thrust) @ limit.weights / KW
        return self.ties.split(rows, limit.available)

    def reading(self, thrust: np.ndarray, limit: PowerLimit) -> SourcePower:
        """The :class:`SourcePower` of a sample's ``thrust`` under ``limit``."""
        return SourcePower(self.sources, self.draw(thrust, limit), limit.available, limit.holds(thrust))


def narrowed(low: np.ndarray, high: np.ndarray, limit: PowerLimit) -> tuple[np.ndarray, np.ndarray]:
    """The static ranges inside the power bounds."""
    bound = np.where(limit.limited, limit.bound, np.inf)
    return np.clip(low, -bound, bound), np.clip(high, -bound, bound)
