"""Running the Level 3 cases: a local process pool (``--workers N``) or a Dask distributed
cluster (``--scheduler ADDRESS``; ``dask[distributed]``, the ``cluster`` extra, imported only
then), the rising search of :class:`~allocator_pkg.dp.level3.search.Level3Search`
deciding what runs next, a tqdm progress bar, and the journal (:mod:`.journal`, ``cases.jsonl``)
that takes every finished case as it completes, so that a run stopped at any moment resumes
(``--resume``) without running a finished case again.

Each case is a pure function of its inputs (the seed among them), so the results are the same
bit for bit on any number of workers and on either engine. A pool worker that dies mid-case
breaks the pool: a new one runs every case that had not come back (at most
:data:`MAX_ATTEMPTS` times each); Dask retries a case whose worker died by itself.
"""

from __future__ import annotations

import concurrent.futures
import os
import pickle
import sys
from collections.abc import Callable
from concurrent.futures.process import BrokenProcessPool
from typing import Any

from .case import Case, CaseResult, CaseSetup, run_case
from .journal import Journal
from .search import Level3Search

MAX_ATTEMPTS = 3
"""Times a pool case runs before the run gives up (a worker died under it each time)."""
DASK_RETRIES = 2
Runner = Callable[[Case, CaseSetup], CaseResult]


class PoolEngine:
    """A local process pool of ``workers``; a broken pool is replaced and its cases run again."""

    def __init__(self, workers: int, runner: Runner, setup: CaseSetup) -> None:
        try:
            pickle.dumps((runner, setup))
        except (pickle.PicklingError, AttributeError, TypeError) as error:
            raise ValueError(f"the case runner and set-up go to worker processes by pickle: {error}") from error
        self.workers, self.runner, self.setup = workers, runner, setup
        self.pool = concurrent.futures.ProcessPoolExecutor(workers)
        self.running: dict[concurrent.futures.Future, Case] = {}
        self.attempts: dict[tuple, int] = {}

    def submit(self, case: Case) -> None:
        attempts = self.attempts[case.key] = self.attempts.get(case.key, 0) + 1
        if attempts > MAX_ATTEMPTS:
            raise RuntimeError(f"case {case}: its worker died {MAX_ATTEMPTS} times")
        try:
            self.running[self.pool.submit(self.runner, case, self.setup)] = case
        except BrokenProcessPool:
            self.attempts[case.key] -= 1
            self._restart([case])

    def wait(self) -> list[CaseResult]:
        done, _ = concurrent.futures.wait(self.running, return_when=concurrent.futures.FIRST_COMPLETED)
        results, lost = [], []
        for future in done:
            case = self.running.pop(future)
            try:
                results.append(future.result())
            except BrokenProcessPool:
                lost.append(case)
        if lost:
            self._restart(lost)
        return results

    def _restart(self, lost: list[Case]) -> None:
        """A new pool running ``lost`` and every case that had not come back."""
        lost = [*lost, *self.running.values()]
        self.pool.shutdown(wait=False, cancel_futures=True)
        self.pool = concurrent.futures.ProcessPoolExecutor(self.workers)
        self.running = {}
        for case in lost:
            self.submit(case)

    def close(self) -> None:
        self.pool.shutdown(wait=True, cancel_futures=True)


class DaskEngine:
    """The cases on a Dask distributed cluster at ``address`` (retried when a worker dies)."""

    def __init__(self, address: str, runner: Runner, setup: CaseSetup) -> None:
        try:
            from dask.distributed import Client, as_completed
        except ImportError as error:
            raise ValueError("--scheduler needs dask[distributed] (pip install allocator_pkg[tools,cluster])") \
                from error
        self.client = Client(address)
        self.runner, self.setup = runner, setup
        self.setup_future = self.client.scatter(setup, broadcast=True)
        self.running: dict[Any, Case] = {}
        self.completed = as_completed([])

    @property
    def workers(self) -> int:
        return max(1, len(self.client.scheduler_info().get("workers", {})))

    def submit(self, case: Case) -> None:
        future = self.client.submit(self.runner, case, self.setup_future, pure=False, retries=DASK_RETRIES,
                                    key=f"level3-{case.heading_deg:g}-{case.number}-{case.group}-{case.seed}-"
                                        f"{os.getpid()}-{id(self)}")
        self.running[future] = case
        self.completed.add(future)

    def wait(self) -> list[CaseResult]:
        results = []
        for future in [next(self.completed), *self.completed.next_batch(block=False)]:
            self.running.pop(future)
            results.append(future.result())
        return results

    def close(self) -> None:
        self.client.close()


def run_search(search: Level3Search, setup: CaseSetup, journal: Journal, workers: int | None = None,
               scheduler: str | None = None, runner: Runner = run_case,
               progress: bool = True) -> dict[tuple, CaseResult]:
    """Every case the search needs, on the engine chosen; each finished one into ``journal``.
    The finished results by :attr:`Case.key`."""
    from tqdm import tqdm

    finished = journal.finished
    engine = (DaskEngine(scheduler, runner, setup) if scheduler else
              PoolEngine(workers or os.cpu_count() or 1, runner, setup))
    bar = tqdm(total=_bound(search, finished), initial=len(finished), unit="case", disable=not progress,
               file=sys.stderr, desc="Level 3")
    try:
        while True:
            running = {case.key for case in engine.running.values()}
            queue = [case for case in search.pending(finished) if case.key not in running]
            room = 2 * engine.workers - len(running)
            for case in queue[:max(room, 0)]:
                engine.submit(case)
            if not engine.running:
                break
            for result in engine.wait():
                journal.append(result)
                bar.update(1)
            bar.total = _bound(search, finished)
            bar.refresh()
    finally:
        bar.close()
        engine.close()
        journal.close()
    return finished


def _bound(search: Level3Search, finished: dict[tuple, CaseResult]) -> int:
    """The most cases the run can take: those finished and every condition up to each undecided
    chain's ceiling (the bar's total, shrinking as chains decide)."""
    left = 0
    for chain in search.chains():
        outcome = search.outcome(chain, finished)
        if not outcome.decided:
            heading, group = chain
            left += sum((heading, number, group, seed) not in finished for seed in range(search.seeds)
                        for number in range(outcome.number + 1, search.ceilings[chain] + 1))
    return len(finished) + left
