"""Bus-tie breakers at runtime (docs/power.md, "Bus ties"): which power sources form one bus
for the state of the ties, and the power rows of that state.

Sources joined by closed ties (directly or through others) are one bus. A bus's power is the
sum of its sources' available power, and a thruster fed by any source of the bus draws on all
of it: the row of the bus's first source (in ``power.sources`` order) carries the bus, its
weights summing the shares of every feed of the thruster on the bus and its limit the sum of
the bus's available power; the rows of the other sources of the bus are empty and unbounded.
An open tie splits them again: each source its own row, its own thrusters. What a bus draws is
split over its sources in proportion to their available power, as parallel generators share
load by their droop: each source is within its available power exactly when the bus is.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import TypeAlias

import numpy as np

from ..effectiveness.power_rows import tied_reach
from ..vehicle.config import BusTie

TieStates: TypeAlias = dict[str, bool]


def bus_heads(sources: Sequence[str], closed: Iterable[Sequence[str]]) -> list[int]:
    """Per source, the index of the first source (in ``sources`` order) of its bus, the sources
    joined by the ``closed`` ties (each the names of the two sources it joins)."""
    head = list(range(len(sources)))
    index = {name: j for j, name in enumerate(sources)}

    def root(j: int) -> int:
        while head[j] != j:
            j = head[j]
        return j

    for first, second in closed:
        a, b = sorted((root(index[first]), root(index[second])))
        head[b] = a
    return [root(j) for j in range(len(sources))]


@dataclass
class BusTies:
    """The ties of one configuration between the sources ``sources`` and each one's state
    (``closed`` by name)."""

    sources: tuple[str, ...]
    ties: tuple[BusTie, ...]
    closed: TieStates = field(default_factory=dict)
    _buses: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    """(head, pooling) of each state of the ties met, read-only (a sample's power reading asks
    for them every sample)."""

    @classmethod
    def of(cls, sources: tuple[str, ...], ties: tuple[BusTie, ...]) -> BusTies:
        """The ties in their configured states."""
        return cls(sources, ties, {tie.name: tie.closed for tie in ties})

    def carried(self, other: BusTies) -> BusTies:
        """These ties with the runtime state of every tie ``other`` has too (a new configuration
        keeps what the operator set)."""
        kept = {name: state for name, state in other.closed.items() if name in self.closed}
        return BusTies(self.sources, self.ties, {**self.closed, **kept})

    def checked(self, name: str) -> BusTie:
        """The tie ``name``; ValueError naming the ties for another name."""
        for tie in self.ties:
            if tie.name == name:
                return tie
        raise ValueError(f"unknown bus tie '{name}'; bus ties: {', '.join(t.name for t in self.ties) or 'none'}")

    def set(self, name: str, closed: bool) -> bool:
        """Open or close the tie ``name`` (:meth:`checked` first); whether its state changed."""
        self.checked(name)
        changed = self.closed[name] != bool(closed)
        self.closed[name] = bool(closed)
        return changed

    @property
    def head(self) -> np.ndarray:
        """For every source, the index of the first source of its bus (itself when no closed tie
        joins it to an earlier one); read-only."""
        return self._of_state()[0]

    def pooling(self) -> np.ndarray:
        """(m x m) matrix that maps a source's column onto its bus's row: entry (j, k) is 1 when
        source j's power and consumers go to row k; read-only."""
        return self._of_state()[1]

    def _of_state(self) -> tuple[np.ndarray, np.ndarray]:
        """(head, pooling) of the state of the ties now, made once per state."""
        state = tuple(self.closed.values())
        known = self._buses.get(state)
        if known is None:
            head = self._head()
            m = len(self.sources)
            pool = np.zeros((m, m))
            pool[np.arange(m), head] = 1.0
            head.setflags(write=False)
            pool.setflags(write=False)
            known = self._buses[state] = (head, pool)
        return known

    def _head(self) -> np.ndarray:
        """:attr:`head` made from the ties' states."""
        closed = [tie.sources for tie in self.ties if self.closed[tie.name]]
        return np.array(bus_heads(self.sources, closed), dtype=int)

    def pool_shares(self, shares: np.ndarray) -> np.ndarray:
        """The (r x m) feed shares by row: each thruster's shares on a bus summed into the bus's
        row."""
        return shares @ self.pooling()

    def pool_available(self, available: np.ndarray) -> np.ndarray:
        """Available power of every row: a bus's sum on its first source, inf on the others."""
        head = self.head
        rows = available @ self.pooling()
        return np.where(head == np.arange(head.size), rows, np.inf)

    def split(self, rows: np.ndarray, available: np.ndarray) -> np.ndarray:
        """What each source gives of its bus's draw ``rows`` (by row): the bus's draw in
        proportion to the available power of its sources (all on the first one when the bus has
        none)."""
        head = self.head
        total = (available @ self.pooling())[head]
        first = head == np.arange(head.size)
        share = np.divide(available, total, out=first.astype(float), where=total > 0.0)
        return rows[head] * share

    def pattern(self, shares: np.ndarray) -> np.ndarray:
        """(m x r) every (row, thruster) pair that some state of the ties makes non-zero
        (:func:`~allocator_pkg.effectiveness.power_rows.tied_reach`)."""
        return tied_reach(self.sources, tuple(tuple(t.sources) for t in self.ties), shares)

    def buses(self) -> list[tuple[str, ...]]:
        """The buses of the state in force: the sources of each, in ``power.sources`` order."""
        head = self.head
        return [tuple(s for s, h in zip(self.sources, head) if h == k) for k in sorted(set(head.tolist()))]

    def reply(self, name: str) -> str:
        """What a change of the tie ``name`` answers: its state and the buses it leaves."""
        buses = " | ".join(" + ".join(bus) for bus in self.buses())
        return f"bus tie {name} {'closed' if self.closed[name] else 'open'} from the next sample; buses: {buses}"

    def text(self) -> str:
        """The state of every tie, for the diagnostics and the log: ``bt_ab closed (swbd_a +
        swbd_b)``."""
        return ", ".join(f"{t.name} {'closed' if self.closed[t.name] else 'open'} ({' + '.join(t.sources)})"
                         for t in self.ties)

