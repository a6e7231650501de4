"""The rising search of [2.4.4] over Level 3 cases, on made-up results."""

from allocator_pkg.dp.level3.case import Case, CaseResult
from allocator_pkg.dp.level3.search import FAILED, STATIC, TOP, Level3Search


def result(heading, number, case, seed, held) -> CaseResult:
    return CaseResult(Case(heading, number, case, seed), 1.0, 0.5, 0.1, held, ())


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
    search = Level3Search((0.0, 90.0), ("intact", "g"), 1, {(0.0, "intact"): 11, (90.0, "intact"): 9,
                                                              (0.0, "g"): 5, (90.0, "g"): 6}, 11)
    fails_at = {(0.0, "intact"): 99, (90.0, "intact"): 4, (0.0, "g"): 99, (90.0, "g"): 2}
    finished = run(search, lambda c: c.number < fails_at[(c.heading_deg, c.group)])
    outcomes = {chain: search.outcome(chain, finished) for chain in search.chains()}
    assert {chain: (o.number, o.reason) for chain, o in outcomes.items()} == {
        (0.0, "intact"): (11, TOP), (90.0, "intact"): (3, FAILED), (0.0, "g"): (5, STATIC), (90.0, "g"): (1, FAILED)}
    assert sorted(k[1] for k in finished if k[:1] == (90.0,) and k[2] == "intact") == [1, 2, 3, 4]
    assert max(k[1] for k in finished if k[0] == 0.0 and k[2] == "g") == 5      # above the static ceiling: never


def test_every_seed_must_hold_and_the_next_condition_waits_for_them_all():
    search = Level3Search((0.0,), ("intact",), 3, {(0.0, "intact"): 11}, 11)
    first = search.pending({})
    assert [c.key for c in first] == [(0.0, 1, "intact", s) for s in range(3)]
    partial = {first[0].key: result(*first[0].key, True)}
    assert [c.seed for c in search.pending(partial)] == [1, 2]      # condition 2 waits for seeds 1 and 2
    finished = run(search, lambda c: not (c.number == 3 and c.seed == 2))
    assert search.outcome((0.0, "intact"), finished).number == 2
    assert {k[1] for k in finished} == {1, 2, 3}


def test_a_vessel_the_static_balance_fails_at_one_runs_nothing():
    search = Level3Search((0.0,), ("intact",), 1, {(0.0, "intact"): 0}, 11)
    assert search.pending({}) == [] and search.done({})
    assert search.outcome((0.0, "intact"), {}).number == 0
