"""The journal of a DNV-ST-0111 Level 3 run, ``cases.jsonl``: a header line (the run's inputs,
:meth:`~allocator_pkg.dp.level3.study.Level3Inputs.fingerprint`), then one finished case a line,
each flushed and fsynced as it completes, so that a run stopped at any moment resumes
(``--resume``) from the cases it holds; a line cut short by a kill ends what is read. A finished
run rewrites it in case order, the same on any engine and worker count."""

from __future__ import annotations

import contextlib
import json
import os
import signal
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from .case import CaseResult


class Journal:
    """``cases.jsonl``: a header line (the run's inputs), then one finished case a line."""

    def __init__(self, path: Path, header: dict[str, Any], resume: bool) -> None:
        self.path = path
        self.finished: dict[tuple, CaseResult] = {}
        lines = [header]
        if resume and path.exists():
            lines = _valid_lines(path)
            if not lines or lines[0] != header:
                raise ValueError(f"--resume: {path} was written for other inputs (or is not a Level 3 journal); "
                                 "run without --resume to start over")
            for data in lines[1:]:
                result = CaseResult.from_json(data)
                self.finished[result.case.key] = result
        self.header = lines[0]
        _replace_lines(path, lines)
        self.handle = path.open("a")

    def append(self, result: CaseResult) -> CaseResult:
        """Write one finished case (flushed and fsynced); the result as read back from its line.
        SIGINT waits until the line is written and counted."""
        line = json.dumps(result.to_json())
        stored = CaseResult.from_json(json.loads(line))
        with _interrupts_held():
            self.handle.write(line + "\n")
            self.handle.flush()
            os.fsync(self.handle.fileno())
            self.finished[stored.case.key] = stored
        return stored

    def finish(self) -> None:
        """Rewrite the (closed) journal as its header and the finished cases in case order
        (:attr:`Case.key`), the same whatever order they finished in."""
        ordered = [self.finished[key].to_json() for key in sorted(self.finished)]
        _replace_lines(self.path, [self.header, *ordered])

    def close(self) -> None:
        self.handle.close()


@contextlib.contextmanager
def _interrupts_held() -> Iterator[None]:
    """SIGINT held back in this block and raised again at its end (Python runs signal handlers in
    the main thread only, so elsewhere there is nothing to hold)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda number, _: caught.append(number))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if caught:
            signal.raise_signal(signal.SIGINT)


def _replace_lines(path: Path, lines: list[dict[str, Any]]) -> None:
    """``path`` replaced at once by ``lines`` (flushed and fsynced before it takes the name)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_suffix(".jsonl.tmp")
    with temporary.open("w") as handle:
        handle.writelines(json.dumps(data) + "\n" for data in lines)
        handle.flush()
        os.fsync(handle.fileno())
    os.replace(temporary, path)


def _valid_lines(path: Path) -> list[dict[str, Any]]:
    """The journal's lines up to the first that is not whole (a run killed mid-write)."""
    lines = []
    for text in path.read_text().splitlines():
        try:
            lines.append(json.loads(text))
        except json.JSONDecodeError:
            break
    return lines
