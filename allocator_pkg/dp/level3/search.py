"""The rising search of DNV-ST-0111 [2.4.4] over Level 3 cases: per heading and case (intact or a
redundancy group), conditions 1, 2, ... are simulated in turn until the first that fails; the
capability number is the one below it [2.2.2]. A condition holds when every seed of it held. A
condition the static Level 2 balance already fails (above the ``ceiling`` of the chain) is not
simulated: the number stops there.

:meth:`Level3Search.pending` is what must run next given what has finished; it asks for the
next condition of a chain only when every seed of the one before has finished, so the cases run
(and every output) are the same in whatever order and on however many workers they finish.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from .case import Case, CaseResult

FAILED = "failed"
STATIC = "static Level 2"
TOP = "top condition"


@dataclass(frozen=True)
class ChainOutcome:
    """A chain's number, why it stops there (``failed``: the next condition failed in the time
    domain; ``static Level 2``: the static balance fails the next one, not simulated; ``top
    condition``: the table ends), and whether it is decided yet."""

    number: int
    reason: str
    decided: bool


@dataclass(frozen=True)
class Level3Search:
    """Headings [deg], cases (``intact`` and the groups), seeds per condition, and per (heading,
    case) the static Level 2 number (the highest condition simulated); ``top`` the table's last
    number."""

    headings: tuple[float, ...]
    cases: tuple[str, ...]
    seeds: int
    ceilings: Mapping[tuple[float, str], int]
    top: int

    def chains(self) -> list[tuple[float, str]]:
        return [(heading, case) for case in self.cases for heading in self.headings]

    def outcome(self, chain: tuple[float, str], finished: Mapping[tuple, CaseResult]) -> ChainOutcome:
        """Where ``chain`` stands given the ``finished`` results (by :attr:`Case.key`)."""
        heading, case = chain
        ceiling = self.ceilings[chain]
        number = 0
        while number < ceiling:
            results = [finished.get((heading, number + 1, case, seed)) for seed in range(self.seeds)]
            if any(result is None for result in results):
                return ChainOutcome(number, "", False)
            if not all(result.held for result in results):
                return ChainOutcome(number, FAILED, True)
            number += 1
        return ChainOutcome(number, TOP if number == self.top else STATIC, True)

    def pending(self, finished: Mapping[tuple, CaseResult]) -> list[Case]:
        """The cases to run next: every unfinished seed of each undecided chain's next condition."""
        cases = []
        for chain in self.chains():
            outcome = self.outcome(chain, finished)
            if not outcome.decided:
                heading, group = chain
                cases += [Case(heading, outcome.number + 1, group, seed) for seed in range(self.seeds)
                          if (heading, outcome.number + 1, group, seed) not in finished]
        return cases

    def done(self, finished: Mapping[tuple, CaseResult]) -> bool:
        return all(self.outcome(chain, finished).decided for chain in self.chains())
