"""The rising search of DNV-ST-0111 [2.4.4] over Level 3 cases: per heading and case (intact or a
redundancy group), conditions 1, 2, ... are simulated in turn until the first that fails; the
capability number is the one below it [2.2.2]. A condition runs the same seed indices 0 ...
``criteria.seeds`` - 1 and holds on the quantile of its seeds' excursions
(:func:`~.statistics.condition_holds`). A condition the static Level 2 balance already fails
(above the ``ceiling`` of the chain) is not simulated: the number stops there. A case is known by
:attr:`~.case.Case.key`, its seed included: a run the search already has (a resumed journal's, one
of fewer seeds) is never asked for again.

:meth:`Level3Search.pending` is what must run next given what has finished; it asks for the
next condition of a chain only when every seed of the one before has finished, so the cases run
(and every output) are the same in whatever order and on however many workers they finish.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from .case import Case, CaseResult, Criteria
from .statistics import condition_holds

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
    """Headings [deg], cases (``intact`` and the groups), the criteria (seeds per condition and
    how they decide it), and per (heading, case) the static Level 2 number (the highest
    condition simulated); ``top`` the table's last number."""

    headings: tuple[float, ...]
    cases: tuple[str, ...]
    criteria: Criteria
    ceilings: Mapping[tuple[float, str], int]
    top: int
    verdicts: dict[tuple[float, str, int], tuple[list[CaseResult], bool]] = field(
        default_factory=dict, init=False, repr=False, compare=False)
    """Each decided condition's runs and verdict, reused while the same runs are asked about
    (the search asks about every chain each time a run finishes)."""

    @property
    def seeds(self) -> int:
        return self.criteria.seeds

    def seed_results(self, chain: tuple[float, str], number: int,
                     finished: Mapping[tuple, CaseResult]) -> list[CaseResult] | None:
        """The results of seeds 0 ... seeds - 1 of ``chain`` at ``number``; None until all have finished."""
        heading, case = chain
        results = [finished.get((heading, number, case, seed)) for seed in range(self.seeds)]
        return None if any(result is None for result in results) else results

    def chains(self) -> list[tuple[float, str]]:
        return [(heading, case) for case in self.cases for heading in self.headings]

    def outcome(self, chain: tuple[float, str], finished: Mapping[tuple, CaseResult]) -> ChainOutcome:
        """Where ``chain`` stands given the ``finished`` results (by :attr:`Case.key`)."""
        ceiling = self.ceilings[chain]
        number = 0
        while number < ceiling:
            results = self.seed_results(chain, number + 1, finished)
            if results is None:
                return ChainOutcome(number, "", False)
            if not self.holds(chain, number + 1, results):
                return ChainOutcome(number, FAILED, True)
            number += 1
        return ChainOutcome(number, TOP if number == self.top else STATIC, True)

    def holds(self, chain: tuple[float, str], number: int, results: list[CaseResult]) -> bool:
        """:func:`~.statistics.condition_holds` of ``results``, computed once for the same runs."""
        key = (*chain, number)
        known = self.verdicts.get(key)
        if known is None or len(known[0]) != len(results) or any(a is not b for a, b in zip(known[0], results)):
            known = self.verdicts[key] = (results, condition_holds(results, self.criteria))
        return known[1]

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
