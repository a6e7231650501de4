"""The buses of the simulated power plant and their frequency: switchboards joined by closed bus
ties form one bus, and each bus's connected generator sets share one frequency by the swing
equation (Kundur, Power System Stability and Control, (3.15) and section 11.1.3: the sets of
one bus as one equivalent machine), per unit on the bus's rating:

    2 H_bus S_bus df/dt = sum_i S_i p_m,i - P_e,    H_bus S_bus = sum_i H_i S_i

with P_e [kW] the load of the bus's switchboards (constant power: no load damping), S_i [kVA]
the ratings and p_m,i the sets' mechanical power [pu of S_i]. Each set gives electrically its
mechanical power less its share of the kinetic energy the bus gives up or takes,
P_e,i = S_i p_m,i - (H_i S_i / H_bus S_bus)(sum_j S_j p_m,j - P_e); in steady state that is
its droop share. A bus with no connected set is dead: frequency 0, nothing supplied, and it
stays dead (no restart of a set in a run)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from ..allocation.bus_ties import bus_heads
from .generator_set import GeneratorSet


@dataclass(frozen=True)
class BusTieSpec:
    """A bus tie breaker between two switchboards."""

    name: str
    between: tuple[str, str]
    closed: bool = True


def buses(switchboards: Sequence[str], ties: dict[str, BusTieSpec], closed: dict[str, bool]) -> list[tuple[str, ...]]:
    """The switchboards grouped into buses by the closed ties (:func:`~...allocation.bus_ties.bus_heads`,
    as the allocator groups its power sources), each bus in switchboard order."""
    heads = bus_heads(switchboards, [tie.between for tie in ties.values() if closed[tie.name]])
    groups: dict[int, list[str]] = {}
    for name, head in zip(switchboards, heads):
        groups.setdefault(head, []).append(name)
    return [tuple(group) for group in groups.values()]


class Bus:
    """One bus: its switchboards, the generator sets on them and its frequency [pu]."""

    def __init__(self, switchboards: tuple[str, ...], sets: list[GeneratorSet], frequency: float) -> None:
        self.switchboards = switchboards
        self.sets = sets
        self.frequency = frequency if self.live else 0.0

    @property
    def live(self) -> bool:
        return any(g.connected for g in self.sets)

    def inertia(self) -> float:
        """sum_i 2 H_i S_i [kW s] of the connected sets."""
        return sum(2.0 * g.spec.inertia * g.spec.rating for g in self.sets if g.connected)

    def mechanical(self) -> float:
        """sum_i S_i p_m,i [kW]."""
        return sum(g.spec.rating * g.p_m for g in self.sets if g.connected)

    def advance(self, load: float, dt: float, time: float) -> list[GeneratorSet]:
        """``dt`` [s] under ``load`` [kW] ending at ``time``: the swing equation (an explicit
        Euler step: ``dt`` is a small share of the governors' period, 2 pi sqrt(2 H T R)), the
        governors at the new frequency, then the frequency relays; the sets that tripped."""
        if not self.live:
            self.frequency = 0.0
            return []
        self.frequency += (self.mechanical() - load) / self.inertia() * dt
        for g in self.sets:
            g.advance(self.frequency, dt)
        tripped = [g for g in self.sets if g.protect(self.frequency, dt, time)]
        if not self.live:
            self.frequency = 0.0
        return tripped

    def electrical(self, load: float) -> dict[str, float]:
        """P_e,i [kW] of each connected set under ``load`` [kW]."""
        if not self.live:
            return {}
        surplus, inertia = self.mechanical() - load, self.inertia()
        return {g.spec.name: g.spec.rating * g.p_m - 2.0 * g.spec.inertia * g.spec.rating / inertia * surplus
                for g in self.sets if g.connected}
