"""The result tables of a DNV-ST-0111 Level 1 report (App. A.3), from a
:class:`~allocator_pkg.dp.level1.Level1` analysis and its complete
:class:`~allocator_pkg.dp.capability_result.CapabilityResult`.

- :func:`table_a1`: per heading the capability number intact, after each redundancy group's
  loss and combined (the lowest over the groups, [2.4.7]), and which group is the worst there;
- :func:`table_a6`: the forbidden zones [3.11.3] in force in each case;
- :func:`loss_sector_table`: beside Table A-6, the sectors of reduced thrust of [3.11.4] and
  [3.11.5] in each case (Table A-6 has room for forbidden zones only: a sector here lowers the
  thrust, down to the lowest factor, and forbids nothing);
- :func:`table_a7`: per case and heading the number, the limiting wind speed and the wind,
  current and wave loads of the number's condition (Table 2-1), unfactored, in the standard's
  frame [2.8.2] (x forward, y to port, moment about Lpp/2 positive bow to port);
- :func:`table_a8`: per case, heading and thruster the thrust at the number's condition and its
  share of the thrust available in that direction (the "utilisation" of Table A-8), from the
  result's allocations (:meth:`~allocator_pkg.dp.level1.Level1.thruster_use`);
- :func:`load_table`: the loads per source for every heading and number from 1, same frame.

Forces in kN, moments in kN m. The utilisation of Table A-8 is that of one allocation which holds
the load: the forces of the largest multiple of the load the balance finds, scaled down to the
load. The standard's template does not fix the allocation; the least-loaded one can be lower.
Not verified by DNV.
"""

from __future__ import annotations

import math

from ..capability_result import INTACT, WORST, CapabilityResult
from ..level1 import DYNAMIC_FACTOR, LOAD_SOURCES, Level1
from ..standard.losses import loss_sectors

KILO = 1e3
A1_FIXED = ("heading_deg", INTACT)
A6_COLUMNS = ("case", "thruster", "from_deg", "to_deg", "flushing")
LOSS_COLUMNS = ("case", "thruster", "from_deg", "to_deg", "lowest_factor", "at_deg")
A7_COLUMNS = ("case", "heading_deg", "capability_number", "wind_speed_limit",
              *(f"{source}_{quantity}" for source in LOAD_SOURCES for quantity in ("fx_kn", "fy_kn", "mz_knm")))
A8_COLUMNS = ("case", "heading_deg", "capability_number", "thruster", "thrust_kn", "angle_deg", "available_kn",
              "utilisation_pct")
LOAD_COLUMNS = ("heading_deg", "capability_number", "wind_speed", "hs", "tp", "current_speed", "source", "fx_kn",
                "fy_kn", "mz_knm")


def groups_of(result: CapabilityResult) -> list[str]:
    """The redundancy groups of a result, in their order."""
    return [case for case in result.numbers if case not in (INTACT, WORST)]


def worst_groups(result: CapabilityResult) -> list[str]:
    """Per heading the group whose loss leaves the lowest number (then the lowest wind speed)."""
    groups = groups_of(result)
    return [min(groups, key=lambda g: (result.numbers[g][k], result.wind_limits[g][k]))
            for k in range(len(result.headings_deg))]


def table_a1(result: CapabilityResult) -> tuple[tuple[str, ...], list[tuple]]:
    """(columns, rows): heading_deg, intact, each group, ``combined`` (the worst single failure) and
    ``worst_group``."""
    groups = groups_of(result)
    columns = (*A1_FIXED, *groups, "combined", "worst_group")
    worst = worst_groups(result)
    rows = [(float(heading), *(int(result.numbers[case][k]) for case in (INTACT, *groups, WORST)), worst[k])
            for k, heading in enumerate(result.headings_deg)]
    return columns, rows


def table_a6(analysis: Level1) -> list[tuple]:
    """(case, thruster, from_deg, to_deg, flushing) of every zone in force, intact and per group;
    angles of the thrust in the body frame (0 forward, 90 to starboard)."""
    return [(case, zone.thruster, round(math.degrees(zone.sector[0]), 2), round(math.degrees(zone.sector[1]), 2),
             zone.flushed)
            for case, failed in analysis.cases().items() for zone in analysis.zones(tuple(failed))]


def loss_sector_table(analysis: Level1) -> list[tuple]:
    """(case, thruster, from_deg, to_deg, lowest_factor, at_deg) of every [3.11.4]/[3.11.5] loss
    sector, intact and per group; thrust angles in the body frame (0 forward, 90 to starboard), the
    factor [3.11.6] linear between the corners (the case's :meth:`~..level1.Level1.thrust_profiles`)."""
    return [(case, name, round(start, 2), round(end, 2), round(lowest, 4), round(at, 2))
            for case, failed in analysis.cases().items()
            for name, profile in analysis.thrust_profiles(tuple(failed)).items()
            for start, end, lowest, at in loss_sectors(profile)]


def table_a7(analysis: Level1, result: CapabilityResult) -> list[tuple]:
    """Per case and heading: number, limiting wind speed, then [Fx, Fy, Mz] of wind, current and
    waves of the number's condition (kN, kN m; unfactored; the standard's frame)."""
    rows = []
    for case in result.numbers:
        for k, heading in enumerate(result.headings_deg):
            number = int(result.numbers[case][k])
            loads = analysis.standard_loads(analysis.conditions[number], math.radians(heading))
            rows.append((case, float(heading), number, float(result.wind_limits[case][k]),
                         *(float(value) / KILO for source in LOAD_SOURCES for value in loads[source])))
    return rows


def load_table(analysis: Level1, result: CapabilityResult) -> list[tuple]:
    """Per heading and number from 1 (to 11 with Table 2-1): the condition, then [Fx, Fy, Mz] of each source and of
    ``total x 1.25`` (the load to balance), kN and kN m, the standard's frame."""
    rows = []
    for heading in result.headings_deg:
        for number in range(1, len(analysis.conditions)):
            condition = analysis.conditions[number]
            loads = analysis.standard_loads(condition, math.radians(heading))
            loads[f"total x {DYNAMIC_FACTOR:g}"] = DYNAMIC_FACTOR * sum(loads.values())
            rows.extend((float(heading), number, condition.wind, condition.hs, condition.tp, condition.current,
                         source, *(float(v) / KILO for v in values)) for source, values in loads.items())
    return rows


def table_a8(result: CapabilityResult) -> list[tuple]:
    """Per case, heading and working thruster at the heading's number: thrust and available thrust
    [kN], thrust angle [deg] and utilisation [%] (the result's allocations)."""
    return [(case, heading, number, use.name, use.thrust / KILO, use.angle_deg, use.available / KILO,
             100.0 * use.utilisation)
            for case, heading, number, uses in result.allocations for use in uses]
