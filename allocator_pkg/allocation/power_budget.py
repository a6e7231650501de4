"""Power per source in the allocation (docs/power.md): what each source gives, as the power rows
a method solves with, and the proportional bounds of a method without rows.

Actuator i draws p_i = P_i |f_i|^(3/2) (1.44); its rated power is R_i = P_i F_i^(3/2), F_i the
largest magnitude of its configured thrust range. Feed j of share s_ij can give
e_ij = min(s_ij, A_j / R_i) of the rated power (0 from a source at 0 kW: a dead feed; the full
share from one that has at least s_ij R_i; a single feed its full share while it has power, the
source's row bounding the rest); S_i = sum_j e_ij. The actuator's power comes from
its feeds in proportion to e (feed j gives p_i e_ij / S_i), and no feed gives more than
e_ij R_i, so p_i <= S_i R_i: with every feed strong the power splits by the shares and the
limit is the rated power; a split-fed actuator whose feed is lost or weak runs on the rest,
derated (|f_i| <= S_i^(2/3) F_i, a range). e is continuous in A_j, so a weak feed coming up
adds thrust rather than tying the actuator to its small power.

**The rows contract** (:meth:`PowerBudget.rows`, read by every method that solves an
optimisation, :mod:`allocator_pkg.effectiveness.power_rows`): a
:class:`~allocator_pkg.effectiveness.power_rows.PowerRows` with, per row j (one per source),
the weight w_ij of each actuator i (actuators x rows: the share of p_i row j carries,
e_ij / S_i on live rows), the available power A_j [W] (inf: the row bounds nothing), the
fixed boolean ``pattern`` (actuators x rows: every (i, j) that some state of the bus ties can
make non-zero), and per actuator the forward and the reverse power coefficient and the range
F_i the chords cover. A method puts sum_i w_ij P_i h(|f_i|) <= A_j (h the chord interpolant of
|f|^(3/2)) into its problem; a change of weights, available power, coefficients or tie state
is values only, a new pattern (a new configuration's feeds or ties) a new structure.

**The proportional bounds** (:meth:`PowerBudget.limit`), for a method without rows (the
pseudo-inverse family, docs/power.md): a source j whose consumers could together draw more
than it has (D_j > A_j, each consumer at the largest thrust faults, voltage and the derating
leave it, m_i) is shared in proportion to those largest draws: each consumer's power is scaled
by rho_j = A_j / D_j, an actuator by the smallest rho of its live feeds. That bounds
|f_i| <= m_i rho^(2/3), and the draw on source j is at most rho_j D_j = A_j by construction.

The sources are taken by row, for the rows and the proportional bounds alike: a closed bus tie
pools the sources of a bus into its first source's row (:mod:`.bus_ties`: weights over every
thruster the bus feeds, A_j the bus's sum, its other rows inf; e_ij on the pooled rows), and
each drive's power has its forward and reverse coefficients, a DEGRADED thruster's counted on
its set-point (:mod:`.drive_power`); the proportional bounds' coefficient is the larger of the
two its range allows, R_i the larger one's. The available power in use follows the restore
ramp (:mod:`.restore_ramp`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..effectiveness.model import AT_LIMIT
from ..effectiveness.power_rows import PowerPattern, PowerRows, feed_shares
from ..vehicle.config import RedundancyGroup, Vehicle
from .bus_ties import BusTies
from .drive_power import KW, DrivePower
from .restore_ramp import RestoreRamp

HELD = 1e-3
"""A short source whose draw, as the chord rows see it, is within this share of its available
power holds the thrust back."""


@dataclass(frozen=True)
class PowerLimit:
    """The power rule at one set of available powers: ``bound`` [N], the largest thrust
    magnitude of every actuator (inf: the power sets none); ``weights`` (r x m), the share of
    actuator i's power drawn from row j (0 from a lost feed; a closed bus on its first source's
    row); ``limited``, the actuators
    whose range the bound narrows; ``available``, the available power [kW] of every source
    the rule took; ``largest`` [N], the largest thrust magnitude faults, speed, voltage and the
    feed limit leave every actuator (m_i; inf for one without feeds); ``rho``, every row's
    share of its consumers' largest draws (1: it limits nothing). With ``rows`` (the method
    solves with the power rows) ``bound`` is only the derating of a lost feed and the rows
    keep the sources within their power; ``proportional`` is then the proportional bounds all the
    same, the fallback's when the method fails."""

    bound: np.ndarray
    weights: np.ndarray
    limited: np.ndarray
    available: np.ndarray
    largest: np.ndarray
    rho: np.ndarray
    proportional: np.ndarray
    rows: PowerRows | None = None

    def holds(self, thrust: np.ndarray) -> bool:
        """Whether the power holds some actuator back at ``thrust``: one whose range a bound
        narrows sits at that bound, or (with rows) a short source's row is full as the chord
        rows see it."""
        if np.any(self.limited & (np.abs(thrust) >= self.bound * (1.0 - AT_LIMIT))):
            return True
        if self.rows is None:
            return False
        full = self.rows.seen(thrust) >= self.rows.available * (1.0 - HELD)
        return bool(np.any(full & (self.rho < 1.0)))


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
        self.shares = feed_shares(vehicle)
        self.pattern = PowerPattern.of(vehicle)
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
        return budget

    @property
    def in_force(self) -> DrivePower:
        """The drives' coefficients on the delivered force at the faults in force (made again
        when :attr:`efficiency` is another array; :meth:`settle` replaces it when its values
        change, never in place)."""
        if self._in_force is None or self._in_force[0] is not self.efficiency:
            self._in_force = (self.efficiency, self.drive.degraded(self.efficiency))
        return self._in_force[1]

    @property
    def target(self) -> np.ndarray:
        """Available power [kW] reported (or the capacity) of every source, 0 for a lost one."""
        return np.array([0.0 if s in self.lost else a for s, a in zip(self.sources, self.reported)])

    def settle(self, efficiency: np.ndarray) -> None:
        """Take the faults' command ``efficiency`` (the drives' coefficients follow it) and the
        available power in force (a drop holds at once on the restore ramp)."""
        efficiency = np.asarray(efficiency, dtype=float)
        if not np.array_equal(efficiency, self.efficiency):
            self.efficiency = efficiency.copy()
        self.ramp.follow(self.target)

    def advance(self, seconds: float) -> bool:
        """The restore ramp ``seconds`` on; whether the available power in force changed."""
        return self.ramp.advance(self.target, seconds)

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

    def _weights(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(w_ij = e_ij / S_i, A_j [W] of every row, S_i = sum_j e_ij) of the ties in force: the
        rows pool a closed bus's feeds and power on its first source (:mod:`.bus_ties`; inf on
        its others), and e_ij = min(s_ij, A_j / R_i) is the share row j of a split-fed actuator
        can give at its rated power R_i (the larger coefficient's), s_ij for a single live row
        (module docstring)."""
        available = self.ties.pool_available(self.available * KW)
        shares = self.ties.pool_shares(self.shares)
        drive = self.in_force
        rated = np.maximum(drive.forward, drive.reverse) * self.rated_thrust ** 1.5
        with np.errstate(divide="ignore", invalid="ignore"):
            room = np.where(rated[:, None] > 0.0, available[None, :] / rated[:, None], np.inf)
        split = ((shares > 0.0).sum(axis=1) > 1)[:, None]
        room = np.where(split, room, np.inf)
        live = np.where(shares > 0.0, np.minimum(shares, np.where(available[None, :] > 0.0, room, 0.0)), 0.0)
        live_share = live.sum(axis=1)
        weights = np.divide(live, live_share[:, None], out=np.zeros_like(live), where=live_share[:, None] > 0.0)
        return weights, available, live_share

    def rows(self) -> PowerRows | None:
        """The power rows' values in force (the contract of the module docstring): the rows of
        the ties in force on the pattern of every tie state, the drives' forward and reverse
        coefficients at the faults in force; None without sources."""
        if self.pattern is None:
            return None
        weights, available, _ = self._weights()
        return self._rows(weights, available)

    def _rows(self, weights: np.ndarray, available: np.ndarray) -> PowerRows:
        """The power rows of ``weights`` and ``available`` [W] (:meth:`_weights`) at the drives'
        coefficients in force."""
        drive = self.in_force
        return PowerRows(pattern=self.pattern, weights=weights, available=available, forward=drive.forward,
                         reverse=drive.reverse, rated=self.rated_thrust)

    def limit(self, low: np.ndarray, high: np.ndarray, rows: bool = False) -> PowerLimit:
        """The power rule given the static force ranges ``low``/``high`` that faults, speed and
        voltage leave (module docstring): the proportional bounds, or with ``rows`` (the method
        solves with the power rows) the derating of lost feeds only, and the rows."""
        kilowatts = self.available
        weights, available, live_share = self._weights()
        derated = np.where(self.fed, live_share ** (2.0 / 3.0) * self.rated_thrust, np.inf)
        largest = np.minimum(np.maximum(np.abs(low), np.abs(high)), derated)
        coefficient = self.in_force.bound_coefficient(low, high)
        drawing = self.fed & (coefficient > 0.0)
        demand = (coefficient * np.where(drawing, largest, 0.0) ** 1.5) @ weights
        rho = np.minimum(1.0, np.divide(available, demand, out=np.ones_like(demand), where=demand > 0.0))
        scale = np.where((weights > 0.0) & drawing[:, None], rho, 1.0).min(axis=1, initial=1.0)
        proportional = np.where(self.fed, np.minimum(derated, largest * scale ** (2.0 / 3.0)), np.inf)
        bound = np.where(self.fed, np.minimum(derated, largest), np.inf) if rows else proportional
        limited = bound < np.maximum(np.abs(low), np.abs(high))
        return PowerLimit(bound=bound, weights=weights, limited=limited, available=kilowatts,
                          largest=np.where(self.fed, largest, np.inf), rho=rho, proportional=proportional,
                          rows=self._rows(weights, available) if rows and self.pattern is not None else None)

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
