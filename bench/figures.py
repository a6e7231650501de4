"""Figures the benchmarks share, without ROS: percentiles, missed periods, a process's CPU time
and resident memory from /proc."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

MISSED_FACTOR = 1.5
"""A stamp interval above this many periods has missed periods."""


def percentiles(values: list[float], *quantiles: float, maximum: bool = False) -> dict[str, float | None]:
    """The given percentiles (and the maximum) of ``values``, in the same unit; None without values."""
    keys = [f"p{q:g}" for q in quantiles] + (["max"] if maximum else [])
    if not values:
        return dict.fromkeys(keys)
    figures = [*np.percentile(values, quantiles), max(values)] if maximum else np.percentile(values, quantiles)
    return {key: round(float(value), 4) for key, value in zip(keys, figures)}


def process_cpu_seconds(pid: int) -> float:
    """User plus system CPU time [s] of process ``pid``, all threads, from /proc/<pid>/stat."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")   # utime, stime (fields 14, 15)


def memory_mb(pid: int) -> dict[str, float]:
    """VmRSS and RssAnon of process ``pid`` [MB], from /proc/<pid>/status."""
    figures = {}
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        key, _, value = line.partition(":")
        if key in ("VmRSS", "RssAnon"):
            figures[key] = int(value.split()[0]) / 1024.0
    if "VmRSS" not in figures:
        raise ProcessLookupError(f"process {pid} has no resident memory (exited)")
    return figures
