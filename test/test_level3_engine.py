"""The Level 3 engines: the same results on 1 and 2 pool workers and on a Dask cluster, a worker
that dies mid-case, and the journal a stopped run resumes from."""

import json
import os
from pathlib import Path

import pytest
from conftest import DATA, ROOT

from allocator_pkg.cli.dp_level3 import Level3Inputs, prepare
from allocator_pkg.cli.level3_engine import Journal, run_search
from allocator_pkg.simulation.level3_case import CaseResult, Criteria, run_case

INPUTS = Level3Inputs(ROOT / "config/dp_vessel.yaml", ROOT / "config/particulars/dp_vessel.yaml",
                      site=DATA / "sites" / "level3_site.yaml", heading_step=90.0,
                      criteria=Criteria(0.05, 3.0, settle=2.0, duration=3.0))
HEADER = {"test": "1"}


@pytest.fixture(scope="module")
def prepared():
    return prepare(INPUTS)


def search_on(prepared, folder: Path, **engine) -> dict:
    return run_search(prepared.search, prepared.setup, Journal(folder / "cases.jsonl", HEADER, False),
                      progress=False, **engine)


@pytest.fixture(scope="module")
def reference(prepared, tmp_path_factory):
    return search_on(prepared, tmp_path_factory.mktemp("one"), workers=1)


@pytest.mark.slow
def test_two_workers_give_the_same_cases_bit_for_bit(prepared, reference, tmp_path):
    assert len(reference) >= 6
    assert search_on(prepared, tmp_path, workers=2) == reference


@pytest.mark.slow
def test_a_dask_cluster_gives_the_same_cases_bit_for_bit(prepared, reference, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp://",
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        assert search_on(prepared, tmp_path, scheduler=cluster.scheduler_address) == reference


def dies_once(case, setup):
    """The case runner, but the worker process dies the first time it meets condition 2 intact at
    0 deg and condition 1 after the loss of switchboard_a at 90 deg."""
    marker = Path(os.environ["L3_DIE_MARKERS"]) / f"{case.heading_deg:g}_{case.group}_{case.number}"
    if case.key[:3] in ((0.0, 2, "intact"), (90.0, 1, "switchboard_a")) and not marker.exists():
        marker.touch()
        os._exit(1)
    return run_case(case, setup)


def test_a_worker_that_dies_mid_case_has_the_case_run_again(prepared, reference, tmp_path, monkeypatch):
    monkeypatch.setenv("L3_DIE_MARKERS", str(tmp_path))
    assert search_on(prepared, tmp_path, workers=2, runner=dies_once) == reference
    assert {path.name for path in tmp_path.glob("*_?")} == {"0_intact_2", "90_switchboard_a_1"}


class Stop(Exception):
    pass


def counting(case, setup):
    """The case runner, leaving a file named after each case it runs."""
    (Path(os.environ["L3_RAN"]) / "_".join(map(str, case.key))).touch()
    return run_case(case, setup)


def test_a_stopped_run_resumes_without_running_a_finished_case(prepared, reference, tmp_path, monkeypatch):
    monkeypatch.setenv("L3_RAN", str(tmp_path))
    path = tmp_path / "cases.jsonl"
    journal = Journal(path, HEADER, False)
    original = journal.append
    counted = []

    def append_then_stop(result):
        stored = original(result)
        counted.append(result)
        if len(counted) == 4:
            raise Stop
        return stored

    journal.append = append_then_stop
    with pytest.raises(Stop):
        run_search(prepared.search, prepared.setup, journal, workers=2, progress=False)
    with path.open("a") as handle:                   # killed in the middle of a line
        handle.write('{"heading_deg": 0.0, "num')
    resumed = Journal(path, HEADER, True)
    assert set(resumed.finished) == {r.case.key for r in counted}
    finished = run_search(prepared.search, prepared.setup, resumed, workers=1, progress=False, runner=counting)
    assert finished == reference
    lines = [json.loads(line) for line in path.read_text().splitlines()]
    assert lines[0] == HEADER and len(lines) == 1 + len(reference)
    ran = {path.name for path in tmp_path.iterdir()} - {"cases.jsonl"}
    assert len(ran) == len(reference) - len(counted)
    assert not ran & {"_".join(map(str, r.case.key)) for r in counted}


def test_resume_refuses_a_journal_of_other_inputs(tmp_path):
    Journal(tmp_path / "cases.jsonl", HEADER, False).close()
    with pytest.raises(ValueError, match="other inputs"):
        Journal(tmp_path / "cases.jsonl", {"test": "2"}, True)


def test_a_result_survives_its_line(reference):
    for result in reference.values():
        assert CaseResult.from_json(json.loads(json.dumps(result.to_json()))) == result
