"""What the seeds of one Level 3 condition say together: per metric (the largest position
excursion and heading deviation of each run, outside and within the post-failure window) the
stated quantile over the seeds (``numpy.quantile`` with the criteria's method, Hyndman and Fan
1996), a percentile-bootstrap confidence interval of that quantile (Efron and Tibshirani 1993,
ch. 13: resample the seeds' values with replacement, take the quantile of each resample, the
interval the (1 - confidence)/2 and (1 + confidence)/2 quantiles of those; a fixed seed, so
every output is reproducible) and the spread (min, median, max).

A condition holds when each metric's quantile is within its limit (:func:`condition_holds`): the
position and heading limits for the run outside the post-failure window, the post-failure limits
within it (a group's cases only). With one seed, or the quantile 1 and method ``higher``, this is
"every seed holds".
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .case import CaseResult, Criteria

METRICS = (("steady_position", "position_limit", "m"), ("steady_heading_deg", "heading_limit_deg", "deg"),
           ("transient_position", "post_failure_position_limit", "m"),
           ("transient_heading_deg", "post_failure_heading_limit_deg", "deg"))
"""(CaseResult field, the criterion limiting it, unit) of every metric a condition is judged on."""


@dataclass(frozen=True)
class Spread:
    """One metric over a condition's seeds: the stated quantile, its bootstrap interval (low,
    high), min, median and max, and the number of seeds."""

    quantile: float
    low: float
    high: float
    minimum: float
    median: float
    maximum: float
    seeds: int


def seed_quantile(values: Sequence[float], criteria: Criteria) -> float:
    """The criteria's quantile of ``values`` by its method."""
    return float(np.quantile(np.asarray(values, dtype=float), criteria.quantile, method=criteria.quantile_method))


def bootstrap_interval(values: Sequence[float], criteria: Criteria) -> tuple[float, float]:
    """The percentile-bootstrap interval at ``criteria.confidence`` of the criteria's quantile of
    ``values``: ``resamples`` resamples of the values with replacement from
    ``numpy.random.default_rng(bootstrap_seed)``, the quantile of each, and the (1 - c)/2 and
    (1 + c)/2 quantiles (linear) of those."""
    data = np.asarray(values, dtype=float)
    rng = np.random.default_rng(criteria.bootstrap_seed)
    draws = data[rng.integers(0, data.size, size=(criteria.resamples, data.size))]
    estimates = np.quantile(draws, criteria.quantile, axis=1, method=criteria.quantile_method)
    tail = 0.5 * (1.0 - criteria.confidence)
    low, high = np.quantile(estimates, (tail, 1.0 - tail))
    return float(low), float(high)


def spread(values: Sequence[float], criteria: Criteria) -> Spread:
    """:class:`Spread` of ``values`` under ``criteria``."""
    data = np.asarray(values, dtype=float)
    return Spread(seed_quantile(data, criteria), *bootstrap_interval(data, criteria), float(np.min(data)),
                  float(np.median(data)), float(np.max(data)), int(data.size))


def metric_values(results: Sequence[CaseResult], metric: str) -> list[float] | None:
    """The values of ``metric`` over ``results``; None when no run has it (an intact case's
    post-failure metrics); ValueError when some runs have it and others not (the seeds of one
    condition share its case and post-failure window)."""
    values = [getattr(result, metric) for result in results]
    missing = sum(value is None for value in values)
    if missing == len(values):
        return None
    if missing:
        raise ValueError(f"{metric}: {missing} of {len(values)} runs lack it; the seeds of one condition "
                         "either all have it or none does")
    return [float(v) for v in values]


def condition_holds(results: Sequence[CaseResult], criteria: Criteria) -> bool:
    """Whether a condition holds on its seeds' ``results``: every metric's quantile within its
    limit (:data:`METRICS`; a metric no run has is not judged)."""
    for metric, limit, _ in METRICS:
        values = metric_values(results, metric)
        if values is not None and seed_quantile(values, criteria) > getattr(criteria, limit):
            return False
    return True


def condition_spreads(results: Sequence[CaseResult], criteria: Criteria) -> dict[str, Spread | None]:
    """Per metric of :data:`METRICS`, its :class:`Spread` over ``results`` (None: not judged)."""
    spreads = {}
    for metric, _, _ in METRICS:
        values = metric_values(results, metric)
        spreads[metric] = None if values is None else spread(values, criteria)
    return spreads
