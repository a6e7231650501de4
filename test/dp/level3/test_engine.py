"""The Level 3 engines: the same results and journal on 1 and 2 pool workers and on a Dask
cluster (two seeds a condition), a worker that dies mid-case, pool workers that end with their parent, a scheduler that
does not answer, and the journal a stopped run resumes from."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import DATA, ROOT

from allocator_pkg.dp.level3 import engine as level3_engine
from allocator_pkg.dp.level3.case import Case, CaseResult, Criteria, run_case
from allocator_pkg.dp.level3.engine import DaskEngine, PoolEngine, open_engine, run_search
from allocator_pkg.dp.level3.journal import Journal
from allocator_pkg.dp.level3.study import Level3Inputs, prepare

INPUTS = Level3Inputs(ROOT / "config/dp_vessel.yaml", ROOT / "config/particulars/dp_vessel.yaml",
                      site=DATA / "sites" / "level3_site.yaml", heading_step=90.0,
                      criteria=Criteria(0.05, 3.0, settle=2.0, duration=3.0, seeds=2, quantile=0.5))
HEADER = {"test": "1"}


@pytest.fixture(scope="module")
def prepared():
    return prepare(INPUTS)


def search_on(prepared, folder: Path, runner=run_case, **engine) -> dict:
    with open_engine(**engine) as opened:
        return run_search(prepared.search, prepared.setup, Journal(folder / "cases.jsonl", HEADER, False), opened,
                          runner, progress=False)


@pytest.fixture(scope="module")
def reference_folder(tmp_path_factory):
    return tmp_path_factory.mktemp("one")


@pytest.fixture(scope="module")
def reference(prepared, reference_folder):
    return search_on(prepared, reference_folder, workers=1)


@pytest.mark.slow
def test_two_workers_give_the_same_cases_and_journal_bit_for_bit(prepared, reference, reference_folder, tmp_path):
    assert len(reference) >= 6
    assert search_on(prepared, tmp_path, workers=2) == reference
    journal = (tmp_path / "cases.jsonl").read_bytes()
    assert journal == (reference_folder / "cases.jsonl").read_bytes()


@pytest.mark.slow
def test_a_dask_cluster_gives_the_same_cases_and_journal_bit_for_bit(prepared, reference, reference_folder,
                                                                     tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp://",
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        assert search_on(prepared, tmp_path, scheduler=cluster.scheduler_address) == reference
    assert (tmp_path / "cases.jsonl").read_bytes() == (reference_folder / "cases.jsonl").read_bytes()


def test_the_finished_journal_is_in_case_order(reference, reference_folder):
    lines = (reference_folder / "cases.jsonl").read_text().splitlines()
    keys = [CaseResult.from_json(json.loads(line)).case.key for line in lines[1:]]
    assert keys == sorted(reference)


def test_a_scheduler_that_does_not_answer_is_refused(monkeypatch):
    pytest.importorskip("dask.distributed")
    monkeypatch.setattr(level3_engine, "CONNECT_TIMEOUT", 1.0)
    with pytest.raises(ValueError, match=r"--scheduler tcp://127.0.0.1:9: no Dask scheduler answers there within 1 s"):
        DaskEngine("tcp://127.0.0.1:9")


SLEEPER = """
import os, sys, time
from pathlib import Path
from allocator_pkg.dp.level3.engine import PoolEngine
from allocator_pkg.dp.level3.case import Case


def sleeper(case, setup):
    Path(sys.argv[1], str(os.getpid())).touch()
    time.sleep(600)


if __name__ == "__main__":
    with PoolEngine(2) as engine:
        engine.start(sleeper, None)
        engine.submit(Case(0.0, 1, "intact", 0))
        engine.submit(Case(0.0, 1, "intact", 1))
        engine.wait()
"""
"""A parent that runs a pool of two workers sleeping in their cases (a file, as spawned workers
import their parent's main module to find ``sleeper``)."""


def alive(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie, ended but not yet reaped, does not)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except (FileNotFoundError, ProcessLookupError):
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_pool_workers_end_when_their_parent_is_killed(tmp_path):
    script, markers = tmp_path / "parent.py", tmp_path / "workers"
    script.write_text(SLEEPER)
    markers.mkdir()
    parent = subprocess.Popen([sys.executable, str(script), str(markers)], start_new_session=True,
                              env={**os.environ, "PYTHONPATH": str(ROOT)})
    workers: list[int] = []
    try:
        deadline = time.monotonic() + 60.0
        while len(workers) < 2 and time.monotonic() < deadline and parent.poll() is None:
            workers = [int(path.name) for path in markers.iterdir()]
            time.sleep(0.05)
        assert len(workers) == 2 and all(map(alive, workers))
        parent.kill()                                  # SIGKILL, the parent only
        parent.wait()
        deadline = time.monotonic() + 10.0
        while any(map(alive, workers)) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not any(map(alive, workers))
    finally:
        for pid in filter(alive, workers):
            os.kill(pid, signal.SIGKILL)
        if parent.poll() is None:
            parent.kill()


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
    assert search_on(prepared, tmp_path, dies_once, workers=2) == reference
    assert {path.name for path in tmp_path.glob("*_?")} == {"0_intact_2", "90_switchboard_a_1"}


class Stop(Exception):
    pass


def sleeps(case, setup):
    """A case runner that takes 30 s, leaving a file as it starts and another as it ends."""
    folder = Path(os.environ["L3_SLEEPS"])
    (folder / f"{os.getpid()}.started").touch()
    time.sleep(30.0)
    (folder / f"{os.getpid()}.finished").touch()


def test_a_pool_stopped_by_an_exception_kills_its_cases_in_flight(tmp_path, monkeypatch):
    monkeypatch.setenv("L3_SLEEPS", str(tmp_path))
    with pytest.raises(Stop), PoolEngine(2) as engine:
        engine.start(sleeps, None)
        engine.submit(Case(0.0, 1, "intact", 0))
        engine.submit(Case(0.0, 1, "intact", 1))
        deadline = time.monotonic() + 60.0
        while len(list(tmp_path.glob("*.started"))) < 2 and time.monotonic() < deadline:
            time.sleep(0.05)
        raise Stop
    workers = [int(path.stem) for path in tmp_path.glob("*.started")]
    assert len(workers) == 2 and not any(map(alive, workers))
    assert not list(tmp_path.glob("*.finished"))          # killed, not waited for


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
    with pytest.raises(Stop), open_engine(workers=2) as engine:
        run_search(prepared.search, prepared.setup, journal, engine, progress=False)
    with path.open("a") as handle:                   # killed in the middle of a line
        handle.write('{"heading_deg": 0.0, "num')
    resumed = Journal(path, HEADER, True)
    assert set(resumed.finished) == {r.case.key for r in counted}
    with open_engine(workers=1) as engine:
        finished = run_search(prepared.search, prepared.setup, resumed, engine, counting, progress=False)
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


def test_a_journal_of_fewer_seeds_resumes_running_only_the_seeds_it_lacks(prepared, reference, tmp_path, monkeypatch):
    """The journal's header leaves out the seeds and the quantile: a journal of the one-seed search
    resumes under two seeds, its runs kept, and the second seed's runs are the only ones run."""
    from dataclasses import replace

    one_seed = replace(INPUTS, criteria=replace(INPUTS.criteria, seeds=1, quantile=0.9))
    assert one_seed.fingerprint() == INPUTS.fingerprint()
    assert replace(INPUTS, criteria=replace(INPUTS.criteria, settle=3.0)).fingerprint() != INPUTS.fingerprint()
    first = prepare(one_seed)
    path = tmp_path / "journal" / "cases.jsonl"
    with open_engine(workers=1) as engine:
        single = run_search(first.search, first.setup, Journal(path, INPUTS.fingerprint(), False), engine,
                            progress=False)
    assert {key[3] for key in single} == {0}
    monkeypatch.setenv("L3_RAN", str(tmp_path))
    with open_engine(workers=1) as engine:
        finished = run_search(prepared.search, prepared.setup, Journal(path, INPUTS.fingerprint(), True), engine,
                              counting, progress=False)
    ran = {path.name for path in tmp_path.iterdir()} - {"journal"}
    assert {key: finished[key] for key in reference} == reference
    assert ran == {"_".join(map(str, key)) for key in set(reference) - set(single)}
    assert ran and ran.isdisjoint("_".join(map(str, key)) for key in single)
