"""Thrust losses of DNV-ST-0111 Level 1 that depend on the thrust direction: flushing a dead
thruster [3.11.4] and the skeg [3.11.5], combined as [3.11.6] combines them.

[3.11.4]: a thruster flushes a dead thruster when the angle between its thrust direction and
the vector from the dead thruster to it is less than phi = arctan(0.6 D / s) (open propeller)
or arctan(0.35 D / s) (ducted), D the diameter of the flushing thruster and s the horizontal
distance. Closer than 8 D (open) or 4 D (ducted), and unless the dead thruster is a tunnel
thruster, it then loses thrust: pointing straight along that vector the factor is
beta = 1 - 1 / (0.02 (s/D)^2 + 0.25 s/D + 1.2), linear in Cartesian coordinates to 1 at the
sector's edges (Figure 3-6): along delta off the centre, beta sin(phi) / (sin(phi - |delta|) +
beta sin|delta|).

[3.11.5]: a thruster above the base line, other than a tunnel thruster, loses thrust flushing a
skeg (or gondola) when the shortest distance s to the vertical plane forward along x from the
skeg's aft most point is less than 15 D (open) or 8 D (ducted) and it is not directly behind the
skeg: s = sqrt(dx^2 + dy^2) aft of that point, |dy| beside the skeg, dx = x_skeg - x_thr,
dy = y_skeg - y_thr (the standard's frame, y to port), alpha_jet = arctan(0.6 D / s). Thrust
angles there (0 forward, counter-clockwise from above, toward port):

- port of the skeg (Table 3-7): alpha_flush = pi/2 - arctan(dx / dy), alpha_maxloss =
  min(max(alpha_flush + alpha_jet, pi/2), pi); the factor is 1 from 0 to max(alpha_flush -
  alpha_jet, 0), 2 alpha_maxloss / pi - 1 at alpha_maxloss, 1 from min(alpha_maxloss +
  4 alpha_jet, pi) to 2 pi;
- starboard (Table 3-8): alpha_flush = 3 pi/2 - arctan(dx / dy), alpha_maxloss =
  max(min(alpha_flush - alpha_jet, 3 pi/2), pi); 1 from pi to max(alpha_maxloss - 4 alpha_jet,
  pi), 3 - 2 alpha_maxloss / pi at alpha_maxloss, 1 from min(alpha_flush + alpha_jet, 2 pi);

linear in the angle between the points ("linear interpolation in polar coordinates").

[3.11.6]: beta_T = beta_misc beta_vent beta_T,flushing_dead beta_T,flushing_skeg, either
flushing factor 1 where it does not apply. The direction-dependent pair is a
:class:`~...capability.thrust_profile.ThrustProfile`: several dead thrusters, or several skegs, take the
lowest factor per direction; the Figure 3-6 notch alone is drawn exactly (its corners), anything
else (the skeg's polar ramps, overlaps) by chords between corners at most :data:`CHORD_STEP`
apart. A thruster of fixed direction takes the factor of that direction (and of the opposite
one reversed).

Read as the public transcription reads it (repository WilliamBoland1/Prosjektoppgave_Collab,
``dp_capability/models/Descriptions/dead_flushing.md`` and ``skeg_loss.md``): the dead
sector centred on the vector from the dead thruster to the flushing one (thrust that sends the
race onto it, as in [3.11.3]); open or ducted by the flushing thruster's duct (a tunnel counts
as open); port or starboard relative to the skeg; "directly behind" as level with it
(y_thr = y_skeg); "above the base line" as a height above the keel > 0. Angles here are thrust
angles in the body frame (FRD: 0 forward, pi/2 to starboard): the standard's mirrored. Not
verified by DNV.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...capability.thrust_profile import TWO_PI, ThrustProfile
from ...configuration.file_keys import NUMBER, FileKey, names
from ...vehicle.config import ActuatorConfig
from .loads import BodyFrame
from .thrust import ThrusterData

DEAD_FLUSHING_DISTANCE = {False: 8.0, True: 4.0}
"""[3.11.4], in diameters of the flushing thruster: open (False) and ducted (True)."""
DEAD_FLUSHING_SPREAD = {False: 0.6, True: 0.35}
"""[3.11.4]: phi = arctan(k D / s), open and ducted."""
SKEG_DISTANCE = {False: 15.0, True: 8.0}
"""[3.11.5], in diameters of the thruster: open and ducted."""
SKEG_KEYS = (
    FileKey("x", NUMBER, "the aft most point of a skeg or gondola (Table A-2), for [3.11.5]", required=True,
            unit="m, body frame", range_doc="finite"),
    FileKey("y", NUMBER, "its y", required=True, unit="m, body frame", range_doc="finite"),
)
"""One item of a particulars file's ``skegs``."""
CHORD_STEP = math.radians(1.0)
"""The largest angle between two corners of a loss that is not straight in Cartesian coordinates."""
READINGS = ("[3.11.4]/[3.11.5] read as the public transcription reads them: the dead sector centred on the "
            "vector from the dead thruster to the flushing one; open or ducted by the flushing thruster (a tunnel "
            "open); several dead thrusters, or skegs, the lowest factor per direction, the two kinds multiplied "
            "[3.11.6]; port or starboard of the skeg by y; level with the skeg is 'directly behind'; 'above the "
            "base line' a height above the keel > 0; the skeg's polar interpolation drawn by chords every 1 deg "
            "(inside it); a fixed thruster takes the factor of its direction")
"""How the clauses are read where the text leaves it open, for the output."""


@dataclass(frozen=True)
class LossUnit:
    """A thruster as the losses see it: horizontal position [m] (body frame), diameter [m],
    ducted, tunnel thruster, height above the keel [m]."""

    name: str
    x: float
    y: float
    diameter: float
    ducted: bool
    tunnel: bool
    height: float


@dataclass(frozen=True)
class Skeg:
    """The aft most point of a skeg or gondola (x, y) [m], body frame (Table A-2)."""

    x: float
    y: float


@dataclass(frozen=True)
class DeadLoss:
    """[3.11.4]: ``thruster`` loses thrust within ``half_angle`` of ``centre`` [rad] (its race
    would hit the dead ``dead``), down to ``beta`` at the centre."""

    thruster: str
    dead: str
    centre: float
    half_angle: float
    beta: float

    def factor(self, angle: float) -> float:
        """Figure 3-6: beta sin(phi) / (sin(phi - |delta|) + beta sin|delta|) inside, 1 outside."""
        delta = abs(math.remainder(angle - self.centre, TWO_PI))
        if delta >= self.half_angle - 1e-9:                            # the edges (to rounding)
            return 1.0
        phi, beta = self.half_angle, self.beta
        return beta * math.sin(phi) / (math.sin(phi - delta) + beta * math.sin(delta))

    def breakpoints(self) -> list[float]:
        return [self.centre - self.half_angle, self.centre, self.centre + self.half_angle]


@dataclass(frozen=True)
class SkegLoss:
    """[3.11.5]: ``thruster``'s factor over the thrust angle, linear between ``points``
    ((angle [rad], factor), increasing, body frame, spanning one turn)."""

    thruster: str
    points: tuple[tuple[float, float], ...]

    def factor(self, angle: float) -> float:
        angles, factors = zip(*self.points)
        return float(np.interp(angles[0] + (angle - angles[0]) % TWO_PI, angles, factors))

    def breakpoints(self) -> list[float]:
        return [angle for angle, _ in self.points]


def dead_flushing_beta(s_over_d: float) -> float:
    """[3.11.4]: 1 - 1 / (0.02 (s/D)^2 + 0.25 s/D + 1.2)."""
    return 1.0 - 1.0 / (0.02 * s_over_d ** 2 + 0.25 * s_over_d + 1.2)


def dead_flushing_loss(thruster: LossUnit, dead: LossUnit) -> DeadLoss | None:
    """The [3.11.4] loss of ``thruster`` flushing ``dead``; None for a dead tunnel thruster or
    one not closer than 8 D (open) / 4 D (ducted)."""
    if dead.tunnel:
        return None
    dx, dy = thruster.x - dead.x, thruster.y - dead.y
    distance = math.hypot(dx, dy)
    if distance == 0.0:
        raise ValueError(f"{thruster.name} and {dead.name} are at the same horizontal position")
    if distance >= DEAD_FLUSHING_DISTANCE[thruster.ducted] * thruster.diameter:
        return None
    half_angle = math.atan(DEAD_FLUSHING_SPREAD[thruster.ducted] * thruster.diameter / distance)
    return DeadLoss(thruster.name, dead.name, math.atan2(dy, dx), half_angle,
                    dead_flushing_beta(distance / thruster.diameter))


def skeg_loss(thruster: LossUnit, skeg: Skeg) -> SkegLoss | None:
    """The [3.11.5] loss of ``thruster`` flushing ``skeg`` (Tables 3-7 and 3-8); None where it
    does not apply (a tunnel, at or below the base line, level with the skeg, too far)."""
    dx, dy = skeg.x - thruster.x, -(skeg.y - thruster.y)              # the standard's frame: y to port
    if thruster.tunnel or thruster.height <= 0.0 or dy == 0.0:
        return None
    distance = math.hypot(dx, dy) if dx > 0.0 else abs(dy)
    if distance >= SKEG_DISTANCE[thruster.ducted] * thruster.diameter:
        return None
    jet = math.atan(0.6 * thruster.diameter / distance)
    pi = math.pi
    if dy < 0.0:                                                       # port of the skeg, Table 3-7
        flush = pi / 2 - math.atan(dx / dy)
        worst = min(max(flush + jet, pi / 2), pi)
        points = [(0.0, 1.0), (max(flush - jet, 0.0), 1.0), (worst, 2 * worst / pi - 1),
                  (min(worst + 4 * jet, pi), 1.0), (TWO_PI, 1.0)]
    else:                                                              # starboard, Table 3-8
        flush = 3 * pi / 2 - math.atan(dx / dy)
        worst = max(min(flush - jet, 3 * pi / 2), pi)
        points = [(0.0, 1.0), (pi, 1.0), (max(worst - 4 * jet, pi), 1.0), (worst, 3 - 2 * worst / pi),
                  (min(flush + jet, TWO_PI), 1.0), (TWO_PI, 1.0)]
    merged: list[tuple[float, float]] = []
    for angle, factor in points:                                       # a range of no width: the lower
        if merged and math.isclose(angle, merged[-1][0], abs_tol=1e-12):
            merged[-1] = (angle, min(merged[-1][1], factor))
        else:
            merged.append((angle, factor))
    body = tuple((-angle, factor) for angle, factor in reversed(merged))   # body angle = -standard angle
    return SkegLoss(thruster.name, body)


def losses(thruster: LossUnit, dead: Iterable[LossUnit], skegs: Iterable[Skeg]) -> tuple[list[DeadLoss],
                                                                                         list[SkegLoss]]:
    """Every [3.11.4] loss of ``thruster`` for the ``dead`` thrusters and every [3.11.5] loss
    for the ``skegs`` that applies."""
    dead_losses = [loss for unit in dead if unit.name != thruster.name
                   if (loss := dead_flushing_loss(thruster, unit)) is not None]
    skeg_losses = [loss for skeg in skegs if (loss := skeg_loss(thruster, skeg)) is not None]
    return dead_losses, skeg_losses


def direction_factor(dead_losses: Sequence[DeadLoss], skeg_losses: Sequence[SkegLoss], angle: float) -> float:
    """[3.11.6]: beta_T,flushing_dead beta_T,flushing_skeg along ``angle`` [rad], each the lowest
    over its losses."""
    dead = min((loss.factor(angle) for loss in dead_losses), default=1.0)
    return dead * min((loss.factor(angle) for loss in skeg_losses), default=1.0)


def thrust_profile(dead_losses: Sequence[DeadLoss], skeg_losses: Sequence[SkegLoss]) -> ThrustProfile | None:
    """The losses as a thrust profile: corners at every breakpoint, and every :data:`CHORD_STEP`
    wherever the boundary is not a single Figure 3-6 chord; None without a loss."""
    if not dead_losses and not skeg_losses:
        return None
    marks = sorted({round(angle % TWO_PI, 12) % TWO_PI
                    for loss in (*dead_losses, *skeg_losses) for angle in loss.breakpoints()})
    angles = []
    for k, start in enumerate(marks):
        end = marks[k + 1] if k + 1 < len(marks) else marks[0] + TWO_PI
        middle = 0.5 * (start + end)
        active_dead = sum(loss.factor(middle) < 1.0 for loss in dead_losses)
        active_skeg = sum(loss.factor(middle) < 1.0 for loss in skeg_losses)
        steps = 1 if active_dead + active_skeg == 0 or (active_dead == 1 and not active_skeg) else \
            max(1, math.ceil((end - start) / CHORD_STEP - 1e-9))
        angles += [start + (end - start) * j / steps for j in range(steps)]
    factors = [direction_factor(dead_losses, skeg_losses, angle) for angle in angles]
    corners = tuple((angle, factor if factor < 1.0 - 1e-9 else 1.0) for angle, factor in zip(angles, factors))
    if all(factor == 1.0 for _, factor in corners):
        return None
    return ThrustProfile(corners)


def loss_units(actuators: Iterable[ActuatorConfig], thrusters: Mapping[str, ThrusterData],
               frame: BodyFrame) -> list[LossUnit]:
    """The thrusters of the vehicle file (positions) with their particulars (Table A-3); control
    surfaces left out."""
    return [LossUnit(a.name, a.position[0], a.position[1], thrusters[a.name].diameter, thrusters[a.name].ducted,
                     thrusters[a.name].kind == "tunnel", frame.height(a.position[2])) for a in actuators
            if not a.is_surface]


def describe_losses(cases: Mapping[str, Mapping[str, ThrustProfile]]) -> str:
    """The loss sectors per case, for the output: thruster, from and to [deg], the lowest factor
    and where (thrust angle in the body frame)."""
    parts = []
    for case, profiles in cases.items():
        sectors = [f"{name} {start:.1f} to {end:.1f} deg, {lowest:.3f} at {at:.1f}"
                   for name, profile in profiles.items() for start, end, lowest, at in loss_sectors(profile)]
        parts.append(f"{case}: " + ("; ".join(sectors) if sectors else "none"))
    return ("Thrust losses by direction ([3.11.4] flushing a dead thruster, [3.11.5] a skeg; from, to, lowest "
            "factor at [deg], thrust angle in the body frame): " + ". ".join(parts) + f". {READINGS}.")


def loss_sectors(profile: ThrustProfile) -> list[tuple[float, float, float, float]]:
    """(from [deg], to [deg], lowest factor, its angle [deg]) of each run of corners below 1, from
    and to the corners at 1 around it; thrust angles in the body frame, from in (-180, 180], to
    after from (less than 360 deg on)."""
    corners, count = profile.corners, len(profile.corners)
    below = [k for k in range(count) if corners[k][1] < 1.0]
    runs: list[list[int]] = []
    for k in below:
        if runs and runs[-1][-1] == k - 1:
            runs[-1].append(k)
        else:
            runs.append([k])
    if len(runs) > 1 and runs[0][0] == 0 and runs[-1][-1] == count - 1:
        runs[0] = runs.pop() + runs[0]                     # across the end of the corner list
    sectors = []
    for run in runs:
        start, end = corners[(run[0] - 1) % count][0], corners[(run[-1] + 1) % count][0]
        lowest = min(run, key=lambda k: corners[k][1])
        sectors.append((_deg(start), _deg(start) + (_deg(end) - _deg(start)) % 360.0, corners[lowest][1],
                        _deg(corners[lowest][0])))
    return sectors


def _deg(angle: float) -> float:
    """[deg] in (-180, 180]."""
    return math.degrees(math.remainder(angle, TWO_PI))


def case_profiles(units: Sequence[LossUnit], failed: Collection[str],
                  skegs: Iterable[Skeg]) -> dict[str, ThrustProfile]:
    """Per working thruster with a loss in a case (``failed`` lost), its profile: [3.11.4] for
    the failed thrusters, [3.11.5] for the skegs."""
    dead = [unit for unit in units if unit.name in failed]
    profiles = {}
    for unit in units:
        if unit.name not in failed and (profile := thrust_profile(*losses(unit, dead, skegs))) is not None:
            profiles[unit.name] = profile
    return profiles


def skegs_from_list(data: Any) -> tuple[Skeg, ...]:
    """The particulars' ``skegs``: a list of mappings with ``x`` and ``y`` [m], the aft most point
    of each skeg or gondola in the vehicle file's body frame (none: no skeg loss)."""
    if data is None:
        return ()
    if not isinstance(data, list):
        raise ValueError("skegs: a list of mappings with x and y [m] (the aft most point of each skeg, body frame)")
    skegs = []
    for k, item in enumerate(data):
        if not isinstance(item, dict) or set(item) != set(names(SKEG_KEYS)) or not all(
                isinstance(item[key], (int, float)) and not isinstance(item[key], bool)
                and math.isfinite(item[key]) for key in names(SKEG_KEYS)):
            raise ValueError(f"skegs[{k}]: a mapping with finite numbers x and y [m], not {item!r}")
        skegs.append(Skeg(float(item["x"]), float(item["y"])))
    return tuple(skegs)
