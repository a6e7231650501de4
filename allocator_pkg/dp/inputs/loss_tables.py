"""A vessel's own thrust-loss tables per thruster, for DNV-ST-0111 Level 2 (:mod:`..level2`), in
place of the prescriptive losses of [3.9.3], [3.9.4], [3.11.4] and [3.11.5]: the factors of its
model tests or CFD (thruster-thruster and thruster-hull interaction, and the loss in a current).

- Over the thrust direction (``angle_deg``, ``factor``): beta(theta) in [0, 1] over the thrust
  angle theta in the body frame (0 forward, 90 deg to starboard), linear in the angle between the
  rows and around 360 deg. It scales the thrust limit the way a [3.11.4]/[3.11.5] loss does (a
  :class:`~...capability.thrust_profile.ThrustProfile`, drawn by chords between corners at most
  :data:`~..standard.losses.CHORD_STEP` apart and :data:`FACTOR_STEP` of the factor apart wherever it is
  below 1, exactly at the rows and never above the linear factor, the spiral r = a + b theta being
  convex; beside a row at 0 the last chord runs into the origin, so the factor is 0 over that
  step); a fixed
  thruster takes the factor of its direction, and of the opposite one reversed.
- Over the current speed (``speed`` [m/s], ``speed_factor``): a factor in [0, 1] on both thrust
  limits at the condition's current speed, linear between the rows and held beyond the ends.

The public transcription of the standard has no Level 2 text: the form of these tables is this
package's reading.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from itertools import pairwise
from typing import Any

import numpy as np

from ...capability.thrust_profile import TWO_PI, ThrustProfile
from ...configuration.file_keys import NUMBERS, FileKey, key_named, names
from ..standard.losses import CHORD_STEP

LOSS_TABLE_KEYS = (
    FileKey("angle_deg", NUMBERS, "the thrust directions of the thruster's loss table over direction (with "
            "`factor`)", unit="deg, body frame (0 forward, 90 to starboard)",
            range_doc="at least two, strictly increasing, spanning less than 360"),
    FileKey("factor", NUMBERS, "the factor on the thrust limit along each direction (with `angle_deg`)",
            minimum=0.0, maximum=1.0, range_doc="one per `angle_deg`, no two neighbours (cyclically) at 0"),
    FileKey("speed", NUMBERS, "the current speeds of the thruster's loss table over speed (with `speed_factor`)",
            unit="m/s", minimum=0.0, range_doc="at least two, strictly increasing"),
    FileKey("speed_factor", NUMBERS, "the factor on both thrust limits at each current speed (with `speed`)",
            minimum=0.0, maximum=1.0, range_doc="one per `speed`"),
)
"""The keys of one thruster's loss tables: ``angle_deg`` with ``factor`` and/or ``speed`` with ``speed_factor``."""
TABLE_KEYS = names(LOSS_TABLE_KEYS)
FACTOR_STEP = 0.02
"""The largest change of the factor between two corners of a direction table's profile (a steep
row pair: chords nearly radial, each within about a sixth of it of the linear factor)."""


@dataclass(frozen=True)
class LossTable:
    """One thruster's loss tables: ``angles`` [rad] (increasing, less than a turn) with their
    ``factors``, and ``speeds`` [m/s] (increasing, >= 0) with their ``speed_factors``; an empty
    pair is not given."""

    thruster: str
    angles: tuple[float, ...] = ()
    factors: tuple[float, ...] = ()
    speeds: tuple[float, ...] = ()
    speed_factors: tuple[float, ...] = ()

    def factor(self, angle: float) -> float:
        """beta at the thrust direction ``angle`` [rad]: linear in the angle, periodic (1 without a table)."""
        if not self.angles:
            return 1.0
        start = self.angles[0]
        return float(np.interp(start + (angle - start) % TWO_PI, [*self.angles, start + TWO_PI],
                               [*self.factors, self.factors[0]]))

    def speed_factor(self, speed: float) -> float:
        """The factor at the current speed [m/s], linear, held beyond the ends (1 without a table)."""
        return float(np.interp(speed, self.speeds, self.speed_factors)) if self.speeds else 1.0

    def profile(self, through: Iterable[float] = ()) -> ThrustProfile | None:
        """The direction table as a thrust profile: corners at the rows, at the angles ``through``
        [rad] (a fixed thruster's directions, exact there) and, between two rows not both at 1,
        every :data:`CHORD_STEP` and every :data:`FACTOR_STEP` of the factor; None without a table
        or with every factor 1."""
        if not self.angles or all(factor == 1.0 for factor in self.factors):
            return None
        start = self.angles[0]
        extra = [start + (angle - start) % TWO_PI for angle in through]
        rows = sorted([*self.angles, *(angle for angle in extra if min(
            abs(math.remainder(angle - row, TWO_PI)) for row in self.angles) > 1e-9)])
        corners: list[tuple[float, float]] = []
        for a, b in pairwise([*rows, start + TWO_PI]):
            fa, fb = self.factor(a), self.factor(b)
            steps = 1 if fa == fb == 1.0 else max(1, math.ceil((b - a) / CHORD_STEP - 1e-9),
                                                  math.ceil(abs(fb - fa) / FACTOR_STEP - 1e-9))
            corners += [(a + (b - a) * j / steps, self.factor(a + (b - a) * j / steps)) for j in range(steps)]
        return ThrustProfile(tuple(corners))

    def describe(self) -> str:
        """The tables given, for the output."""
        parts = []
        if self.angles:
            lowest = int(np.argmin(self.factors))
            parts.append(f"over the thrust direction ({len(self.angles)} rows, lowest {self.factors[lowest]:.3f} at "
                         f"{math.degrees(self.angles[lowest]):.1f} deg)")
        if self.speeds:
            parts.append("over the current speed (" + ", ".join(
                f"{f:.3f} at {s:g} m/s" for s, f in zip(self.speeds, self.speed_factors)) + ")")
        return f"{self.thruster} " + " and ".join(parts)


def loss_tables(data: Any, prefix: str = "level2.thrust_loss") -> dict[str, LossTable]:
    """The particulars' ``level2.thrust_loss``: per thruster, by its name, ``angle_deg`` with
    ``factor`` and/or ``speed`` with ``speed_factor``; refused naming the key."""
    if data is None:
        return {}
    if not isinstance(data, Mapping):
        raise ValueError(f"{prefix}: a mapping of thruster names to {', '.join(TABLE_KEYS)}")
    tables = {}
    for name, row in data.items():
        key = f"{prefix}.{name}"
        if not isinstance(row, Mapping) or not row or set(row) - set(TABLE_KEYS):
            raise ValueError(f"{key}: a mapping with angle_deg and factor, and/or speed and speed_factor")
        angles, factors = _pair(row, key, "angle_deg", "factor")
        if angles and not angles[-1] - angles[0] < 360.0:
            raise ValueError(f"{key}.angle_deg: spanning less than 360 deg (the table is periodic)")
        if any(a == b == 0.0 for a, b in zip(factors, (*factors[1:], *factors[:1]))):
            raise ValueError(f"{key}.factor: no two neighbouring rows at 0 (a direction without thrust is a "
                             "forbidden sector of the vehicle file)")
        speeds, speed_factors = _pair(row, key, "speed", "speed_factor")
        if speeds and not key_named(LOSS_TABLE_KEYS, "speed").holds(speeds[0]):
            raise ValueError(f"{key}.speed: at least 0 m/s")
        tables[str(name)] = LossTable(str(name), tuple(math.radians(a) for a in angles), factors, speeds,
                                      speed_factors)
    return tables


def check_thrusters(tables: Mapping[str, LossTable], thrusters: Iterable[str],
                    prefix: str = "level2.thrust_loss") -> None:
    """Refused naming the key: a table of a thruster the vehicle file does not have."""
    known = set(thrusters)
    for name in tables:
        if name not in known:
            raise ValueError(f"{prefix}.{name}: no thruster of that name in the vehicle file; it has "
                             f"{', '.join(sorted(known))}")


def _pair(row: Mapping[str, Any], key: str, column: str, values: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """The columns ``column`` (strictly increasing) and ``values`` (in [0, 1]) of one table, both or neither."""
    if (column in row) != (values in row):
        raise ValueError(f"{key}: {column} and {values} go together")
    if column not in row:
        return (), ()
    result = []
    for name in (column, values):
        items = row[name]
        if (not isinstance(items, list) or len(items) < 2 or not all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in items)):
            raise ValueError(f"{key}.{name}: a list of at least two finite numbers")
        result.append(tuple(float(v) for v in items))
    if len(result[0]) != len(result[1]):
        raise ValueError(f"{key}: {column} and {values} need one value per row")
    if not all(b > a for a, b in pairwise(result[0])):
        raise ValueError(f"{key}.{column}: strictly increasing")
    bounds = key_named(LOSS_TABLE_KEYS, values)
    if not all(bounds.holds(v) for v in result[1]):
        raise ValueError(f"{key}.{values}: each in {bounds.interval()}")
    return result[0], result[1]
