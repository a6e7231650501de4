"""The power balance per switchboard of DNV-ST-0111 [3.12.3]-[3.12.5], jointly with the thrust.

Each source (a switchboard or prime mover, a column of Table A-5) keeps 10 % of its power for
hotel and consumers outside the thruster system, the electrical losses included [3.12.3],
[3.12.4]: P_usable = 0.9 capacity. In a balance the thrusters must give the required forces with
every source within its usable power [2.4.9], [3.12.5]:

    sum_i s_ji P_B,i r_i^(3/2) <= P_usable,j       for every source j,

s_ji the share of thruster i's power from source j (Table A-5), r_i its thrust in the direction it
pushes as a fraction of the thrust it can give that way (after its losses [3.11.4]/[3.11.5];
behind a rudder [3.10], of the propeller's thrust). P = P_B r^(3/2) is [3.9.2]'s
T_nominal ~ (D P_B)^(2/3) turned around: the standard states no part-load power of its own (the
transcription's reading, ``power.md``). A thruster that lost the share s of its feeds keeps
(1 - s) P_B and the thrust of that power, its power per newton unchanged.

:class:`PoweredCapability` adds this to the capability linear programme: per thruster on a source
that could be short, r_i above its force over its range (for a rotatable thruster over a
72-gon around the circle, r at most 1 / cos(pi/72) = 0.1 % high, and over each half-plane of its
piece: a chord of a loss or of a rudder's fan) and q_i above the chords of
r^(3/2) at r = 0, 0.05, ..., 1 (at most 0.002 high), and one row per such source,
sum_i s_ji P_B,i q_i <= P_usable,j. Both approximations overstate the power: the balance is
conservative. A source that can give every thruster it feeds its full P_B share cannot bind and
has no rows. Level 1's balance (:class:`~..case_balance.CaseBalance`) solves without the rows first
where that decides the answer (:func:`within`). Not verified by DNV.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ...capability.envelope import Capability
from ...capability.thrust_profile import ForceProfile
from ...effectiveness.model import Model
from ...vehicle.config import ActuatorConfig, Vehicle

POWER_RESERVE = 0.10
"""[3.12.3]-[3.12.4]: the share of a source's power kept for hotel and non-thruster consumers."""
PART_LOAD_STEP = 0.05
"""Between the points where the chords of r^(3/2) meet."""
R_SIDES = 72
"""Faces of the polygon that bounds a rotatable thruster's thrust fraction."""
PLANE_THROUGH_ORIGIN = 1e-9
"""A half-plane offset (per unit radius) at most this is taken to pass through the origin."""


def usable(capacity: float) -> float:
    """P_usable [kW] of a source: its capacity less the reserve of [3.12.3]-[3.12.4]."""
    return (1.0 - POWER_RESERVE) * capacity


def part_load_power(fraction: float) -> float:
    """P / P_B at the thrust fraction r: r^(3/2), [3.9.2] turned around."""
    return float(fraction) ** 1.5


@dataclass(frozen=True)
class PowerLimits:
    """The power rows of one case: the thrusters on sources that could be short, those sources,
    and ``load[j, i]`` = s_ji P_B,i / P_usable,j (the share of source j's usable power thruster i
    draws at its full thrust)."""

    thrusters: tuple[str, ...]
    sources: tuple[str, ...]
    load: np.ndarray

    def key(self) -> tuple:
        return self.thrusters, self.sources, tuple(self.load.ravel())


def feed_share(vehicle: Vehicle, name: str, lost: tuple[str, ...] = ()) -> float:
    """The share of its P_B a thruster keeps when ``lost`` sources are: the sum of its remaining
    feed shares (Table A-5); 1 without feeds."""
    actuator = next(a for a in vehicle.actuators if a.name == name)
    if not actuator.feeds:
        return 1.0
    return sum(share for feed, share in zip(actuator.feeds, actuator.feed_shares) if feed not in lost)


def demand(vehicle: Vehicle, powers: Mapping[str, float], source: str, lost: tuple[str, ...] = ()) -> float:
    """[kW] what the working thrusters a source feeds draw from it at full thrust: sum of
    s_ji P_B,i (``powers``: P_B by thruster)."""
    return sum(share * powers[a.name] for a in vehicle.actuators if a.name not in lost
               for feed, share in zip(a.feeds, a.feed_shares) if feed == source)


def power_limits(vehicle: Vehicle, powers: Mapping[str, float], lost: tuple[str, ...] = ()) -> PowerLimits | None:
    """The power rows of the case that loses ``lost`` (actuators and sources); None when no
    working source could be short (each can give its thrusters their full P_B shares)."""
    capacities = {s.name: s.capacity for s in vehicle.power_sources if s.name not in lost}
    short = tuple(s for s, capacity in capacities.items() if demand(vehicle, powers, s, lost) > usable(capacity))
    if not short:
        return None
    thrusters = tuple(a.name for a in vehicle.actuators if a.name not in lost and any(f in short for f in a.feeds))
    load = np.zeros((len(short), len(thrusters)))
    for i, name in enumerate(thrusters):
        actuator = next(a for a in vehicle.actuators if a.name == name)
        for feed, share in zip(actuator.feeds, actuator.feed_shares):
            if feed in short:
                j = short.index(feed)
                load[j, i] = share * powers[name] / usable(capacities[feed])
    return PowerLimits(thrusters, short, load)


def _chords() -> list[tuple[float, float]]:
    """(slope, intercept) of each chord of r^(3/2) between neighbouring points PART_LOAD_STEP apart."""
    points = np.linspace(0.0, 1.0, round(1.0 / PART_LOAD_STEP) + 1)
    chords = []
    for a, b in itertools.pairwise(points):
        slope = (part_load_power(b) - part_load_power(a)) / (b - a)
        chords.append((slope, part_load_power(a) - slope * a))
    return chords


CHORDS = _chords()


class PoweredCapability(Capability):
    """The capability of a Level 1 variant with its sources' power limits (the rows above)."""

    def __init__(self, vehicle: Vehicle, method: str, limits: PowerLimits,
                 profiles: Mapping[str, ForceProfile] | None = None):
        super().__init__(vehicle, method, speed=0.0, profiles=profiles)
        if self.sides is None:
            raise ValueError(f"method {method} cannot redistribute force, so the power of "
                             f"{', '.join(limits.sources)} [3.12] cannot be balanced with it; choose a method with a "
                             "thrust region (--method qp or lp)")
        self.limits = limits
        self._rows: dict[tuple, tuple[np.ndarray, np.ndarray]] = {}

    def _programme(self, cost, a_ub, b_ub, a_eq, b_eq, bounds, pieces):
        """The programme with the columns r_i, q_i of each powered thruster after the others,
        their rows, and one row per source; the solution cut back to the programme's columns."""
        base, extra = len(cost), 2 * len(self.limits.thrusters)
        key = (base, tuple(pieces))
        if key not in self._rows:
            self._rows[key] = self._power_rows(base, pieces)
        rows, right = self._rows[key]
        head = np.array(a_ub).reshape(-1, base) if a_ub else np.zeros((0, base))
        a_all = np.vstack([np.hstack([head, np.zeros((len(head), extra))]), rows])
        result = super()._programme(np.concatenate([cost, np.zeros(extra)]), list(a_all), [*b_ub, *right],
                                    np.hstack([a_eq, np.zeros((a_eq.shape[0], extra))]), b_eq,
                                    [*bounds, *[(0.0, None)] * extra], pieces)
        if result.usable:
            result.x = result.x[:base]
        return result

    def _power_rows(self, base: int, pieces) -> tuple[np.ndarray, np.ndarray]:
        """(rows, right-hand sides) of the power (:func:`power_rows`)."""
        return power_rows(self.limits, self.model, self.vehicle.actuators, base, pieces)


def within(limits: PowerLimits, model: Model, actuators: Sequence[ActuatorConfig], force: np.ndarray,
           pieces) -> bool:
    """Whether the extended forces keep every source within its usable power, with r and q as
    the rows bound them (``actuators``: the variant's, with its thrust ranges): r_i the largest of
    its :func:`fraction_entries` rows at ``force`` (0 without rows), q_i the largest chord there."""
    fractions = [max((sum(coefficient * force[column] for column, coefficient in row) for row in rows), default=0.0)
                 for rows in fraction_entries(limits, model, actuators, pieces)]
    powers = [max(0.0, *(slope * fraction + intercept for slope, intercept in CHORDS)) for fraction in fractions]
    return bool(np.all(limits.load @ np.array(powers) <= 1.0))


def fraction_entries(limits: PowerLimits, model: Model, actuators: Sequence[ActuatorConfig],
                     pieces) -> list[list[tuple[int, float]]]:
    """Per thruster of ``limits``, its rows r_i >= its force over its range: each row's
    (force column, coefficient) pairs (a rotatable thruster's over the 72-gon's faces next to its
    piece's cone, the only ones its force can reach, and its piece's half-planes; a fixed one's
    over thrust_max and over thrust_min, where it pushes that way)."""
    names = [a.name for a in actuators]
    rot, scalar = list(model.rot), list(model.scalar)
    entries = []
    for name in limits.thrusters:
        index = names.index(name)
        if index in rot:
            c1, c2 = model.rot_columns[rot.index(index)]
            entries.append([[(c1, a1), (c2, a2)] for a1, a2 in _fraction_rows(pieces[rot.index(index)])])
            continue
        column, actuator = model.scalar_columns[scalar.index(index)], actuators[index]
        rows = [[(column, 1.0 / actuator.thrust_max)]] if actuator.thrust_max > 0.0 else []
        if actuator.thrust_min < 0.0:
            rows.append([(column, 1.0 / actuator.thrust_min)])
        entries.append(rows)
    return entries


def power_rows(limits: PowerLimits, model: Model, actuators: Sequence[ActuatorConfig], base: int,
               pieces) -> tuple[np.ndarray, np.ndarray]:
    """(rows, right-hand sides) of the power over the programme's ``base`` columns and the
    columns r_i, q_i after them: per thruster its :func:`fraction_entries` rows, q_i above the
    chords; then one row per source."""
    count = len(limits.thrusters)
    rows, right = [], []

    def row(entries: dict[int, float], value: float) -> None:
        line = np.zeros(base + 2 * count)
        for column, coefficient in entries.items():
            line[column] += coefficient
        rows.append(line)
        right.append(value)

    for k, fractions in enumerate(fraction_entries(limits, model, actuators, pieces)):
        r, q = base + k, base + count + k
        for entries in fractions:
            row({**dict(entries), r: -1.0}, 0.0)
        for slope, intercept in CHORDS:
            row({r: slope, q: -1.0}, -intercept)
    for j in range(len(limits.sources)):
        row({base + count + i: limits.load[j, i] for i in range(count)}, 1.0)
    return np.array(rows), np.array(right)


def _fraction_rows(piece) -> list[tuple[float, float]]:
    """(a1, a2) per row r >= a1 f1 + a2 f2 that bounds a rotatable thruster's thrust fraction in its
    piece (start, end, radius, line, half-planes): the 72-gon's faces next to the cone over
    radius cos(pi/72), and each half-plane n . f <= c radius of a loss or a rudder's fan over
    c radius, so r is the force over what the piece gives in its direction (the gauge of the piece:
    along theta the piece reaches min(radius, c radius / n . u) over its half-planes). A half-plane
    through the origin (c = 0) bounds the directions only and adds no row."""
    start, end, radius, _, planes = piece
    if radius <= 0.0:
        return []
    apothem = radius * math.cos(math.pi / R_SIDES)
    rows = [(math.cos(angle) / apothem, math.sin(angle) / apothem) for angle in _faces(start, end)]
    return rows + [(nx / (offset * radius), ny / (offset * radius)) for nx, ny, offset in planes
                   if offset > PLANE_THROUGH_ORIGIN]


def _faces(start: float, end: float) -> list[float]:
    """The face normals [rad] of the 72-gon within half a face of the cone [start, end]: a force
    in the cone is farthest along one of them."""
    half = math.pi / R_SIDES + 1e-12
    faces = []
    for side in range(R_SIDES):
        angle = 2.0 * math.pi * side / R_SIDES
        offset = (angle - start) % (2.0 * math.pi)
        inside = offset <= end - start
        near = min(abs(offset - (end - start)), 2.0 * math.pi - offset) <= half
        if inside or near:
            faces.append(angle)
    return faces
