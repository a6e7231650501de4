"""DP capability Level 1 after DNV-ST-0111: the highest environmental condition held per heading.

The standard's Level 1 is a quasi-static balance: for each heading of the environment (wind,
waves and current from the same direction), the loads of the condition of each DP capability
number (0-11, the Beaufort scale with a sea state and a current: :data:`CONDITIONS`), times
the dynamic allowance :data:`DYNAMIC_ALLOWANCE`, must be balanced by the thrusters. The
number of a heading is the highest condition balanced with every lower one balanced too; the
limiting wind speed the highest wind balanced when the conditions between two numbers are
interpolated linearly (:func:`condition_at`). This is done intact and for each failure group
(actuators lost together); the worst single failure is, per heading, the lowest over the
groups. :meth:`Level1Result.summary` gives DP capability-L1(A, B, C, D).

The loads are :mod:`.environment_loads`; whether the thrusters hold them is
:meth:`Capability.reach <allocator_pkg.analysis.capability.Capability.reach>` (a linear
programme over the configured thrust ranges, forbidden sectors and failed actuators, with the
configured method's constraints), the required wrench divided by the thrust loss factor.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from ..effectiveness.faults import FaultMode
from ..vehicle.config import DOF_NAMES, Vehicle
from .capability import Capability
from .environment_loads import (
    RHO_AIR,
    RHO_WATER,
    LoadCoefficients,
    VesselParticulars,
    current_load,
    wave_drift_load,
    wind_load,
)

DYNAMIC_ALLOWANCE = 1.25
"""Factor on the sum of the environmental loads."""
THRUST_LOSS_FACTOR = 0.9
"""General thrust loss factor on the available thrust (the particulars file may set another)."""
BOW_SECTOR_DEG = 30.0
"""A and C are the minima within this many degrees of the bow."""
MAX_STEP_DEG = 10.0
"""The standard asks for headings this far apart or closer."""
BISECTION_STEPS = 14
"""Halvings of the interval between two capability numbers for the limiting wind speed."""
INTACT = "intact"
WORST = "worst single failure"


@dataclass(frozen=True)
class Condition:
    """One environmental condition: wind [m/s], Hs [m], Tp [s], current [m/s]."""

    wind: float
    hs: float
    tp: float
    current: float


CONDITIONS = (
    Condition(0.0, 0.0, 0.0, 0.0),
    Condition(1.5, 0.1, 3.5, 0.25),
    Condition(3.4, 0.4, 4.5, 0.50),
    Condition(5.4, 0.8, 5.5, 0.75),
    Condition(7.9, 1.3, 6.5, 0.75),
    Condition(10.7, 2.1, 7.5, 0.75),
    Condition(13.8, 3.1, 8.5, 0.75),
    Condition(17.1, 4.2, 9.0, 0.75),
    Condition(20.7, 5.7, 10.0, 0.75),
    Condition(24.4, 7.4, 10.5, 0.75),
    Condition(28.4, 9.5, 11.5, 0.75),
    Condition(32.6, 12.1, 12.0, 0.75),
)
"""The conditions of DP capability numbers 0 to 11 (index = number)."""
TOP = len(CONDITIONS) - 1


def condition_at(level: float) -> Condition:
    """The condition at a fractional capability number in [0, 11], each quantity linear between
    the two numbers around it."""
    if not 0.0 <= level <= TOP:
        raise ValueError(f"a capability number between 0 and {TOP}, not {level}")
    low = min(math.floor(level), TOP - 1)
    t = level - low
    a, b = CONDITIONS[low], CONDITIONS[low + 1]
    return Condition(*((1.0 - t) * getattr(a, f.name) + t * getattr(b, f.name) for f in fields(Condition)))


def environment_load(vessel: VesselParticulars, condition: Condition, direction: float) -> np.ndarray:
    """[X, Y, N] of the condition's wind, waves and current, all from ``direction`` [rad],
    times :data:`DYNAMIC_ALLOWANCE`."""
    return DYNAMIC_ALLOWANCE * (wind_load(vessel, condition.wind, direction)
                                + current_load(vessel, condition.current, direction)
                                + wave_drift_load(vessel, condition.hs, condition.tp, direction))


@dataclass(frozen=True)
class Particulars:
    """A particulars file: the hull, the failure groups (name: actuators lost together; empty:
    each actuator alone) and the thrust loss factor."""

    vessel: VesselParticulars
    failure_groups: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    thrust_loss_factor: float = THRUST_LOSS_FACTOR
    name: str = ""

    def __post_init__(self) -> None:
        if not (math.isfinite(self.thrust_loss_factor) and 0.0 < self.thrust_loss_factor <= 1.0):
            raise ValueError(f"thrust_loss_factor: a number in (0, 1], not {self.thrust_loss_factor!r}")


_HULL_KEYS = ("lpp", "beam", "draught", "wind_area_frontal", "wind_area_lateral", "wind_centre_x",
              "underwater_centre_x")


def particulars_from_mapping(data: Mapping[str, Any], name: str = "") -> Particulars:
    """The particulars of a mapping with the keys of a particulars file (``docs/dp_capability.md``)."""
    if not isinstance(data, Mapping):
        raise ValueError("a particulars file is a mapping of keys to values")
    known = {*_HULL_KEYS, "coefficients", "failure_groups", "thrust_loss_factor", "name"}
    unknown = sorted(set(data) - known)
    if unknown:
        raise ValueError(f"unknown key(s): {', '.join(unknown)}; known: {', '.join(sorted(known))}")
    missing = [key for key in _HULL_KEYS[:5] if key not in data]
    if missing:
        raise ValueError(f"missing key(s): {', '.join(missing)}")
    coefficients = data.get("coefficients") or {}
    if not isinstance(coefficients, Mapping):
        raise ValueError("coefficients: a mapping of coefficient names to numbers")
    names = {f.name for f in fields(LoadCoefficients)}
    bad = sorted(set(coefficients) - names)
    if bad:
        raise ValueError(f"coefficients: unknown key(s) {', '.join(bad)}; known: {', '.join(sorted(names))}")
    hull = {key: _number(data, key) for key in _HULL_KEYS if key in data}
    vessel = VesselParticulars(**hull, coefficients=LoadCoefficients(
        **{key: _number(coefficients, key, "coefficients.") for key in coefficients}))
    groups = data.get("failure_groups") or {}
    if not isinstance(groups, Mapping) or not all(
            isinstance(members, list) and members and all(isinstance(m, str) for m in members)
            for members in groups.values()):
        raise ValueError("failure_groups: a mapping of group names to non-empty lists of actuator names")
    return Particulars(vessel=vessel, failure_groups={str(k): tuple(v) for k, v in groups.items()},
                       thrust_loss_factor=_number(data, "thrust_loss_factor") if "thrust_loss_factor" in data
                       else THRUST_LOSS_FACTOR, name=str(data.get("name", name)))


def _number(data: Mapping[str, Any], key: str, prefix: str = "") -> float:
    value = data[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{prefix}{key}: a number, not {value!r}")
    return float(value)


def load_particulars(path: str | Path) -> Particulars:
    """Read a particulars file (YAML)."""
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as error:
        raise ValueError(f"{path}: {error}") from error
    try:
        return particulars_from_mapping(data, path.stem)
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from error


@dataclass(frozen=True)
class Level1Result:
    """Capability numbers and limiting wind speeds per heading for each case: ``intact``, each
    failure group by name, and ``worst failure`` (per heading the lowest over the groups)."""

    headings_deg: np.ndarray
    numbers: dict[str, np.ndarray]
    wind_limits: dict[str, np.ndarray]
    notes: tuple[str, ...]

    def summary(self) -> tuple[int, int, int, int]:
        """(A, B, C, D): intact minimum within +-30 deg of the bow and over every heading, the
        same for the worst single failure."""
        return level1_summary(self.headings_deg, self.numbers[INTACT], self.numbers[WORST])

    def summary_line(self) -> str:
        return "DP capability-L1({}, {}, {}, {})".format(*self.summary())

    def rows(self) -> list[tuple[str, float, int, float]]:
        """(case, heading_deg, capability_number, wind_speed_limit) for every case and heading."""
        return [(case, float(heading), int(self.numbers[case][k]), float(self.wind_limits[case][k]))
                for case in self.numbers for k, heading in enumerate(self.headings_deg)]


def level1_summary(headings_deg: np.ndarray, intact: np.ndarray, worst: np.ndarray) -> tuple[int, int, int, int]:
    """(A, B, C, D) of the numbers per heading."""
    off_bow = np.abs((np.asarray(headings_deg) + 180.0) % 360.0 - 180.0)
    bow = off_bow <= BOW_SECTOR_DEG + 1e-9
    return (int(np.min(intact[bow])), int(np.min(intact)), int(np.min(worst[bow])), int(np.min(worst)))


class Level1:
    """The Level 1 balance of one vehicle and its particulars."""

    def __init__(self, vehicle: Vehicle, particulars: Particulars, method: str | None = None):
        self.vehicle = vehicle
        self.particulars = particulars
        names = set(vehicle.names)
        for group, members in particulars.failure_groups.items():
            unknown = [m for m in members if m not in names]
            if unknown:
                raise ValueError(f"failure_groups.{group}: no actuator named {', '.join(unknown)}; "
                                 f"the vehicle has {', '.join(vehicle.names)}")
        self.groups = dict(particulars.failure_groups) or {name: (name,) for name in vehicle.names}
        self.capability = Capability(vehicle, method, speed=0.0)
        self.uncontrolled = [DOF_NAMES.index(d) for d in ("surge", "sway", "yaw") if d not in vehicle.dofs]

    def balanced(self, level: float, direction: float, failed: tuple[str, ...] = ()) -> bool:
        """Whether the thrusters hold the condition at ``level`` from ``direction`` [rad]."""
        load = environment_load(self.particulars.vessel, condition_at(level), direction)
        tau = np.zeros(6)
        tau[[0, 1, 5]] = -load / self.particulars.thrust_loss_factor
        if not np.any(tau):
            return True
        if np.any(np.abs(tau[self.uncontrolled]) > 1e-9 * np.max(np.abs(tau))):
            return False                        # a load where no actuator is asked to push
        faults = dict.fromkeys(failed, FaultMode.FAILED)
        model = self.capability.model
        scale = float(np.max(np.abs(tau[model.dof_index]) / np.maximum(model.authority, 1e-12)))
        return self.capability.reach(tau / scale, faults)[0] >= scale * (1.0 - 1e-9)   # asked in units of authority

    def heading(self, direction: float, failed: tuple[str, ...] = ()) -> tuple[int, float]:
        """(capability number, limiting wind speed [m/s]) of one heading."""
        return limit(lambda level: self.balanced(level, direction, failed))

    def run(self, step_deg: float = 10.0) -> Level1Result:
        if not 0.0 < step_deg <= 90.0 or not math.isclose(360.0 / step_deg, round(360.0 / step_deg)):
            raise ValueError(f"a heading step that divides 360 deg and is at most 90 deg, not {step_deg}")
        headings = np.arange(round(360.0 / step_deg)) * step_deg
        cases = {INTACT: (), **self.groups}
        numbers, winds = {}, {}
        for case, failed in cases.items():
            pairs = [self.heading(math.radians(h), failed) for h in headings]
            numbers[case] = np.array([p[0] for p in pairs], dtype=int)
            winds[case] = np.array([p[1] for p in pairs])
        numbers[WORST] = np.min([numbers[g] for g in self.groups], axis=0)
        winds[WORST] = np.min([winds[g] for g in self.groups], axis=0)
        notes = self.notes()
        if step_deg > MAX_STEP_DEG:
            notes.append(f"Headings every {step_deg:g} deg: coarser than the standard's {MAX_STEP_DEG:g} deg.")
        return Level1Result(headings, numbers, winds, tuple(notes))

    def notes(self) -> list[str]:
        """What the numbers assume, for the output."""
        v = self.particulars.vessel
        c = v.coefficients
        notes = [
            f"Thrust: the configured thrust ranges, forbidden sectors and failed actuators of the params file "
            f"(method {self.capability.method}), times a thrust loss factor {self.particulars.thrust_loss_factor:g}; "
            "not the standard's nominal thrust from power and propeller diameter, and no ventilation, "
            "thruster-thruster (beyond the forbidden sectors) or current flushing losses.",
            f"Loads times the dynamic allowance {DYNAMIC_ALLOWANCE:g}; "
            f"air {RHO_AIR:g} kg/m^3, water {RHO_WATER:g} kg/m^3.",
            f"Hull: Lpp {v.lpp:g} m, B {v.beam:g} m, T {v.draught:g} m, wind areas {v.wind_area_frontal:g} m^2 "
            f"frontal and {v.wind_area_lateral:g} m^2 lateral (centre x {v.wind_centre_x:g} m), "
            f"underwater centre x {v.underwater_centre_x:g} m.",
            "Coefficients: " + ", ".join(f"{f.name} {getattr(c, f.name):g}" for f in fields(LoadCoefficients)) + ".",
            "Failure groups: " + "; ".join(f"{g}: {', '.join(m)}" for g, m in self.groups.items()) + ".",
            "Limiting wind speed: conditions between two numbers interpolated linearly; "
            f"at number {TOP} the table's {CONDITIONS[TOP].wind:g} m/s (held at least that).",
        ]
        if self.uncontrolled:
            lost = ", ".join(DOF_NAMES[i] for i in self.uncontrolled)
            notes.append(f"Not controlled: {lost}; a load there is not held.")
        return notes


def limit(balanced: Callable[[float], bool]) -> tuple[int, float]:
    """(capability number, limiting wind speed) from a test of a fractional number: the highest
    number held with every lower one, then bisection toward the next."""
    number = 0
    while number < TOP and balanced(number + 1):
        number += 1
    if number == TOP:
        return number, CONDITIONS[TOP].wind
    low, high = float(number), float(number + 1)
    for _ in range(BISECTION_STEPS):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if balanced(middle) else (low, middle)
    return number, condition_at(low).wind


def level1(vehicle: Vehicle, particulars: Particulars, step_deg: float = 10.0,
           method: str | None = None) -> Level1Result:
    """DP capability Level 1 of a vehicle: every heading, intact and for each failure group."""
    return Level1(vehicle, particulars, method).run(step_deg)
