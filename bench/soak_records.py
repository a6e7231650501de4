"""The soak's bookkeeping (bench/soak.py): the state the node should run, each change in flight,
the tally of actions and violations, the figures made of a run's samples (memory growth, late
ticks by their cause) and the verdict on a run."""

from __future__ import annotations

import itertools
import math
import time
from dataclasses import dataclass, field

import numpy as np
from figures import MISSED_FACTOR

from allocator_pkg import Vehicle

RATE_HZ = 500.0
WARM_UP = 60.0               # s before the RSS baseline
MAX_VIOLATIONS_KEPT = 50
DISTURBED = 0.05             # s after a disturbance in which a late tick is put down to it
SLOW_SAMPLE = 1e-3           # s of allocation next to a late tick that it is put down to
SILENCE = 0.5                # s without commands that counts as the node hanging
RSS_LIMIT_MB = 5.0


@dataclass(frozen=True)
class State:
    """What the node should be running: the vehicle and each actuator's efficiency."""

    vehicle: Vehicle
    efficiency: dict[str, float]

    def limits(self, index: int) -> tuple[float, float]:
        actuator = self.vehicle.actuators[index]
        scale = self.efficiency.get(actuator.name, 1.0)
        return actuator.thrust_min * scale, actuator.thrust_max * scale


@dataclass
class Change:
    """A request and the state it leads to; ``answered`` is None while it is in flight."""

    sent: float
    state: State
    answered: float | None = None


@dataclass
class Tally:
    """What happened: actions and their answers, checks and violations."""

    actions: dict[str, int] = field(default_factory=dict)
    refused: list[str] = field(default_factory=list)          # valid requests the node refused
    accepted_invalid: list[str] = field(default_factory=list)
    checked: int = 0
    extreme_allocated: int = 0
    violations: int = 0
    examples: list[str] = field(default_factory=list)
    times: list[float] = field(default_factory=list)         # when each action was sent [s]

    def count(self, action: str) -> None:
        self.actions[action] = self.actions.get(action, 0) + 1
        self.times.append(time.time())

    def violation(self, text: str) -> None:
        self.violations += 1
        if len(self.examples) < MAX_VIOLATIONS_KEPT:
            self.examples.append(text)


class History:
    """The states the node has run through, to judge each command by its own stamp."""

    def __init__(self, initial: State) -> None:
        self.changes = [Change(sent=-math.inf, state=initial, answered=-math.inf)]

    @property
    def latest(self) -> State:
        """The state of the newest change that was not refused (in flight or answered)."""
        return self.changes[-1].state

    def at(self, stamp: float, period: float) -> tuple[State, State, bool]:
        """(state before, state after, whether a change was in flight) at ``stamp``: a change
        counts as in flight from its request until one period after its answer."""
        before = after = self.changes[0].state
        flight = False
        for change in self.changes[1:]:
            if change.sent > stamp:
                break
            answered = change.answered if change.answered is not None else math.inf
            if stamp <= answered + period:
                flight = True
                after = change.state
            else:
                before = after = change.state
        return before, after, flight

    def forget(self, change: Change) -> None:
        """A refused request changed nothing."""
        self.changes.remove(change)


def memory_summary(samples: list[tuple[float, dict[str, float]]]) -> dict:
    """Growth of VmRSS after the warm-up (None if the run was too short to tell)."""
    after = [(t, mb) for t, mb in samples if t >= WARM_UP]
    result: dict = {"warm_up_s": WARM_UP, "samples": [(t, mb["VmRSS"], mb.get("RssAnon")) for t, mb in samples]}
    if len(after) < 2 or after[-1][0] - after[0][0] < WARM_UP:
        return {**result, "baseline": None, "growth": None, "max_growth": None, "slope_mb_per_min": None}
    baseline = after[0][1]["VmRSS"]
    rss = np.array([mb["VmRSS"] for _, mb in after])
    minutes = np.array([t for t, _ in after]) / 60.0
    return {**result, "baseline": baseline, "final": float(rss[-1]), "growth": round(float(rss[-1] - baseline), 2),
            "max_growth": round(float(rss.max() - baseline), 2),
            "slope_mb_per_min": round(float(np.polyfit(minutes, rss, 1)[0]), 3)}


def late_ticks(stamps: list[float], solve_at: dict[float, float], disturbances: list[float]) -> dict[str, int]:
    """Missed periods (as bench/probe.py counts them) by what came right before each late
    tick: a disturbance, a slow sample, or neither (see the module docstring)."""
    period = 1.0 / RATE_HZ
    sent = np.sort(np.array(disturbances))
    causes = {"after a disturbance": 0, "next to a slow sample": 0, "elsewhere": 0}
    for before, after in itertools.pairwise(stamps):
        interval = after - before
        if interval <= MISSED_FACTOR * period:
            continue
        k = int(np.searchsorted(sent, after, side="right")) - 1
        if k >= 0 and after - sent[k] <= DISTURBED:
            cause = "after a disturbance"
        elif max(solve_at.get(before, 0.0), solve_at.get(after, 0.0)) > SLOW_SAMPLE:
            cause = "next to a slow sample"
        else:
            cause = "elsewhere"
        causes[cause] += round(interval / period) - 1
    return causes


def failures(result: dict) -> list[str]:
    """Why the soak failed; empty when it passed."""
    reasons = [result["crash"]] if result["crash"] else []
    if result["exit_code"] != 0:
        reasons.append(f"allocator_node exit code {result['exit_code']}")
    if result["longest_silence_s"] > SILENCE:
        reasons.append(f"no commands for {result['longest_silence_s']} s")
    if result["violations"]:
        reasons.append(f"{result['violations']} violations, first: {result['violation_examples'][:5]}")
    reasons += [f"valid change refused: {text}" for text in result["valid_changes_refused"]]
    reasons += [f"invalid change accepted: {text}" for text in result["invalid_changes_accepted"]]
    if result["unanswered"]:
        reasons.append(f"{result['unanswered']} requests unanswered")
    growth = result["rss_mb"]["max_growth"]
    if growth is not None and not growth < RSS_LIMIT_MB:
        reasons.append(f"RSS grew {growth} MB after the warm-up (limit {RSS_LIMIT_MB} MB)")
    return reasons
