"""The journal of a DNV-ST-0111 Level 3 run, ``cases.jsonl``: a header line (the run's inputs,
:meth:`~allocator_pkg.dp.level3.study.Level3Inputs.fingerprint`), then one finished case a line,
each flushed and fsynced as it completes, so that a run stopped at any moment resumes
(``--resume``) from the cases it holds; a line cut short by a kill ends what is read."""

from __future__ import annotations

import json
import os
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
        path.parent.mkdir(parents=True, exist_ok=True)
        temporary = path.with_suffix(".jsonl.tmp")
        with temporary.open("w") as handle:
            handle.writelines(json.dumps(data) + "\n" for data in lines)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(temporary, path)
        self.handle = path.open("a")

    def append(self, result: CaseResult) -> CaseResult:
        """Write one finished case (flushed and fsynced); the result as read back from its line."""
        line = json.dumps(result.to_json())
        self.handle.write(line + "\n")
        self.handle.flush()
        os.fsync(self.handle.fileno())
        stored = CaseResult.from_json(json.loads(line))
        self.finished[stored.case.key] = stored
        return stored

    def close(self) -> None:
        self.handle.close()


def _valid_lines(path: Path) -> list[dict[str, Any]]:
    """The journal's lines up to the first that is not whole (a run killed mid-write)."""
    lines = []
    for text in path.read_text().splitlines():
        try:
            lines.append(json.loads(text))
        except json.JSONDecodeError:
            break
    return lines
