"""The verdict of a run against its scenario's bounds: each bound an upper limit on one metric,
over the whole run (``bounds``) or over a named window (``windows[].bounds``). A metric that
is not a finite number breaks its bound."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .metrics import METRIC_UNITS

RUN = "run"
"""The scope of a bound over the whole run."""


@dataclass(frozen=True)
class Check:
    scope: str
    """``run`` or a window's name"""
    metric: str
    value: float
    bound: float

    @property
    def passed(self) -> bool:
        return math.isfinite(self.value) and self.value <= self.bound


def checks(metrics: dict[str, float], bounds: dict[str, float], windows: dict[str, dict[str, float]] | None = None,
           window_bounds: dict[str, dict[str, float]] | None = None) -> list[Check]:
    """One check per bound: ``bounds`` against the run's ``metrics``, and each window's bounds
    (``window_bounds``, by window name) against that window's metrics (``windows``)."""
    found = [Check(RUN, name, float(metrics[name]), float(bound)) for name, bound in bounds.items()]
    for scope, limits in (window_bounds or {}).items():
        found += [Check(scope, name, float((windows or {})[scope][name]), float(bound))
                  for name, bound in limits.items()]
    return found


def broken(found: list[Check]) -> list[Check]:
    return [check for check in found if not check.passed]


def verdict_lines(found: list[Check]) -> list[str]:
    """A table of the checks (verdict, scope, metric with its unit, value, bound) and a last
    line: PASS with the number of bounds, or FAIL with the number broken."""
    lines = [f"{'':4s}  {'scope':14s} {'metric':30s} {'value':>12s} {'bound':>12s}"]
    for check in found:
        label = f"{check.metric} [{METRIC_UNITS[check.metric]}]"
        lines.append(f"{'PASS' if check.passed else 'FAIL'}  {check.scope:14s} {label:30s} {check.value:12.4g} "
                     f"{check.bound:12.4g}")
    failed = broken(found)
    lines.append(f"verdict: FAIL, {len(failed)} of {count(found)} broken" if failed else
                 f"verdict: PASS, {count(found)} held" if found else "verdict: PASS, no bounds")
    return lines


def count(found: list[Check]) -> str:
    """'1 bound', '3 bounds'."""
    return f"{len(found)} bound" + ("" if len(found) == 1 else "s")
