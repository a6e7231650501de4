"""A site's environment for DP capability Level 2 in place of DNV-ST-0111 Table 2-1.

A site environment is a table of conditions over the capability numbers 1 to n (n at most 11;
number 0 is calm), each a wind speed [m/s], a significant wave height Hs [m], a peak period Tp
[s] (or a zero-crossing period Tz, Tp = 1.4049 Tz [3.3.3]) and a current speed [m/s]. Keys, each
optional but at least one of them given:

- ``name``: what the site is (text);
- ``wind``: a list, one speed per number, rising, in (0, 70];
- ``hs``: a value for every number or a list, in [0, 25];
- ``tp`` or ``tz`` (not both): a value or a list, in (0, 30];
- ``current``: a value or a list, in [0, 5].

Lists have one entry per number and the same length n; a quantity not given is Table 2-1's for
numbers 1 to n (n = 11 when no list is given). So ``current: 1.2`` is Table 2-1 with the site's
current at every number, a full set of lists is the site's own condition table. A bad key is
refused naming it. The keys sit under ``level2.site`` of the particulars file or at the top of a
file of their own (:func:`load_site`). The standard's Level 2 text is not in the transcription used
here: this is the package's reading. Not verified by DNV.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from ..standard.loads import TZ_FROM_TP
from ..standard.weather import TOP, WEATHER_CONDITIONS, WeatherCondition

QUANTITIES = ("wind", "hs", "tp", "tz", "current")
SITE_KEYS = ("name", *QUANTITIES)
RANGES = {"wind": (0.0, 70.0, False), "hs": (0.0, 25.0, True), "tp": (0.0, 30.0, False),
          "tz": (0.0, 30.0, False), "current": (0.0, 5.0, True)}
"""(low, high, low included) of each quantity: wind [m/s], Hs [m], Tp and Tz [s], current [m/s]."""
UNITS = {"wind": "m/s", "hs": "m", "tp": "s", "tz": "s", "current": "m/s"}


@dataclass(frozen=True)
class SiteEnvironment:
    """The conditions of capability numbers 0 (calm) to n of a site, where they come from
    (``source``), and which quantities the site gives (the rest are Table 2-1's)."""

    name: str
    conditions: tuple[WeatherCondition, ...]
    source: str
    given: tuple[str, ...]

    def describe(self) -> str:
        """One line for the notes: the site, its source and its conditions."""
        rows = "; ".join(f"{n}: {c.wind:g} m/s, Hs {c.hs:g} m, Tp {c.tp:.3g} s, current {c.current:g} m/s"
                         for n, c in enumerate(self.conditions) if n)
        given = {"tp" if q == "tz" else q for q in self.given}
        kept = [q for q in ("wind", "hs", "tp", "current") if q not in given]
        return (f"Environment: the site {self.name!r} ({self.source}) in place of Table 2-1, numbers 0 to "
                f"{len(self.conditions) - 1}; given: {', '.join(self.given)}"
                + (f"; Table 2-1's {', '.join(kept)}" if kept else "") + f". Conditions {rows}.")


def site_from_mapping(data: Any, prefix: str = "level2.site", source: str = "") -> SiteEnvironment:
    """The site environment of a mapping with the keys above; refused naming the key."""
    if not isinstance(data, Mapping):
        raise ValueError(f"{prefix}: a mapping with keys {', '.join(SITE_KEYS)}")
    unknown = sorted(set(data) - set(SITE_KEYS))
    if unknown:
        raise ValueError(f"{prefix}: unknown key(s) {', '.join(map(str, unknown))}; known: {', '.join(SITE_KEYS)}")
    given = tuple(q for q in QUANTITIES if q in data)
    if not given:
        raise ValueError(f"{prefix}: give at least one of {', '.join(QUANTITIES)}")
    if "tp" in data and "tz" in data:
        raise ValueError(f"{prefix}.tz: give tp or tz, not both")
    lengths = {q: len(data[q]) for q in given if isinstance(data[q], (list, tuple))}
    if "wind" in given and "wind" not in lengths:
        raise ValueError(f"{prefix}.wind: a list of wind speeds, one per capability number")
    count = next(iter(lengths.values()), TOP)
    for quantity, length in lengths.items():
        if not 1 <= length <= TOP or length != count:
            raise ValueError(f"{prefix}.{quantity}: {length} entries; every list needs the same number of entries, "
                             f"1 to {TOP} (one per capability number from 1)")
    columns = {q: _column(data[q], count, f"{prefix}.{q}", q) for q in given}
    if "tz" in columns:
        columns["tp"] = [TZ_FROM_TP * value for value in columns.pop("tz")]
    table = {q: columns.get(q, [getattr(WEATHER_CONDITIONS[n], q) for n in range(1, count + 1)])
             for q in ("wind", "hs", "tp", "current")}
    wind = [0.0, *table["wind"]]
    for number in range(1, count + 1):
        if wind[number] <= wind[number - 1]:
            raise ValueError(f"{prefix}.wind[{number - 1}]: the wind speed of number {number} must exceed that of "
                             f"number {number - 1} ({wind[number]:g} <= {wind[number - 1]:g} m/s)")
    conditions = (WEATHER_CONDITIONS[0], *(WeatherCondition(*(table[q][k] for q in ("wind", "hs", "tp", "current")))
                                           for k in range(count)))
    name = data.get("name", "site")
    if not isinstance(name, str):
        raise ValueError(f"{prefix}.name: text, not {name!r}")
    return SiteEnvironment(name, conditions, source or prefix, given)


def load_site(path: str | Path) -> SiteEnvironment:
    """A site environment file (YAML, the keys above at its top)."""
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as error:
        raise ValueError(f"{path}: {error}") from error
    try:
        return site_from_mapping(data, "site", str(path))
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from error


def _column(value: Any, count: int, key: str, quantity: str) -> list[float]:
    values = list(value) if isinstance(value, (list, tuple)) else [value] * count
    low, high, closed = RANGES[quantity]
    result = []
    for k, item in enumerate(values):
        where = f"{key}[{k}]" if isinstance(value, (list, tuple)) else key
        if isinstance(item, bool) or not isinstance(item, (int, float)) or not math.isfinite(item):
            raise ValueError(f"{where}: a finite number [{UNITS[quantity]}], not {item!r}")
        if not (low <= item if closed else low < item) or item > high:
            bracket = "[" if closed else "("
            raise ValueError(f"{where}: {item:g} {UNITS[quantity]} outside {bracket}{low:g}, {high:g}]")
        result.append(float(item))
    return result
