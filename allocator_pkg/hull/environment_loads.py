"""Mean wind, current and wave-drift loads on a ship-shaped hull at rest.

Pure functions of a vessel's main particulars: no actuators, no effectiveness, so that a
capability balance and a closed-loop simulation's environment model can share them.

Frames and angles: loads are [X, Y, N] in the body frame FRD (X forward, Y to starboard,
N turning the bow to starboard). ``direction`` [rad] is where the environment comes from,
relative to the bow and clockwise: 0 head on, pi/2 from starboard. The flow goes the other
way, so a head wind pushes the hull aft (X < 0) and a wind from starboard pushes it to port.

Every load is a drag-like force with a constant coefficient over a reference area (wind and
current) or a reflecting length (wave drift), resolved along the body axes with cos and sin
of the direction; the yaw moment is the side force times a lever that moves from the centre of
the lateral area toward the end facing the flow (:func:`lever`). The coefficients are the
fields of :class:`LoadCoefficients` (:data:`COEFFICIENT_KEYS`), each with its default and where it
comes from in ``docs/dp_capability.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np

from ..configuration.file_keys import NUMBER, FileKey, key_named

RHO_AIR = 1.226
"""Air density [kg/m^3]."""
RHO_WATER = 1026.0
"""Sea water density [kg/m^3]."""
GRAVITY = 9.81
"""[m/s^2]."""


COEFFICIENT_KEYS = (
    FileKey("wind_surge", NUMBER, "head-on wind drag over the frontal wind area", default=0.7, minimum=0.0),
    FileKey("wind_sway", NUMBER, "beam wind drag over the lateral wind area", default=0.9, minimum=0.0),
    FileKey("current_surge", NUMBER, "head-on current drag over beam x draught", default=0.6, minimum=0.0),
    FileKey("current_sway", NUMBER, "beam current drag over length x draught (two-dimensional cross-flow drag of "
            "a hull section)", default=0.7, minimum=0.0),
    FileKey("drift_surge", NUMBER, "fraction of a flat wall's wave drift the bow gives, over the beam", default=0.5,
            minimum=0.0),
    FileKey("drift_sway", NUMBER, "fraction of a flat wall's wave drift the side gives, over the length",
            default=1.0, minimum=0.0),
    FileKey("lever_shift", NUMBER, "how far [fraction of Lpp] the centre of a side load moves toward the end "
            "facing the flow when the flow comes along the hull (a flat plate's quarter chord); none for beam flow",
            default=0.25, minimum=0.0),
)
"""The ``coefficients`` of a particulars file, the fields of :class:`LoadCoefficients`."""


@dataclass(frozen=True)
class LoadCoefficients:
    """Dimensionless load coefficients, each a key of :data:`COEFFICIENT_KEYS` with its default
    (stated assumptions, see the docs)."""

    wind_surge: float = key_named(COEFFICIENT_KEYS, "wind_surge").default
    wind_sway: float = key_named(COEFFICIENT_KEYS, "wind_sway").default
    current_surge: float = key_named(COEFFICIENT_KEYS, "current_surge").default
    current_sway: float = key_named(COEFFICIENT_KEYS, "current_sway").default
    drift_surge: float = key_named(COEFFICIENT_KEYS, "drift_surge").default
    drift_sway: float = key_named(COEFFICIENT_KEYS, "drift_sway").default
    lever_shift: float = key_named(COEFFICIENT_KEYS, "lever_shift").default

    def __post_init__(self) -> None:
        for item in fields(self):
            value = getattr(self, item.name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0.0):
                raise ValueError(f"coefficients.{item.name}: a finite number >= 0, not {value!r}")


@dataclass(frozen=True)
class VesselParticulars:
    """Main particulars [m, m^2] of a ship-shaped hull; x positions in the body frame of the
    vehicle's params file (forward positive)."""

    lpp: float
    beam: float
    draught: float
    wind_area_frontal: float
    wind_area_lateral: float
    wind_centre_x: float
    """x of the centre of the lateral wind area."""
    underwater_centre_x: float
    """x of the centre of the lateral underwater area (current and waves)."""
    coefficients: LoadCoefficients = field(default_factory=LoadCoefficients)

    def __post_init__(self) -> None:
        for name in ("lpp", "beam", "draught", "wind_area_frontal", "wind_area_lateral"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0):
                raise ValueError(f"{name}: a finite number > 0, not {value!r}")
        for name in ("wind_centre_x", "underwater_centre_x"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value)):
                raise ValueError(f"{name}: a finite number, not {value!r}")


def lever(direction: float, centre_x: float, lpp: float, shift: float) -> float:
    """x [m] where a side load acts: ``centre_x + shift lpp (1 - 2 |direction| / pi)``, with
    ``direction`` wrapped to [-pi, pi] (forward of the centre for flow from ahead, aft of it
    for flow from astern, at it for beam flow)."""
    wrapped = abs(math.remainder(direction, 2.0 * math.pi))
    return centre_x + shift * lpp * (1.0 - 2.0 * wrapped / math.pi)


def _resolved(surge: float, sway: float, direction: float, centre_x: float, lpp: float,
              shift: float) -> np.ndarray:
    """[X, Y, N] of a load of head-on size ``surge`` and beam size ``sway`` from ``direction``."""
    x = -surge * math.cos(direction)
    y = -sway * math.sin(direction)
    return np.array([x, y, y * lever(direction, centre_x, lpp, shift)])


def wind_load(vessel: VesselParticulars, speed: float, direction: float) -> np.ndarray:
    """[X, Y, N] of a steady wind of ``speed`` [m/s]: 1/2 rho_air V^2 C A over the frontal
    area (surge) and the lateral area (sway)."""
    c = vessel.coefficients
    pressure = 0.5 * RHO_AIR * speed ** 2
    return _resolved(pressure * c.wind_surge * vessel.wind_area_frontal,
                     pressure * c.wind_sway * vessel.wind_area_lateral,
                     direction, vessel.wind_centre_x, vessel.lpp, c.lever_shift)


def current_load(vessel: VesselParticulars, speed: float, direction: float) -> np.ndarray:
    """[X, Y, N] of a uniform current of ``speed`` [m/s]: 1/2 rho_water V^2 C A over beam x
    draught (surge) and length x draught (sway)."""
    c = vessel.coefficients
    pressure = 0.5 * RHO_WATER * speed ** 2
    return _resolved(pressure * c.current_surge * vessel.beam * vessel.draught,
                     pressure * c.current_sway * vessel.lpp * vessel.draught,
                     direction, vessel.underwater_centre_x, vessel.lpp, c.lever_shift)


def reflection_factor(peak_period: float, draught: float) -> float:
    """Share of the incoming wave energy a hull of ``draught`` stops: 1 - exp(-2 k T), with k
    the deep-water wave number of the peak period, k = (2 pi / Tp)^2 / g (the energy flux of
    a deep-water wave below depth T is exp(-2 k T) of the whole and passes under the keel)."""
    if peak_period <= 0.0:
        return 1.0
    deep = GRAVITY * peak_period * peak_period / (8.0 * math.pi ** 2 * draught)    # 1 / (2 k T)
    return 1.0 if deep == 0.0 else 1.0 - math.exp(-1.0 / deep)


def wave_drift_load(vessel: VesselParticulars, hs: float, peak_period: float, direction: float) -> np.ndarray:
    """[X, Y, N] of the mean wave drift in a long-crested sea of significant height ``hs`` [m]
    and peak period [s]: a fully reflecting wall takes rho g Hs^2 / 16 per metre in irregular
    waves; the hull takes that times :func:`reflection_factor` and its coefficient, over the
    beam (surge) and the length (sway)."""
    if hs == 0.0:
        return np.zeros(3)
    c = vessel.coefficients
    per_metre = RHO_WATER * GRAVITY * hs ** 2 / 16.0 * reflection_factor(peak_period, vessel.draught)
    return _resolved(per_metre * c.drift_surge * vessel.beam, per_metre * c.drift_sway * vessel.lpp,
                     direction, vessel.underwater_centre_x, vessel.lpp, c.lever_shift)
