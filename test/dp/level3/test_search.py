"""The rising search of [2.4.4] over Level 3 cases, on made-up results."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from allocator_pkg.dp.level3.case import Case, CaseResult, Criteria
from allocator_pkg.dp.level3.search import FAILED, STATIC, TOP, ChainOutcome, Level3Search

ONE = Criteria(1.0, seeds=1)
ALL = Criteria(1.0, seeds=3, quantile=1.0)
"""One seed; three that must all hold (the largest excursion decides)."""


def result(heading, number, case, seed, held) -> CaseResult:
    """A run 0.5 m off when it holds and 2 m when not (position limit 1 m)."""
    excursion = 0.5 if held else 2.0
    return CaseResult(Case(heading, number, case, seed), excursion, 0.3, 0.1, held, (), excursion, 0.1, None, None)


def run(search: Level3Search, holds) -> dict:
    """Finish what the search asks, batch by batch, with ``holds(case)``."""
    finished = {}
    while not search.done(finished):
        batch = search.pending(finished)
        assert batch
        for case in batch:
            finished[case.key] = result(*case.key, holds(case))
    return finished


def test_numbers_stop_at_the_first_failing_condition_and_never_look_above():
    search = Level3Search((0.0, 90.0), ("intact", "g"), ONE, {(0.0, "intact"): 11, (90.0, "intact"): 9,
                                                              (0.0, "g"): 5, (90.0, "g"): 6}, 11)
    fails_at = {(0.0, "intact"): 99, (90.0, "intact"): 4, (0.0, "g"): 99, (90.0, "g"): 2}
    finished = run(search, lambda c: c.number < fails_at[(c.heading_deg, c.group)])
    outcomes = {chain: search.outcome(chain, finished) for chain in search.chains()}
    assert {chain: (o.number, o.reason) for chain, o in outcomes.items()} == {
        (0.0, "intact"): (11, TOP), (90.0, "intact"): (3, FAILED), (0.0, "g"): (5, STATIC), (90.0, "g"): (1, FAILED)}
    assert sorted(k[1] for k in finished if k[:1] == (90.0,) and k[2] == "intact") == [1, 2, 3, 4]
    assert max(k[1] for k in finished if k[0] == 0.0 and k[2] == "g") == 5      # above the static ceiling: never


def test_every_seed_must_hold_and_the_next_condition_waits_for_them_all():
    search = Level3Search((0.0,), ("intact",), ALL, {(0.0, "intact"): 11}, 11)
    first = search.pending({})
    assert [c.key for c in first] == [(0.0, 1, "intact", s) for s in range(3)]
    partial = {first[0].key: result(*first[0].key, True)}
    assert [c.seed for c in search.pending(partial)] == [1, 2]      # condition 2 waits for seeds 1 and 2
    finished = run(search, lambda c: not (c.number == 3 and c.seed == 2))
    assert search.outcome((0.0, "intact"), finished).number == 2
    assert {k[1] for k in finished} == {1, 2, 3}


def test_a_vessel_the_static_balance_fails_at_one_runs_nothing():
    search = Level3Search((0.0,), ("intact",), ONE, {(0.0, "intact"): 0}, 11)
    assert search.pending({}) == [] and search.done({})
    assert search.outcome((0.0, "intact"), {}).number == 0


def excursion_run(key, table) -> CaseResult:
    """A run whose largest excursion is ``table[number][seed]`` [m]."""
    heading, number, case, seed = key
    value = table[number - 1][seed]
    return CaseResult(Case(heading, number, case, seed), value, 0.0, 0.0, value <= 1.0, (), value, 0.0, None, None)


EXCURSIONS = st.lists(st.lists(st.floats(0.0, 2.0), min_size=6, max_size=6), min_size=11, max_size=11)


@given(EXCURSIONS, st.integers(1, 5), st.sampled_from([0.5, 0.9, 1.0]))
def test_each_run_is_asked_once_and_the_number_is_below_the_first_quantile_over_the_limit(table, seeds, q):
    criteria = Criteria(1.0, seeds=seeds, quantile=q)
    search = Level3Search((0.0,), ("intact",), criteria, {(0.0, "intact"): 11}, 11)
    finished, asked = {}, []
    while not search.done(finished):
        batch = search.pending(finished)
        asked += [case.key for case in batch]
        finished.update((case.key, excursion_run(case.key, table)) for case in batch)
    quantiles = [float(np.quantile(row[:seeds], q)) for row in table]
    expected = next((n for n, value in enumerate(quantiles) if value > 1.0), 11)
    assert search.outcome((0.0, "intact"), finished).number == expected
    assert len(asked) == len(set(asked)) == seeds * min(expected + 1, 11)


def test_more_seeds_run_only_the_seeds_not_yet_run():
    """A search of 5 seeds given the runs of one of 3: conditions 1 and 2 run seeds 3 and 4 only."""
    table = [[0.5] * 6] * 11
    three = Level3Search((0.0,), ("intact",), Criteria(1.0, seeds=3), {(0.0, "intact"): 2}, 11)
    finished = {}
    while not three.done(finished):
        finished.update((c.key, excursion_run(c.key, table)) for c in three.pending(finished))
    assert len(finished) == 6
    five = Level3Search((0.0,), ("intact",), Criteria(1.0, seeds=5), {(0.0, "intact"): 2}, 11)
    asked = []
    while not five.done(finished):
        batch = five.pending(finished)
        asked += [c.key for c in batch]
        finished.update((c.key, excursion_run(c.key, table)) for c in batch)
    assert sorted(asked) == [(0.0, n, "intact", s) for n in (1, 2) for s in (3, 4)]


def test_a_verdict_is_kept_for_the_same_runs_and_taken_again_for_others():
    search = Level3Search((0.0,), ("intact",), Criteria(1.0, seeds=2, quantile=1.0), {(0.0, "intact"): 1}, 11)
    good = {(0.0, 1, "intact", s): result(0.0, 1, "intact", s, True) for s in range(2)}
    bad = {**good, (0.0, 1, "intact", 1): result(0.0, 1, "intact", 1, False)}
    assert search.outcome((0.0, "intact"), good) == ChainOutcome(1, STATIC, True)
    assert search.outcome((0.0, "intact"), bad) == ChainOutcome(0, FAILED, True)
    assert search.outcome((0.0, "intact"), good) == ChainOutcome(1, STATIC, True)
