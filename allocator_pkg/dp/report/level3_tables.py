"""The CSV tables of a DNV-ST-0111 Level 3 study: why each number stops where it does
(``_limits.csv``), every run (``_cases.csv``) and every condition's statistics over its seeds
(``_quantiles.csv``: per metric the stated quantile, its bootstrap interval and the spread)."""

from __future__ import annotations

from collections.abc import Mapping

from ..level3.case import CaseResult
from ..level3.statistics import METRICS, condition_holds, condition_spreads
from ..level3.study import Level3Study

CASE_COLUMNS = ("case", "heading_deg", "capability_number", "seed", "wind_speed", "hs", "tp", "current",
                "max_position_m", "mean_position_m", "max_heading_deg", "steady_position_m", "steady_heading_deg",
                "transient_position_m", "transient_heading_deg", "held")
LIMIT_COLUMNS = ("case", "heading_deg", "capability_number", "limited_by")
SPREAD_COLUMNS = ("quantile", "ci_low", "ci_high", "min", "median", "max")
QUANTILE_COLUMNS = ("case", "heading_deg", "capability_number", "seeds",
                    *(f"{metric.replace('_deg', '')}_{column}" for metric, _, _ in METRICS
                      for column in SPREAD_COLUMNS),
                    "held")
CASES_TABLE = ("Level 3 runs: the condition (number; wind [m/s], Hs [m], Tp [s], current [m/s]) from the heading, "
               "intact or the group failed after settling; position excursion from the set-point [m] (max, mean), "
               "heading deviation [deg] (max); the largest of each outside (steady) and within (transient) the "
               "post-failure window; whether the run alone kept within the limits")
LIMITS_TABLE = ("Level 3 per case and heading: the capability number and what limits it (failed: the next "
                "condition failed in the time domain; static Level 2: the static balance fails the next one, not "
                "simulated; top condition)")
QUANTILES_TABLE = ("Level 3 per condition simulated: over its seeds, per metric (position [m] and heading [deg], "
                   "outside (steady) and within (transient) the post-failure window) the stated quantile, its "
                   "percentile-bootstrap interval and min, median, max; held: every quantile within its limit")


def limit_rows(prepared: Level3Study, finished: Mapping[tuple, CaseResult]) -> list[tuple]:
    search = prepared.search
    return [(case, heading, outcome.number, outcome.reason) for heading, case in search.chains()
            for outcome in (search.outcome((heading, case), finished),)]


def _order(prepared: Level3Study):
    order = {case: k for k, case in enumerate(prepared.search.cases)}
    return lambda key: (order[key[2]], key[0], key[1], key[3])


def case_rows(prepared: Level3Study, finished: Mapping[tuple, CaseResult]) -> list[tuple]:
    """One row per run, in the order of the search's chains, then number and seed."""
    rows = []
    for key in sorted(finished, key=_order(prepared)):
        result, condition = finished[key], prepared.setup.conditions[key[1]]
        rows.append((key[2], key[0], key[1], key[3], condition.wind, condition.hs, condition.tp, condition.current,
                     result.max_position, result.mean_position, result.max_heading_deg, result.steady_position,
                     result.steady_heading_deg, _blank(result.transient_position),
                     _blank(result.transient_heading_deg), result.held))
    return rows


def quantile_rows(prepared: Level3Study, finished: Mapping[tuple, CaseResult]) -> list[tuple]:
    """One row per condition whose seeds have all run, in the order of :func:`case_rows`."""
    search, criteria = prepared.search, prepared.setup.criteria
    conditions = sorted({key[:3] for key in finished}, key=lambda k: _order(prepared)((*k, 0)))
    rows = []
    for heading, number, case in conditions:
        results = search.seed_results((heading, case), number, finished)
        if results is None:
            continue
        cells = []
        for spread in condition_spreads(results, criteria).values():
            cells += ([""] * len(SPREAD_COLUMNS) if spread is None else
                      [spread.quantile, spread.low, spread.high, spread.minimum, spread.median, spread.maximum])
        rows.append((case, heading, number, len(results), *cells, condition_holds(results, criteria)))
    return rows


def _blank(value: float | None) -> float | str:
    return "" if value is None else value
