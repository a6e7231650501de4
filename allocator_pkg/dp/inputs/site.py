"""A site's environment for DP capability Level 2 in place of DNV-ST-0111 Table 2-1.

A site environment is a table of conditions over the capability numbers 1 to n (n at most 11;
number 0 is calm), each a wind speed [m/s], a significant wave height Hs [m], a peak period Tp
[s] (or a zero-crossing period Tz, Tp = 1.4049 Tz [3.3.3]) and a current speed [m/s]. Keys
(:data:`SITE_KEYS`), each optional but at least one quantity given: ``name``, ``wind`` (a
rising list), ``hs``, ``tp`` or ``tz`` (not both) and ``current`` (each a value or a list).

Lists have one entry per number and the same length n; a quantity not given is Table 2-1's for
numbers 1 to n (n = 11 when no list is given). So ``current: 1.2`` is Table 2-1 with the site's
current at every number, a full set of lists is the site's own condition table. A bad key is
refused naming it.

Level 3's sea (:class:`SiteSea`): ``peak_factor`` (JONSWAP's gamma, a value or a list per
number; absent: DNV-RP-C205's from Hs and Tp), ``spreading`` (n of DNV-RP-C205's cos^n
spreading, 3.5.8.4; absent: long-crested) and ``wave_direction``, ``current_direction`` (where
they come from relative to the wind [deg]; absent: collinear, Level 1's). Level 2's static
balance keeps wind, waves and current collinear and the standard's long-crested drift [3.7]
whatever these say (its loads are the standard's formulas for one heading).

The keys sit under ``level2.site`` of the particulars file or at the top of a file of their
own (:func:`load_site`). The standard's Level 2 text is not in the transcription used here:
this is the package's reading. Not verified by DNV.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ...configuration.file_keys import NUMBER, NUMBERS, TEXT, FileKey, check_keys, key_named, names
from ...configuration.yaml_file import read_mapping
from ..standard.loads import TZ_FROM_TP
from ..standard.weather import TOP, WEATHER_CONDITIONS, WeatherCondition

SITE_KEYS = (
    FileKey("name", TEXT, "what the site is (the notes name it)", default="site"),
    FileKey("wind", NUMBERS, "a list: the wind speed of each number", unit="m/s", minimum=0.0, maximum=70.0,
            exclusive_minimum=True, range_doc="rising"),
    FileKey("hs", NUMBERS, "Hs: one value for every number, or a list", unit="m", minimum=0.0, maximum=25.0),
    FileKey("tp", NUMBERS, "the peak period: a value or a list (not with tz)", unit="s", minimum=0.0, maximum=30.0,
            exclusive_minimum=True),
    FileKey("tz", NUMBERS, "the zero-crossing period (Tp = 1.4049 Tz, [3.3.3]): a value or a list (not with tp)",
            unit="s", minimum=0.0, maximum=30.0, exclusive_minimum=True),
    FileKey("current", NUMBERS, "a value or a list", unit="m/s", minimum=0.0, maximum=5.0),
    FileKey("peak_factor", NUMBERS, "JONSWAP's gamma (Level 3's sea): a value or a list", minimum=1.0, maximum=10.0,
            default_doc="DNV-RP-C205's from Hs and Tp"),
    FileKey("spreading", NUMBER, "n of DNV-RP-C205's cos^n directional spreading (3.5.8.4) of Level 3's sea",
            minimum=0.0, maximum=100.0, default_doc="long-crested"),
    FileKey("wave_direction", NUMBER, "where the waves come from relative to the wind (Level 3)", unit="deg",
            minimum=-180.0, maximum=180.0, default_doc="collinear"),
    FileKey("current_direction", NUMBER, "where the current comes from relative to the wind (Level 3)", unit="deg",
            minimum=-180.0, maximum=180.0, default_doc="collinear"),
)
"""The keys of a site environment, each optional, at least one besides ``name`` given; a
quantity not given is Table 2-1's, the sea's keys (:class:`SiteSea`) not given Level 1's
collinear long-crested sea with DNV-RP-C205's peak factor."""
QUANTITIES = ("wind", "hs", "tp", "tz", "current")
"""The keys of the conditions (Table 2-1's columns)."""
SEA_KEYS = ("peak_factor", "spreading", "wave_direction", "current_direction")
"""The keys of :class:`SiteSea`."""


@dataclass(frozen=True)
class SiteSea:
    """What a site says of Level 3's sea beyond the conditions: JONSWAP's peak factor per
    capability number 0 ... n (empty: DNV-RP-C205's from Hs and Tp; 0 for number 0, calm), the
    cos^n spreading exponent (0: long-crested) and where the waves and the current come from
    relative to the wind [deg] (None: collinear with it, Level 1's environment). Level 2's static
    balance does not use them (:mod:`..level2`)."""

    peak_factors: tuple[float, ...] = ()
    spreading: float = 0.0
    wave_direction: float | None = None
    current_direction: float | None = None

    @property
    def collinear(self) -> bool:
        return self.wave_direction is None and self.current_direction is None

    def peak_factor(self, number: int) -> float:
        """gamma of ``number``; 0: DNV-RP-C205's from the condition's Hs and Tp."""
        return self.peak_factors[number] if self.peak_factors else 0.0

    def describe(self) -> str:
        """What the sea is, for the notes."""
        gamma = ("peak factor " + ", ".join(f"{g:g}" for g in self.peak_factors[1:]) + " (numbers 1 to "
                 f"{len(self.peak_factors) - 1})") if self.peak_factors else "DNV-RP-C205's peak factor"
        spread = f"cos^{self.spreading:g} spreading (DNV-RP-C205 3.5.8.4)" if self.spreading else "long-crested"
        directions = "wind, waves and current collinear (Level 1)" if self.collinear else \
            (f"site directions relative to the wind: waves {self.wave_direction or 0.0:g} deg, current "
             f"{self.current_direction or 0.0:g} deg")
        return f"JONSWAP sea with {gamma}, {spread}; {directions}"


@dataclass(frozen=True)
class SiteEnvironment:
    """The conditions of capability numbers 0 (calm) to n of a site, where they come from
    (``source``), and which quantities the site gives (the rest are Table 2-1's)."""

    name: str
    conditions: tuple[WeatherCondition, ...]
    source: str
    given: tuple[str, ...]
    sea: SiteSea = SiteSea()

    def describe(self) -> str:
        """One line for the notes: the site, its source, its conditions and, where it gives any of
        :data:`SEA_KEYS`, Level 3's sea."""
        rows = "; ".join(f"{n}: {c.wind:g} m/s, Hs {c.hs:g} m, Tp {c.tp:.3g} s, current {c.current:g} m/s"
                         for n, c in enumerate(self.conditions) if n)
        given = {"tp" if q == "tz" else q for q in self.given}
        kept = [q for q in ("wind", "hs", "tp", "current") if q not in given]
        sea = f" Level 3: {self.sea.describe()}; Level 2 collinear." if self.sea != SiteSea() else ""
        return (f"Environment: the site {self.name!r} ({self.source}) in place of Table 2-1, numbers 0 to "
                f"{len(self.conditions) - 1}; given: {', '.join(self.given) or 'none of the conditions'}"
                + (f"; Table 2-1's {', '.join(kept)}" if kept else "") + f". Conditions {rows}.{sea}")


def site_from_mapping(data: Any, prefix: str = "level2.site", source: str = "") -> SiteEnvironment:
    """The site environment of a mapping with the keys above; refused naming the key."""
    if not isinstance(data, Mapping):
        raise ValueError(f"{prefix}: a mapping with keys {', '.join(names(SITE_KEYS))}")
    check_keys(data, SITE_KEYS, prefix)
    given = tuple(q for q in QUANTITIES if q in data)
    if not given and not any(key in data for key in SEA_KEYS):
        raise ValueError(f"{prefix}: give at least one of {', '.join(QUANTITIES + SEA_KEYS)}")
    if "tp" in data and "tz" in data:
        raise ValueError(f"{prefix}.tz: give tp or tz, not both")
    lengths = {q: len(data[q]) for q in (*given, "peak_factor") if isinstance(data.get(q), (list, tuple))}
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
    name = data.get("name", key_named(SITE_KEYS, "name").default)
    if not isinstance(name, str):
        raise ValueError(f"{prefix}.name: text, not {name!r}")
    return SiteEnvironment(name, conditions, source or prefix, given, _sea(data, count, prefix))


def _sea(data: Mapping[str, Any], count: int, prefix: str) -> SiteSea:
    """The site's :class:`SiteSea` from :data:`SEA_KEYS`; refused naming the key."""
    gammas = ()
    if "peak_factor" in data:
        gammas = (0.0, *_column(data["peak_factor"], count, f"{prefix}.peak_factor", "peak_factor"))
    single = {key: _column(data[key], 1, f"{prefix}.{key}", key)[0] if not isinstance(data[key], (list, tuple))
              else _refuse_list(f"{prefix}.{key}") for key in SEA_KEYS[1:] if key in data}
    return SiteSea(gammas, single.get("spreading", 0.0), single.get("wave_direction"), single.get("current_direction"))


def _refuse_list(where: str) -> float:
    raise ValueError(f"{where}: one value, not a list")


def load_site(path: str | Path) -> SiteEnvironment:
    """A site environment file (YAML, the keys above at its top); every error names the path."""
    data = read_mapping(path, "a site environment file")
    try:
        return site_from_mapping(data, "site", str(path))
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from error


def _column(value: Any, count: int, where_key: str, quantity: str) -> list[float]:
    values = list(value) if isinstance(value, (list, tuple)) else [value] * count
    key = key_named(SITE_KEYS, quantity)
    result = []
    for k, item in enumerate(values):
        where = f"{where_key}[{k}]" if isinstance(value, (list, tuple)) else where_key
        if isinstance(item, bool) or not isinstance(item, (int, float)) or not math.isfinite(item):
            raise ValueError(f"{where}: a finite number [{key.unit or '-'}], not {item!r}")
        if not key.holds(item):
            unit = f" {key.unit}" if key.unit else ""
            raise ValueError(f"{where}: {item:g}{unit} outside {key.interval()}")
        result.append(float(item))
    return result
