"""Named stretches of a run that metrics are taken over, besides the whole run: the ones a
scenario names (``windows``: name, start, end [s] and bounds of their own) and the automatic
ones of its faults: ``fault`` from a fault (an actuator's or a redundancy group's) until the
faults are cleared (or the run ends) and ``after_fault`` from the clearing until the next fault (or the end), numbered
``fault_1``, ``after_fault_1``, ... when there is more than one fault interval."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Window:
    """[start, end) [s] of the run, and the bounds (metric name: largest value) it is held to."""

    name: str
    start: float
    end: float
    bounds: dict[str, float] = field(default_factory=dict)

    def scaled(self, factor: float) -> Window:
        return Window(self.name, self.start * factor, self.end * factor, dict(self.bounds))


def fault_intervals(events, duration: float) -> list[tuple[float, float]]:
    """[start, end) [s] of each stretch with a fault in force: from the first fault (of an
    actuator or a redundancy group) while
    none is in force to the next ``clear_faults`` (or ``duration``). ``events`` sorted by time,
    each with ``time`` and ``kind``."""
    intervals, start = [], None
    for event in events:
        if event.time >= duration:
            break
        if event.kind in ("fault", "group_fault") and start is None:
            start = event.time
        elif event.kind == "clear_faults" and start is not None:
            intervals.append((start, event.time))
            start = None
    if start is not None:
        intervals.append((start, duration))
    return intervals


def fault_windows(events, duration: float) -> list[Window]:
    """The automatic windows of a run's faults (see the module)."""
    intervals = fault_intervals(events, duration)
    windows = []
    for k, (start, end) in enumerate(intervals):
        suffix = f"_{k + 1}" if len(intervals) > 1 else ""
        windows.append(Window(f"fault{suffix}", start, end))
        after = intervals[k + 1][0] if k + 1 < len(intervals) else duration
        if end < after:
            windows.append(Window(f"after_fault{suffix}", end, after))
    return windows
