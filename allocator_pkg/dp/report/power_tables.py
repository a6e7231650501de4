"""The power tables of a DNV-ST-0111 Level 1 report, Tables A-9 and A-10: the power the thrusters
draw at each heading's limiting condition, per thruster and per switchboard or prime mover.

The transcription (repository WilliamBoland1/Prosjektoppgave_Collab, ``power.md``) reads [3.12.5]
and App. A.3.5 as: the thrust utilisation, thrust loss factor and power utilisation at switchboard
level are documented per condition, on the templates of Tables A-8 to A-10, with the reserved
power per switchboard in Table A-10; it gives neither table's columns. Read here:

- :func:`table_a9`: per case, heading and working thruster at the heading's number, its thrust
  fraction r (Table A-8's utilisation: its thrust over what it can give that way), the power it
  draws, s P_B r^(3/2) with s the sum of its working feed shares (:mod:`..standard.power_balance`), and that
  power per source (its feed share of it, Table A-5);
- :func:`table_a10`: per case, heading and working source, its available power, the 10 % reserved
  [3.12.3], the usable rest, the power its thrusters draw (the sum of its Table A-9 column) and
  that as a share of the usable power.

The allocation is Table A-8's (the result's
:attr:`~allocator_pkg.dp.capability_result.CapabilityResult.allocations`): the forces of the
largest multiple of the load, scaled down to the load; another allocation that holds the load can
draw less.
Not verified by DNV.
"""

from __future__ import annotations

from ..capability_result import CapabilityResult
from ..level1 import Level1
from ..standard.power_balance import POWER_RESERVE, part_load_power, usable

A9_FIXED = ("case", "heading_deg", "capability_number", "thruster", "thrust_fraction", "power_kw")
A10_COLUMNS = ("case", "heading_deg", "capability_number", "source", "available_kw", "reserved_kw", "usable_kw",
               "thrusters_kw", "utilisation_pct")


def a9_columns(analysis: Level1) -> tuple[str, ...]:
    """:data:`A9_FIXED`, then ``<source>_kw`` per power source."""
    return (*A9_FIXED, *(f"{source}_kw" for source in analysis.capacities))


def source_powers(analysis: Level1, name: str, fraction: float, lost: tuple[str, ...]) -> dict[str, float]:
    """[kW] per working source what a thruster at the thrust fraction ``fraction`` draws from it:
    s_j P_B r^(3/2) (its feed shares, Table A-5)."""
    actuator = analysis.vehicle.actuator(name)
    power = analysis.particulars.thrusters[name].power * part_load_power(fraction)
    return {feed: share * power for feed, share in zip(actuator.feeds, actuator.feed_shares) if feed not in lost}


def table_a9(analysis: Level1, result: CapabilityResult) -> list[tuple]:
    """Per case, heading and working thruster (:func:`a9_columns`): the thrust fraction, the power
    [kW] it draws (without feeds: P_B r^(3/2)) and per source what it draws from there."""
    rows = []
    for case, heading, number, uses in result.allocations:
        lost = tuple(analysis.groups.get(case, ()))
        for use in uses:
            drawn = source_powers(analysis, use.name, use.utilisation, lost)
            total = sum(drawn.values()) if analysis.vehicle.actuator(use.name).feeds else \
                analysis.particulars.thrusters[use.name].power * part_load_power(use.utilisation)
            rows.append((case, heading, number, use.name, use.utilisation, total,
                         *(drawn.get(source, 0.0) for source in analysis.capacities)))
    return rows


def table_a10(analysis: Level1, result: CapabilityResult) -> list[tuple]:
    """Per case, heading and working source (:data:`A10_COLUMNS`): available, reserved and usable
    power, what its thrusters draw [kW] and that over the usable power [%]."""
    rows = []
    for case, heading, number, uses in result.allocations:
        lost = tuple(analysis.groups.get(case, ()))
        drawn = {source: 0.0 for source in analysis.capacities if source not in lost}
        for use in uses:
            for source, power in source_powers(analysis, use.name, use.utilisation, lost).items():
                drawn[source] += power
        for source, power in drawn.items():
            capacity = analysis.capacities[source]
            rows.append((case, heading, number, source, capacity, POWER_RESERVE * capacity, usable(capacity), power,
                         100.0 * power / usable(capacity)))
    return rows
