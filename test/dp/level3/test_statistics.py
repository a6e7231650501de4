"""A condition's statistics over its seeds: the quantile against the Hyndman and Fan definitions
written out here, the percentile bootstrap against its exact distribution (an order statistic of
a resample is binomial) and against scipy.stats.bootstrap, and the decision rule on constructed
runs."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy import stats

from allocator_pkg.dp.level3.case import Case, CaseResult, Criteria
from allocator_pkg.dp.level3.statistics import (
    bootstrap_interval,
    condition_holds,
    condition_spreads,
    metric_values,
    seed_quantile,
    spread,
)

VALUES = st.lists(st.floats(0.0, 100.0, allow_nan=False), min_size=1, max_size=25)
QUANTILES = st.floats(0.01, 1.0)


def written_out(values, q: float, method: str) -> float:
    """Hyndman and Fan (1996) on the sorted values x[0..n-1]: type 7 (linear) interpolates at
    h = (n - 1) q; ``higher`` takes x[ceil((n - 1) q)]; type 1 (inverted_cdf) x[ceil(n q) - 1]."""
    x, n = sorted(values), len(values)
    if method == "linear":
        h = (n - 1) * q
        low = math.floor(h)
        return x[low] + (h - low) * (x[min(low + 1, n - 1)] - x[low])
    if method == "higher":
        return x[math.ceil((n - 1) * q - 1e-12)]
    return x[max(math.ceil(n * q - 1e-12) - 1, 0)]


@given(VALUES, QUANTILES, st.sampled_from(["linear", "higher", "inverted_cdf"]))
def test_the_quantile_is_hyndman_and_fans(values, q, method):
    assert seed_quantile(values, Criteria(quantile=q, quantile_method=method)) == pytest.approx(
        written_out(values, q, method), rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("n, q, confidence", [(10, 0.9, 0.8), (12, 0.75, 0.9), (20, 0.9, 0.9), (5, 0.8, 0.9),
                                              (9, 0.5, 0.8), (11, 0.8, 0.8)])
def test_the_bootstrap_interval_is_the_exact_bootstrap_distributions(n, q, confidence):
    """Distinct values x_(1) < ... < x_(n) and the type-1 quantile: a resample's quantile is its
    k-th order statistic, k = ceil(n q), so P(T* <= x_(j)) = P(Binomial(n, j / n) >= k) exactly;
    the interval's ends are the (1 -+ c)/2 quantiles of that distribution."""
    values = np.linspace(1.0, 3.0, n) ** 2
    k = math.ceil(n * q - 1e-12)
    cdf = np.array([stats.binom.sf(k - 1, n, j / n) for j in range(1, n + 1)])
    tail = 0.5 * (1.0 - confidence)
    expected = []
    for level in (tail, 1.0 - tail):
        assert np.min(np.abs(cdf - level)) > 0.01, "a level at a step of the CDF: the test cannot tell"
        expected.append(values[int(np.argmax(cdf >= level))])
    interval = bootstrap_interval(values, Criteria(quantile=q, quantile_method="inverted_cdf",
                                                   confidence=confidence, resamples=20000))
    assert interval == pytest.approx(tuple(expected), rel=1e-12)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_bootstrap_interval_agrees_with_scipys(seed):
    rng = np.random.default_rng(100 + seed)
    values = rng.gumbel(4.0, 1.0, 40)
    criteria = Criteria(quantile=0.9, confidence=0.9, resamples=20000, bootstrap_seed=seed)
    theirs = stats.bootstrap((values,), lambda x, axis: np.quantile(x, 0.9, axis=axis), confidence_level=0.9,
                             n_resamples=20000, method="percentile", random_state=np.random.default_rng(seed + 7))
    ours = bootstrap_interval(values, criteria)
    gap = np.max(np.diff(np.sort(values))[-8:])                # the order statistics the ends fall between
    assert ours[0] == pytest.approx(theirs.confidence_interval.low, abs=gap)
    assert ours[1] == pytest.approx(theirs.confidence_interval.high, abs=gap)


@given(VALUES)
def test_the_spread_is_reproducible_and_brackets_the_quantile(values):
    criteria = Criteria(resamples=200)
    first, second = spread(values, criteria), spread(values, criteria)
    assert first == second
    assert first.minimum <= first.low <= first.high <= first.maximum
    assert first.minimum <= first.quantile <= first.maximum and first.seeds == len(values)
    assert first.median == pytest.approx(float(np.median(values)))


RUNS = st.lists(st.tuples(st.floats(0.0, 20.0), st.floats(0.0, 10.0), st.floats(0.0, 20.0), st.floats(0.0, 10.0)),
                min_size=1, max_size=12)


def runs(rows, group="g") -> list[CaseResult]:
    transient = group != "intact"
    return [CaseResult(Case(0.0, 3, group, seed), max(p, t if transient else 0.0), 0.0, max(h, d), True, (), p, h,
                       t if transient else None, d if transient else None)
            for seed, (p, h, t, d) in enumerate(rows)]


@given(RUNS, QUANTILES, st.sampled_from(["linear", "higher", "inverted_cdf"]), st.sampled_from(["intact", "g"]),
       st.tuples(*[st.floats(0.5, 15.0)] * 4))
def test_a_condition_holds_when_every_quantile_is_within_its_limit(rows, q, method, group, limits):
    criteria = Criteria(limits[0], limits[1], quantile=q, quantile_method=method, post_failure_position_limit=limits[2],
                        post_failure_heading_limit_deg=limits[3])
    columns = list(zip(*rows))
    judged = range(4) if group != "intact" else range(2)
    expected = all(written_out(columns[m], q, method) <= limits[m] + 1e-9 for m in judged)
    near = any(abs(written_out(columns[m], q, method) - limits[m]) < 1e-6 for m in judged)
    if not near:
        assert condition_holds(runs(rows, group), criteria) == expected
    spreads = condition_spreads(runs(rows, group), criteria)
    assert (spreads["transient_position"] is None) == (group == "intact")


@given(RUNS, st.sampled_from(["intact", "g"]))
def test_the_top_quantile_by_the_higher_method_is_every_seed_holds(rows, group):
    criteria = Criteria(5.0, 3.0, quantile=1.0, quantile_method="higher", post_failure_position_limit=8.0,
                        post_failure_heading_limit_deg=4.0)
    every = all(p <= 5.0 and h <= 3.0 and (group == "intact" or (t <= 8.0 and d <= 4.0)) for p, h, t, d in rows)
    assert condition_holds(runs(rows, group), criteria) == every


def test_a_metric_some_runs_lack_is_refused():
    mixed = runs([(1.0, 1.0, 2.0, 2.0)]) + runs([(1.0, 1.0, 2.0, 2.0)], "intact")
    assert metric_values(mixed, "steady_position") == [1.0, 1.0]
    assert metric_values(runs([(1.0, 1.0, 2.0, 2.0)], "intact"), "transient_position") is None
    with pytest.raises(ValueError, match="transient_position: 1 of 2 runs lack it"):
        metric_values(mixed, "transient_position")
