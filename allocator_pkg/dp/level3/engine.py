"""Running the Level 3 cases: a local process pool (``--workers N``) or a Dask distributed
cluster (``--scheduler ADDRESS``; ``dask[distributed]``, the ``cluster`` extra, imported only
then), the rising search of :class:`~allocator_pkg.dp.level3.search.Level3Search`
deciding what runs next, a tqdm progress bar, and the journal (:mod:`.journal`, ``cases.jsonl``)
that takes every finished case as it completes, so that a run stopped at any moment resumes
(``--resume``) without running a finished case again.

Each case is a pure function of its inputs (the seed among them), so the results are the same
bit for bit on any number of workers and on either engine; a finished run rewrites the journal
in case order, so that it too is the same. A pool worker that dies mid-case breaks the pool: a
new one runs every case that had not come back (at most :data:`MAX_ATTEMPTS` times each); Dask
runs a case whose worker died on another (up to its ``distributed.scheduler.allowed-failures``).

The engine is opened (:func:`open_engine`: a scheduler that does not answer is an error) before
the journal is touched. Pool workers end with the process that made the pool however it ends,
SIGKILL included, and leave SIGINT to it: an interrupted run stops its cases and raises
:class:`Interrupted`.
"""

from __future__ import annotations

import abc
import concurrent.futures
import ctypes
import multiprocessing
import os
import pickle
import signal
import sys
import threading
import time
from collections.abc import Callable
from concurrent.futures.process import BrokenProcessPool
from typing import Any

from .case import Case, CaseResult, CaseSetup, run_case
from .journal import Journal
from .search import Level3Search

MAX_ATTEMPTS = 3
"""Times a pool case runs before the run gives up (a worker died under it each time)."""
DASK_RETRIES = 2
"""Times Dask runs a case again that raised an exception (a dead worker counts against the
scheduler's ``allowed-failures`` instead)."""
CONNECT_TIMEOUT = 10.0
"""Seconds a Dask scheduler has to answer before ``--scheduler`` is refused."""
PR_SET_PDEATHSIG = 1
"""prctl(2): the signal a process gets when its parent ends (Linux)."""
Runner = Callable[[Case, CaseSetup], CaseResult]


class CaseLost(RuntimeError):
    """A case the engine could not finish: its workers kept dying (or, on Dask, it kept raising)."""


class Interrupted(Exception):
    """A run stopped by SIGINT after ``done`` of at most ``total`` cases (each finished one in
    the journal); ``total`` None: before the cases started."""

    def __init__(self, done: int, total: int | None) -> None:
        where = f"after {done} of {total} cases" if total is not None else "before the cases started"
        super().__init__(f"interrupted {where}; rerun with --resume")
        self.done, self.total = done, total


def _follow_parent(parent: int) -> None:
    """A pool worker's start: it ends when ``parent`` (the process that made the pool) ends, however
    that ends (Linux: SIGKILL from the kernel, ``PR_SET_PDEATHSIG``; elsewhere a thread watching
    the parent), and it ignores SIGINT, which a terminal sends to the whole process group: the
    parent decides what an interrupt stops."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        libc = ctypes.CDLL(None, use_errno=True)
        if libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) != 0:
            raise OSError(ctypes.get_errno(), "prctl(PR_SET_PDEATHSIG)")
    else:
        threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()
    if os.getppid() != parent:                      # the parent ended before the signal was set
        os._exit(1)


def _watch_parent(parent: int) -> None:
    """End this process once its parent ``parent`` has ended (it is then another's child)."""
    while os.getppid() == parent:
        time.sleep(0.5)
    os._exit(1)


class _Engine(abc.ABC):
    """What both engines share: a context that closes the engine, stopping its cases in flight
    when the block ends by an exception (an interrupt among them)."""

    def __enter__(self) -> _Engine:
        return self

    def __exit__(self, kind: type | None, *_: object) -> None:
        self.close(stop=kind is not None)

    @abc.abstractmethod
    def close(self, stop: bool = False) -> None:
        """Release the engine; ``stop``: end the cases in flight too."""


class PoolEngine(_Engine):
    """A local process pool of ``workers``; a broken pool is replaced and its cases run again.
    Its workers are spawned, fresh interpreters that share nothing with the process that makes
    the pool (a forked one inherits its heap and its threads' state, ROS and DDS objects among
    them, which the child's garbage collector may then destroy without the threads behind them),
    and end with it (:func:`_follow_parent`)."""

    def __init__(self, workers: int) -> None:
        if workers < 1:
            raise ValueError(f"--workers: an integer >= 1, not {workers}")
        self.workers = workers
        self.runner: Runner | None = None
        self.setup: CaseSetup | None = None
        self.pool: concurrent.futures.ProcessPoolExecutor | None = None
        self.running: dict[concurrent.futures.Future, Case] = {}
        self.attempts: dict[tuple, int] = {}

    def start(self, runner: Runner, setup: CaseSetup) -> None:
        """Run cases with ``runner`` on ``setup`` (both go to the workers by pickle)."""
        try:
            pickle.dumps((runner, setup))
        except (pickle.PicklingError, AttributeError, TypeError) as error:
            raise ValueError(f"the case runner and set-up go to worker processes by pickle: {error}") from error
        self.runner, self.setup = runner, setup
        self.pool = self._new_pool()

    def _new_pool(self) -> concurrent.futures.ProcessPoolExecutor:
        return concurrent.futures.ProcessPoolExecutor(self.workers, multiprocessing.get_context("spawn"),
                                                      initializer=_follow_parent, initargs=(os.getpid(),))

    def submit(self, case: Case) -> None:
        attempts = self.attempts[case.key] = self.attempts.get(case.key, 0) + 1
        if attempts > MAX_ATTEMPTS:
            raise CaseLost(f"case {case}: its worker died {MAX_ATTEMPTS} times")
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
        self.pool = self._new_pool()
        self.running = {}
        for case in lost:
            self.submit(case)

    def close(self, stop: bool = False) -> None:
        """Shut the pool down; ``stop``: end the cases in flight too (their workers are killed)."""
        if self.pool is None:
            return
        # the executor has no public way to end a case in flight (terminate_workers: Python 3.14)
        workers = list((self.pool._processes or {}).values()) if stop else []
        self.pool.shutdown(wait=False, cancel_futures=True)
        for process in workers:
            process.kill()
        for process in workers:
            process.join()
        self.pool.shutdown(wait=True)
        self.pool, self.running = None, {}


class DaskEngine(_Engine):
    """The cases on the Dask distributed cluster at ``address``: refused (ValueError) when no
    scheduler answers there within :data:`CONNECT_TIMEOUT`. A case that raises runs again
    :data:`DASK_RETRIES` times; one whose worker dies runs on another, up to the scheduler's
    ``allowed-failures``."""

    def __init__(self, address: str) -> None:
        try:
            from dask.distributed import Client, as_completed
        except ImportError as error:
            raise ValueError("--scheduler needs dask[distributed] (the cluster extra: pip install -e '.[cluster]' "
                             "in the checkout)") from error
        try:
            self.client = Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
        except (OSError, ValueError, TypeError) as error:
            raise ValueError(f"--scheduler {address}: no Dask scheduler answers there within "
                             f"{CONNECT_TIMEOUT:g} s ({error})") from error
        self.runner: Runner | None = None
        self.setup_future: Any = None
        self.running: dict[Any, Case] = {}
        self.completed = as_completed([], loop=self.client.loop)

    @property
    def workers(self) -> int:
        return max(1, len(self.client.scheduler_info().get("workers", {})))

    def start(self, runner: Runner, setup: CaseSetup) -> None:
        """Run cases with ``runner`` on ``setup`` (scattered to every worker)."""
        self.runner = runner
        self.setup_future = self.client.scatter(setup, broadcast=True)

    def submit(self, case: Case) -> None:
        future = self.client.submit(self.runner, case, self.setup_future, pure=False, retries=DASK_RETRIES,
                                    key=f"level3-{case.heading_deg:g}-{case.number}-{case.group}-{case.seed}-"
                                        f"{os.getpid()}-{id(self)}")
        self.running[future] = case
        self.completed.add(future)

    def wait(self) -> list[CaseResult]:
        results = []
        for future in [next(self.completed), *self.completed.next_batch(block=False)]:
            case = self.running.pop(future)
            try:
                results.append(future.result())
            except Exception as error:          # KilledWorker, or the case's own error after its retries
                raise CaseLost(f"case {case} on the Dask cluster: {type(error).__name__}: {error}") from error
        return results

    def close(self, stop: bool = False) -> None:
        """Disconnect; ``stop``: cancel the cases in flight first."""
        if stop and self.running:
            self.client.cancel(list(self.running))
        self.running = {}
        self.client.close()


def open_engine(workers: int | None = None, scheduler: str | None = None) -> PoolEngine | DaskEngine:
    """The Dask engine at ``scheduler`` (connected), else a pool of ``workers`` (default the CPU
    count); ValueError for a bad count or a scheduler that does not answer."""
    return DaskEngine(scheduler) if scheduler else PoolEngine((os.cpu_count() or 1) if workers is None else workers)


def run_search(search: Level3Search, setup: CaseSetup, journal: Journal, engine: PoolEngine | DaskEngine,
               runner: Runner = run_case, progress: bool = True) -> dict[tuple, CaseResult]:
    """Every case the search needs, on ``engine`` (opened, left open), each finished one into
    ``journal`` (closed, in case order once the search is done). The finished results by
    :attr:`Case.key`; :class:`Interrupted` on SIGINT (KeyboardInterrupt)."""
    from tqdm import tqdm

    finished = journal.finished
    bar = tqdm(total=_bound(search, finished), initial=len(finished), unit="case", disable=not progress,
               file=sys.stderr, desc="Level 3")
    try:
        engine.start(runner, setup)
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
    except KeyboardInterrupt:
        raise Interrupted(len(finished), _bound(search, finished)) from None
    finally:
        bar.close()
        journal.close()
    journal.finish()
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
