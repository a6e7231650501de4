"""A vessel's own wind or current load coefficients over heading, for DNV-ST-0111 Level 2
(:mod:`..level2`), in place of the prescriptive formulas of [3.5] and [3.6].

Non-dimensional, in the standard's frame [2.8.2] (x forward, y to port, the moment about Lpp/2
positive turning the bow to port), over the direction the flow comes *from* (0 deg head on,
90 deg from starboard, clockwise), linear between the rows and around 360 deg:

- wind: Fx = q A_F,wind Cx, Fy = q A_L,wind Cy, Mz = q A_L,wind Lpp Cn, q = 1/2 rho_air V^2;
- current: Fx = q B T Cx, Fy = q A_L,current Cy, Mz = q A_L,current Lpp Cn, q = 1/2 rho_water V^2.

The normalisation is this package's (the common one of wind-tunnel and model-test reports); the
public transcription of the standard has no Level 2 text to take it from.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from itertools import pairwise
from typing import Any

import numpy as np

from ...configuration.file_keys import NUMBERS, FileKey, names

COEFFICIENT_COLUMNS = (
    FileKey("heading_deg", NUMBERS, "the headings the flow comes from (0 head on, 90 from starboard)", required=True,
            unit="deg", range_doc="at least two, strictly increasing, in [0, 360)"),
    FileKey("cx", NUMBERS, "Cx at each heading", required=True, range_doc="one per heading"),
    FileKey("cy", NUMBERS, "Cy at each heading", required=True, range_doc="one per heading"),
    FileKey("cn", NUMBERS, "Cn at each heading", required=True, range_doc="one per heading"),
)
"""The keys of a coefficient table, every one given."""
COLUMNS = names(COEFFICIENT_COLUMNS)


@dataclass(frozen=True)
class CoefficientTable:
    """Cx, Cy, Cn at each heading [deg], headings increasing in [0, 360)."""

    headings_deg: tuple[float, ...]
    cx: tuple[float, ...]
    cy: tuple[float, ...]
    cn: tuple[float, ...]

    def at(self, direction: float) -> np.ndarray:
        """[Cx, Cy, Cn] for the flow from ``direction`` [rad], linear between rows, periodic."""
        heading = math.degrees(direction) % 360.0
        period = np.array([*self.headings_deg, self.headings_deg[0] + 360.0])
        if heading < period[0]:
            heading += 360.0
        return np.array([np.interp(heading, period, [*values, values[0]]) for values in (self.cx, self.cy, self.cn)])


def coefficient_table(data: Any, key: str) -> CoefficientTable:
    """The table of a mapping of :data:`COLUMNS` to lists; refused naming ``key`` and the column."""
    if not isinstance(data, Mapping) or set(data) != set(COLUMNS):
        raise ValueError(f"{key}: a mapping of {', '.join(COLUMNS)} to lists of numbers")
    columns = {}
    for name in COLUMNS:
        values = data[name]
        if (not isinstance(values, list) or len(values) < 2
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                           for v in values)):
            raise ValueError(f"{key}.{name}: a list of at least two finite numbers")
        columns[name] = tuple(float(v) for v in values)
    if len({len(values) for values in columns.values()}) != 1:
        raise ValueError(f"{key}: {', '.join(COLUMNS)} need one value per heading")
    headings = columns["heading_deg"]
    if not (headings[0] >= 0.0 and headings[-1] < 360.0 and all(b > a for a, b in pairwise(headings))):
        raise ValueError(f"{key}.heading_deg: strictly increasing, from 0 up to below 360 deg")
    return CoefficientTable(*(columns[name] for name in COLUMNS))
