"""Rudders behind propellers in DNV-ST-0111 Level 1 [3.10]: the force of a propeller and its
rudder together.

[3.10.1], for a rudder behind a propeller giving positive thrust:

    F_surge = T_effective (1 - C_x alpha^2),   F_sway = T_effective C_Y alpha,
    C_Y = 0.0126 k1 k2 A_r / D^2,   C_x = 0.02 C_Y,

alpha the rudder angle in degrees ("for rudder angle above 30 degrees values for 30 degrees shall
be used"), k1 of the profile type (Table 3-5), k2 of the arrangement (Table 3-6: 1.15 behind a
fixed propeller nozzle, else 1.0), A_r the area of the movable part of the rudder directly
behind the propeller (chord at most 1.0 D), D the propeller diameter, T_effective the forward
effective thrust of [3.9.1]. [3.10.2]: with negative thrust the rudder is neglected. [3.8.3]: the
force acts where the rudder stock meets the propeller axis.

So the forces of the pair are a fan (the origin and the curve of the forward thrust over
alpha in [-alpha_max, alpha_max], convex: a parabola bulging away from the origin, drawn by chords
every degree of alpha, inside it) or the reversed thrust along the shaft, one or the other
(:class:`RudderFan`, a :class:`~...capability.thrust_profile.ForceProfile`). The forbidden zones and losses of
[3.11] take the shaft direction, as for the propeller alone.

After the public transcription in the repository WilliamBoland1/Prosjektoppgave_Collab
(``dp_capability/models/Descriptions/rudders.md``; shaft lines only, as it reads [3.8.3]). Not
verified by DNV.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

from ...capability.thrust_profile import ForcePiece, ForceProfile, HalfPlane
from ...configuration.file_keys import BOOLEAN, NUMBER, TEXT, FileKey, check_keys, key_named, names
from ...vehicle.config import AZIMUTH, RUDDER, ActuatorConfig, RotationConfig, Vehicle
from .thrust import ThrusterData

RUDDER_C_Y = 0.0126
"""[3.10.1]: C_Y = 0.0126 k1 k2 A_r / D^2, per degree of rudder angle."""
RUDDER_C_X_FROM_C_Y = 0.02
"""[3.10.1]: C_x = 0.02 C_Y, per degree squared."""
RUDDER_ANGLE_CAP_DEG = 30.0
"""[3.10.1]: beyond 30 deg the values of 30 deg."""
K1 = {"naca": 1.1, "hollow": 1.35, "flat_sided": 1.1, "fish_tail": 1.4, "flap": 1.65, "nozzle": 1.9, "mixed": 1.21}
"""Table 3-5, profile type (Figure 3-5), ahead: NACA-Goettingen, hollow profile, flat-sided, with
"fish tail", with flap, nozzle rudder, mixed profiles (e.g. HSVA)."""
K2_FIXED_NOZZLE = 1.15
"""Table 3-6: a rudder behind a fixed propeller nozzle (all other arrangements 1.0)."""
ANGLE_STEP_DEG = 1.0
"""The fan's corners: every this many degrees of rudder angle."""
RUDDER_KEYS = (
    FileKey("propeller", TEXT, "the propeller it is behind", required=True, range_doc="a `shaft_line` of `thrusters`"),
    FileKey("profile", TEXT, "Table 3-5", required=True, choices=tuple(K1)),
    FileKey("area", NUMBER, "A_r: the movable part directly behind the propeller, chord at most 1.0 D",
            required=True, unit="m^2", minimum=0.0, exclusive_minimum=True),
    FileKey("behind_fixed_nozzle", BOOLEAN, "Table 3-6", default=False),
)
"""A rudder's row of Table A-4 in a particulars file (``rudders.<rudder>``); the defaults of :class:`RudderData`."""
READINGS = ("[3.10] read as the public transcription reads it: behind shaft lines only; A_r as given (the chord "
            "limit of 1.0 D is the user's); the largest rudder angle the vehicle file's deflection_max, at most "
            "30 deg; the fan drawn by chords every 1 deg of rudder angle (inside it); the [3.11] zones and losses "
            "of the shaft direction")
"""How the clause is read where the text leaves it open, for the output."""


@dataclass(frozen=True)
class RudderData:
    """A rudder's row of Table A-4: the propeller it is behind (a shaft line of the particulars'
    ``thrusters``), profile type (Table 3-5), A_r [m^2] and whether it is behind a fixed nozzle."""

    name: str
    propeller: str
    profile: str
    area: float
    behind_fixed_nozzle: bool = key_named(RUDDER_KEYS, "behind_fixed_nozzle").default

    def __post_init__(self) -> None:
        key = f"rudders.{self.name}"
        if not isinstance(self.propeller, str):
            raise ValueError(f"{key}.propeller: the name of the propeller the rudder is behind")
        if self.profile not in K1:
            raise ValueError(f"{key}.profile: one of {', '.join(K1)} (Table 3-5), not {self.profile!r}")
        if isinstance(self.area, bool) or not isinstance(self.area, (int, float)) or not (
                math.isfinite(self.area) and self.area > 0.0):
            raise ValueError(f"{key}.area: A_r [m^2], a finite number > 0, not {self.area!r}")
        if not isinstance(self.behind_fixed_nozzle, bool):
            raise ValueError(f"{key}.behind_fixed_nozzle: true or false, not {self.behind_fixed_nozzle!r}")


def rudder_coefficients(rudder: RudderData, diameter: float) -> tuple[float, float]:
    """(C_x, C_Y) of [3.10.1] for a propeller of diameter D [m]."""
    k2 = K2_FIXED_NOZZLE if rudder.behind_fixed_nozzle else 1.0
    c_y = RUDDER_C_Y * K1[rudder.profile] * k2 * rudder.area / diameter ** 2
    return RUDDER_C_X_FROM_C_Y * c_y, c_y


def rudder_force(c_x: float, c_y: float, thrust: float, angle_deg: float, max_angle_deg: float) -> tuple[float, float]:
    """(F_surge, F_sway) [N] of [3.10.1] at a rudder angle [deg], clipped to the rudder's maximum
    and to 30 deg; positive angles give positive sway."""
    alpha = max(-min(max_angle_deg, RUDDER_ANGLE_CAP_DEG), min(angle_deg, max_angle_deg, RUDDER_ANGLE_CAP_DEG))
    return thrust * (1.0 - c_x * alpha ** 2), thrust * c_y * alpha


@dataclass(frozen=True)
class RudderFan:
    """The forces of a propeller along ``shaft`` [rad, body frame] with its rudder: the fan of
    [3.10.1] at the forward thrust, or the reversed thrust along the shaft [3.10.2]."""

    c_x: float
    c_y: float
    max_angle_deg: float
    shaft: float = 0.0

    def corners(self) -> list[tuple[float, float]]:
        """(angle [rad], share of the forward thrust) of the fan's corners, increasing."""
        limit = min(self.max_angle_deg, RUDDER_ANGLE_CAP_DEG)
        steps = max(1, math.ceil(2.0 * limit / ANGLE_STEP_DEG - 1e-9))
        points = [rudder_force(self.c_x, self.c_y, 1.0, -limit + 2.0 * limit * k / steps, limit)
                  for k in range(steps + 1)]
        return [(self.shaft + math.atan2(sway, surge), math.hypot(surge, sway)) for surge, sway in points]

    def factor(self, angle: float) -> float:
        """The share of the forward thrust along ``angle`` [rad] (on a chord of the fan); the share
        of the reversed thrust is 1 along the shaft backwards, and nothing else is reachable."""
        offset = math.remainder(angle - self.shaft, 2.0 * math.pi)
        corners = [(math.remainder(a - self.shaft, 2.0 * math.pi), share) for a, share in self.corners()]
        for (a, ra), (b, rb) in itertools.pairwise(corners):
            if a <= offset <= b:
                xa, ya, xb, yb = ra * math.cos(a), ra * math.sin(a), rb * math.cos(b), rb * math.sin(b)
                cross = xa * yb - ya * xb
                denominator = math.cos(offset) * (yb - ya) - math.sin(offset) * (xb - xa)
                return cross / denominator if denominator > 0.0 else min(ra, rb)
        return 1.0 if abs(abs(offset) - math.pi) < 1e-9 else 0.0

    def available(self, angle: float, low: float, high: float) -> float:
        """The thrust along ``angle`` [rad] of a propeller of range [low, high] with its rudder: the
        forward thrust times :meth:`factor` in the fan, -low straight back, else nothing."""
        backwards = abs(math.remainder(angle - self.shaft, 2.0 * math.pi)) > math.pi / 2
        return (-low if backwards else high) * self.factor(angle)

    def force_pieces(self, arcs: Sequence[tuple[float, float]], low: float, high: float) -> list[ForcePiece]:
        """The fan at the forward thrust ``high`` (the chords' half-planes and its edges) and the
        ray backwards along the shaft at -``low``; ``arcs`` do not apply (the rudder turns the
        force, the propeller does not turn)."""
        corners = self.corners()
        pieces: list[ForcePiece] = []
        if high > 0.0:
            planes: list[HalfPlane] = []
            for (a, ra), (b, rb) in itertools.pairwise(corners):
                xa, ya, xb, yb = ra * math.cos(a), ra * math.sin(a), rb * math.cos(b), rb * math.sin(b)
                nx, ny = yb - ya, xa - xb
                size = math.hypot(nx, ny)
                planes.append((nx / size, ny / size, (nx * xa + ny * ya) / size))
            pieces.append((corners[0][0], corners[-1][0], high, False, tuple(planes)))
        if low < 0.0:
            back = self.shaft + math.pi
            pieces.append((back, back, -low, False, ()))
        return pieces or [(self.shaft, self.shaft, 0.0, True, ())]


@dataclass(frozen=True)
class RudderPair:
    """A shaft line with the rudder behind it: the rudder's name, the pair's :class:`RudderFan` and
    where its force acts (the rudder stock on the propeller axis [3.8.3], body frame)."""

    rudder: str
    fan: RudderFan
    position: tuple[float, float, float]

    def turned(self, propeller: ActuatorConfig) -> ActuatorConfig:
        """The propeller (its thrust range that of Level 1) as a thruster whose force the rudder
        turns: rotatable all round, its forces those of :attr:`fan`."""
        rotation = RotationConfig(-math.pi, math.pi, 0.0, (), propeller.thrust_min < 0.0, 0.0)
        return replace(propeller, type=AZIMUTH, position=self.position, rotation=rotation)


def rudder_pairs(vehicle: Vehicle, thrusters: Mapping[str, ThrusterData],
                 rudders: Mapping[str, RudderData]) -> dict[str, RudderPair]:
    """Per shaft line with a rudder, by the propeller's name, the pair; refused naming the key when
    a control surface of the vehicle file has no ``rudders`` row (or is a fin), a row names no
    rudder, or its propeller is not a shaft line of fixed horizontal direction ahead of it."""
    surfaces = {a.name: a for a in vehicle.actuators if a.is_surface}
    for name in rudders:
        if name not in surfaces or surfaces[name].type != RUDDER:
            raise ValueError(f"rudders.{name}: no rudder of that name in the vehicle file")
    pairs = {}
    for name, surface in surfaces.items():
        if name not in rudders:
            raise ValueError(f"rudders.{name}: missing; Level 1 needs each control surface as a rudder behind a "
                             "propeller (Table A-4) ([3.10]; fins are not in Level 1)")
        data = rudders[name]
        propeller = next((a for a in vehicle.actuators if a.name == data.propeller), None)
        row = thrusters.get(data.propeller)
        if propeller is None or row is None or row.kind != "shaft_line" or propeller.rotatable \
                or propeller.is_surface or abs(propeller.direction[2]) > 1e-9:
            raise ValueError(f"rudders.{name}.propeller: a shaft line of the vehicle file and the particulars' "
                             f"thrusters (fixed, horizontal), not {data.propeller!r} ([3.10] as transcribed)")
        (xp, yp, zp), (xr, yr, _), (dx, dy, _) = propeller.position, surface.position, propeller.direction
        along = (xr - xp) * dx + (yr - yp) * dy
        if along >= 0.0:
            raise ValueError(f"rudders.{name}.propeller: the rudder is not behind {data.propeller}")
        c_x, c_y = rudder_coefficients(data, row.diameter)
        fan = RudderFan(c_x, c_y, math.degrees(surface.surface.deflection_max), math.atan2(dy, dx))
        pairs[data.propeller] = RudderPair(name, fan, (xp + along * dx, yp + along * dy, zp))
    return pairs


def force_profiles(variant: Vehicle, losses: Mapping[str, ForceProfile],
                   pairs: Mapping[str, RudderPair]) -> dict[str, ForceProfile]:
    """What the capability analysis takes for a variant's rotatable thrusters: a turned shaft
    line's :class:`RudderFan` (its losses are in its range), another thruster's ``losses``."""
    rotatable = {a.name for a in variant.actuators if a.rotatable}
    profiles = {name: profile for name, profile in losses.items() if name in rotatable}
    profiles.update({name: pair.fan for name, pair in pairs.items() if name in rotatable})
    return profiles


def describe_rudders(pairs: Mapping[str, RudderPair]) -> str:
    """The rudders behind propellers, for the output."""
    return "Rudders behind propellers [3.10]: " + ("; ".join(
        f"{pair.rudder} behind {name}: C_Y {pair.fan.c_y:.5f}/deg, C_x {pair.fan.c_x:.7f}/deg^2, alpha up to "
        f"{min(pair.fan.max_angle_deg, RUDDER_ANGLE_CAP_DEG):g} deg, force at x {pair.position[0]:g} m"
        for name, pair in pairs.items()) or "none") + (f". {READINGS}." if pairs else ".")


def rudders_from_mapping(data: Any) -> dict[str, RudderData]:
    """The particulars' ``rudders``: per control surface of the vehicle file, by its name, the
    keys of :data:`RUDDER_KEYS` (``behind_fixed_nozzle`` optional, false)."""
    if data is None:
        return {}
    if not isinstance(data, Mapping):
        raise ValueError("rudders: a mapping of the vehicle file's rudder names to their Table A-4 data")
    rudders = {}
    for name, row in data.items():
        if not isinstance(row, Mapping):
            raise ValueError(f"rudders.{name}: a mapping with keys {', '.join(names(RUDDER_KEYS))}")
        check_keys(row, RUDDER_KEYS, f"rudders.{name}")
        rudders[str(name)] = RudderData(name=str(name), **row)
    return rudders
