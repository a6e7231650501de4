"""Environmental loads of DNV-ST-0111 Level 1: wind [3.5], current [3.6], wave drift [3.7].

The standard's formulas, in its own frame [2.8.2]: x forward, y to port, z up, origin at Lpp/2
on the centreline at the keel; forces positive forward and to port, the moment positive
turning the bow to port. ``direction`` [rad] is where the environment comes from, clockwise:
0 head on, pi/2 from starboard. The formulas fold it onto [0, pi] (:func:`fold`) where a port
direction acts as its starboard mirror, and use ``sin(direction)`` for the side force.

The loads are unfactored; the caller multiplies their sum by the dynamic factor [3.2.2].
:class:`BodyFrame` turns them into the vehicle file's body frame FRD (x forward, y to starboard,
z down) about that frame's origin: Y and N change sign, N moves to the body origin.

Edition December 2021, after the public transcription of [3.5]-[3.7] in the repository
WilliamBoland1/Prosjektoppgave_Collab (``dp_capability/models``), checked there against the
standard's text; not verified by DNV.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...hull.environment_loads import GRAVITY, RHO_AIR, RHO_WATER

TZ_FROM_TP = 1.4049
"""Tp / Tz of the Pierson-Moskowitz spectrum with cos^2 spreading [3.3.3]."""
C_WL_AFT_RANGE = (0.85, 1.15)
"""[3.7] clips the aft waterplane coefficient to this range."""


def fold(direction: float) -> float:
    """The formulas' ``dir``: |direction| wrapped to [-pi, pi], in [0, pi]."""
    return abs(math.remainder(direction, 2.0 * math.pi))


def _positive(key: str, value: float) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"{key}: a finite number > 0, not {value!r}")


def _finite(key: str, value: float) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{key}: a finite number, not {value!r}")


@dataclass(frozen=True)
class DnvHull:
    """The hull inputs of [3.5]-[3.7] (Table A-2), in the standard's frame: x [m] forward of Lpp/2."""

    lpp: float
    """Length between perpendiculars [m]."""
    beam: float
    """Breadth at the waterline B [m]."""
    draught: float
    """Draught T [m]."""
    los: float
    """Length between the foremost and aftmost points under water, Los [m]."""
    los_centre_x: float
    """x of Los / 2 [m]."""
    bow_angle: float
    """Bow angle of Figure 3-2 [rad], in (0, pi/2)."""
    waterplane_area_aft: float
    """Waterplane area aft of Lpp/2, A_WLaft [m^2]."""
    wind_area_frontal: float
    """Frontal projected area above water A_F,wind [m^2]."""
    wind_area_lateral: float
    """Lateral projected area above water A_L,wind [m^2]."""
    wind_centre_x: float
    """x of the centre of A_L,wind, x_L,air [m]."""
    current_area_lateral: float
    """Lateral projected area under water A_L,current [m^2]."""
    current_centre_x: float
    """x of the centre of A_L,current, x_L,current [m]."""

    def __post_init__(self) -> None:
        for key in ("lpp", "beam", "draught", "los", "waterplane_area_aft", "wind_area_frontal",
                    "wind_area_lateral", "current_area_lateral"):
            _positive(key, getattr(self, key))
        for key in ("los_centre_x", "wind_centre_x", "current_centre_x"):
            _finite(key, getattr(self, key))
        _finite("bow_angle", self.bow_angle)
        if not 0.0 < self.bow_angle < math.pi / 2:
            raise ValueError(f"bow_angle: between 0 and 90 deg, not {math.degrees(self.bow_angle):g} deg")

    @property
    def waterplane_coefficient_aft(self) -> float:
        """C_WLaft = A_WLaft / (Lpp / 2 B) before the clip of [3.7]."""
        return self.waterplane_area_aft / (0.5 * self.lpp * self.beam)


def wind_load(hull: DnvHull, speed: float, direction: float) -> np.ndarray:
    """[Fx, Fy, Mz] of [3.5]: 1/2 rho_air V^2 A_F (-0.7 cos), 1/2 rho_air V^2 A_L (0.9 sin),
    Fy at x_L,air + 0.3 (1 - 2 dir / pi) Lpp."""
    pressure = 0.5 * RHO_AIR * speed ** 2
    fy = pressure * hull.wind_area_lateral * 0.9 * math.sin(direction)
    lever = hull.wind_centre_x + 0.3 * (1.0 - 2.0 * fold(direction) / math.pi) * hull.lpp
    return np.array([pressure * hull.wind_area_frontal * -0.7 * math.cos(direction), fy, fy * lever])


def current_load(hull: DnvHull, speed: float, direction: float) -> np.ndarray:
    """[Fx, Fy, Mz] of [3.6]: 1/2 rho_water V^2 B T (-0.07 cos), 1/2 rho_water V^2 A_L,current
    (0.6 sin), Fy at x_L,current + clip(0.4 (1 - 2 dir / pi), -0.2, 0.25) Lpp."""
    pressure = 0.5 * RHO_WATER * speed ** 2
    fy = pressure * hull.current_area_lateral * 0.6 * math.sin(direction)
    shift = min(max(0.4 * (1.0 - 2.0 * fold(direction) / math.pi), -0.2), 0.25)
    return np.array([pressure * hull.beam * hull.draught * -0.07 * math.cos(direction), fy,
                     fy * (hull.current_centre_x + shift * hull.lpp)])


def period_factor(period_ratio: float) -> float:
    """f(T') of [3.7]: 1 below 1, T'^-3 exp(1 - T'^-3) from 1 on (continuous at 1)."""
    if period_ratio < 1.0:
        return 1.0
    inverse_cube = period_ratio ** -3
    return inverse_cube * math.exp(1.0 - inverse_cube)


def wave_drift_load(hull: DnvHull, hs: float, tp: float, direction: float) -> np.ndarray:
    """[Fx, Fy, Mz] of [3.7] in a sea of significant height ``hs`` [m] and peak period ``tp`` [s]:

    Fx = 1/2 rho g Hs^2 B 0.09 h1 h2 f(Tz / (0.9 Lpp^0.33)),
    Fy = 1/2 rho g Hs^2 Los 0.09 sin(direction) f(Tz / (0.75 B^0.5)),
    Mz = Fy (x_Los + (0.05 - 0.14 dir / pi) Los), with
    h1 = h1A + dir / pi (h1B - h1A), h1A = 0.8 bow_angle^0.45, h1B = 0.7 C_WLaft^2 (C_WLaft
    clipped to [0.85, 1.15]), h2 = 0.05 + 0.95 arctan(1.45 (dir - 1.75)), Tz = Tp / 1.4049.
    Zero in a calm sea (Hs 0), whatever the period."""
    if hs == 0.0:
        return np.zeros(3)
    folded = fold(direction)
    pressure = 0.5 * RHO_WATER * GRAVITY * hs ** 2
    tz = tp / TZ_FROM_TP
    c_wl_aft = min(max(hull.waterplane_coefficient_aft, C_WL_AFT_RANGE[0]), C_WL_AFT_RANGE[1])
    h1_bow = 0.8 * hull.bow_angle ** 0.45
    h1 = h1_bow + folded / math.pi * (0.7 * c_wl_aft ** 2 - h1_bow)
    h2 = 0.05 + 0.95 * math.atan(1.45 * (folded - 1.75))
    fx = pressure * hull.beam * 0.09 * h1 * h2 * period_factor(tz / (0.9 * hull.lpp ** 0.33))
    fy = pressure * hull.los * 0.09 * math.sin(direction) * period_factor(tz / (0.75 * math.sqrt(hull.beam)))
    return np.array([fx, fy, fy * (hull.los_centre_x + (0.05 - 0.14 * folded / math.pi) * hull.los)])


@dataclass(frozen=True)
class BodyFrame:
    """Where the vehicle file's body origin is in the standard's frame: ``origin_x`` [m] forward
    of Lpp/2, ``origin_height`` [m] above the keel (on the centreline)."""

    origin_x: float
    origin_height: float

    def __post_init__(self) -> None:
        _finite("body_origin_x", self.origin_x)
        _finite("body_origin_height", self.origin_height)

    def load(self, standard: np.ndarray) -> np.ndarray:
        """[X, Y, N] in FRD about the body origin of [Fx, Fy, Mz] in the standard's frame about
        its origin: the moment about the body origin is Mz - origin_x Fy, then y and z turn over."""
        fx, fy, mz = standard
        return np.array([fx, -fy, -(mz - self.origin_x * fy)])

    def standard_x(self, body_x: float) -> float:
        """x [m] forward of Lpp/2 of a body-frame x."""
        return body_x + self.origin_x

    def height(self, body_z: float) -> float:
        """Height [m] above the keel of a body-frame z (down)."""
        return self.origin_height - body_z


@dataclass(frozen=True)
class LoadComponents:
    """The unfactored loads [X, Y, N] in the body frame (FRD, about its origin), one per source."""

    wind: np.ndarray
    current: np.ndarray
    waves: np.ndarray

    @property
    def total(self) -> np.ndarray:
        return self.wind + self.current + self.waves
