"""Thrust losses of the simulated thrusters, as plain data a caller computes (the DNV-ST-0111
Level 3 case computes them with the capability analysis' clauses, :mod:`allocator_pkg.dp.level3.case_losses`):
per set of dead actuators, each working actuator's factor on its positive and on its negative
thrust (misc. losses, ventilation, the power its remaining feeds give) and its factor by thrust
direction (flushing a dead thruster or a skeg), a
:class:`~allocator_pkg.capability.thrust_profile.ThrustProfile`. The thrust an actuator
delivers is its command, inside its range, times these factors at the direction it pushes."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from ..capability.thrust_profile import ThrustProfile


@dataclass(frozen=True)
class LossCase:
    """The factors while the actuators ``dead`` do not work; an actuator not named keeps 1."""

    dead: frozenset[str]
    forward: Mapping[str, float] = field(default_factory=dict)
    reverse: Mapping[str, float] = field(default_factory=dict)
    profiles: Mapping[str, ThrustProfile] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for kind in ("forward", "reverse"):
            for name, factor in getattr(self, kind).items():
                if not 0.0 <= factor <= 1.0:
                    raise ValueError(f"thrust_losses.{kind}.{name}: a factor in [0, 1], not {factor!r}")


@dataclass(frozen=True)
class ThrustLosses:
    """The loss cases of a run (intact, and each set of dead actuators it reaches) and what they
    are, in a sentence, for a report."""

    cases: tuple[LossCase, ...]
    description: str = ""

    def case(self, dead: frozenset[str]) -> LossCase:
        """The case of the dead actuators ``dead``, else the case of most dead actuators among
        those whose dead are all dead now (the intact case at least; the actuators of a group
        fail one after the other within one step); ValueError when there is none."""
        within = [found for found in self.cases if found.dead <= dead]
        if not within:
            raise ValueError(f"thrust_losses: no loss case within {', '.join(sorted(dead)) or 'no actuator'} dead "
                             f"(cases: {'; '.join(', '.join(sorted(c.dead)) or 'intact' for c in self.cases)})")
        return max(within, key=lambda found: len(found.dead))

    def names(self) -> set[str]:
        """Every actuator the cases name."""
        return {name for case in self.cases for table in (case.dead, case.forward, case.reverse, case.profiles)
                for name in table}
