"""Capability analysis: the largest generalised force a vehicle can hold in each direction.

For each direction in a plane of two DOFs (surge and sway by default, the dynamic-positioning
capability plot), with the other controlled DOFs held at given values (yaw moment 0 by
default), a small linear programme finds the largest magnitude the actuators can produce with
the configured limits, faults and the configured method's constraints: each method says
which polygon its constraints put on a rotatable thruster's force
(:meth:`~allocator_pkg.methods.base.AllocationMethod.thrust_region_sides` and
``thrust_region_apothem``: the circle itself for ``qp``, ``nonlinear`` and ``dynamic``, the
survey's polygon of ``azimuth_polygon_sides`` sides for ``lp``, cut by the circle where it
reaches beyond it, since every thrust is clipped to its limit), or that it cannot redistribute
force (``pseudoinverse``, ``svd_filter``), in which case only forces the weighted
pseudo-inverse gives within every limit count, found by bisection on the pseudo-inverse.
``explicit`` serves only actuators of fixed direction, whose box it shares with ``qp``.

Rotatable thrusters may turn to any allowed angle (steady state: rate limits do not apply).
The faults decide the ranges and the flushing zones in force as they do for the allocator
(:class:`~allocator_pkg.allocation.conditions.Conditions`): a forbidden sector that
``protects`` a thruster lifts while that thruster does not work, with ``flushing_zones: dnv``
the zones follow the working thrusters, and a thruster pushing onto a dead one has its
[3.11.4] loss (or leaves the loss sector alone). A forbidden sector makes the set of forces
a thruster can give non-convex; it is split into convex pieces (cones at most pi wide) and
every combination of pieces is solved, keeping the best. A thrust limit that depends on the
thrust direction (``profiles``: a :class:`~.thrust_profile.ForceProfile` per rotatable
thruster: a loss sector, a propeller with its rudder) gives the thruster's convex pieces
itself, bounded by half-planes. Control surfaces give the lift of the given speed, thrusters
with voltage-indexed tables the thrust of the given supply voltage.

:func:`region`, :func:`unmodelled` and :func:`differing_methods` tell which registered
methods can serve a vehicle and which of them share a capability.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np

from ..allocation.conditions import Conditions
from ..allocation.drive_power import DrivePower, within_drive_limits
from ..allocation.power_budget import PowerBudget, PowerLimit
from ..allocation.solve import check_method
from ..effectiveness.faults import Fault, FaultMode, FaultSet
from ..effectiveness.model import Model
from ..effectiveness.power_rows import PowerRows
from ..effectiveness.sectors import can_push_along
from ..effectiveness.weighted_inverse import PseudoInverseGains
from ..methods import METHODS
from ..methods.base import CIRCLE_SIDES
from ..solvers.linear_program import solve_linear_programme
from ..solvers.outcome import Solution
from ..vehicle.angles import TWO_PI
from ..vehicle.config import Vehicle
from .envelope_power import with_power_rows
from .thrust_profile import ForceProfile
from .thruster_pieces import thruster_pieces

FORCE_DOFS = ("surge", "sway", "heave")

PowerRule = tuple[PowerBudget, PowerLimit]
"""The power sources with the available power in force, and the rule's limit at it."""


@dataclass(frozen=True)
class Envelope:
    """Largest request per direction: ``points`` (k x 2) in the plane's physical units."""

    directions: np.ndarray
    points: np.ndarray

    @property
    def magnitude(self) -> np.ndarray:
        return np.hypot(self.points[:, 0], self.points[:, 1])


class Capability:
    """Capability of one vehicle in a plane of two controlled DOFs."""

    def __init__(self, vehicle: Vehicle, method: str | None = None, speed: float = 2.0,
                 plane: tuple[str, str] | None = None, profiles: Mapping[str, ForceProfile] | None = None):
        self.vehicle = vehicle
        self.profiles = dict(profiles or {})
        self._power: PowerRows | None = None
        """A direction-dependent thrust limit per rotatable thruster, by name (none: its limit every way)."""
        fixed = [name for name in self.profiles if not vehicle.actuator(name).rotatable]
        if fixed:
            raise ValueError(f"thrust profiles are for rotatable thrusters; {', '.join(fixed)} is fixed")
        self.method = method or vehicle.method
        if self.method not in METHODS:
            raise ValueError(f"unknown method '{self.method}'; choose from {', '.join(METHODS)}")
        check_method(self.method, reachable(vehicle))
        self.sides = METHODS[self.method].thrust_region_sides(vehicle)
        if self.profiles and self.sides is None:
            raise ValueError(f"method '{self.method}' cannot redistribute force, so it has no thrust profiles "
                             f"({', '.join(self.profiles)}); choose a method that can (e.g. qp or lp)")
        self.apothem = METHODS[self.method].thrust_region_apothem(vehicle)
        self.speed = speed
        self.model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
        self.plane = plane or default_plane(vehicle)
        missing = [d for d in self.plane if d not in vehicle.dofs]
        if missing:
            raise ValueError(f"the plane {self.plane} needs controlled DOFs; {', '.join(missing)} is not controlled")
        rows = list(vehicle.dofs)
        self._plane_rows = [rows.index(d) for d in self.plane]
        same_units = all(d in FORCE_DOFS for d in self.plane) or not any(d in FORCE_DOFS for d in self.plane)
        authority = self.model.authority[self._plane_rows]
        self.axis_scale = np.ones(2) if same_units else authority / max(float(np.max(authority)), 1e-12)

    def max_force(self, direction: float, yaw_moment: float = 0.0,
                  faults: Mapping[str, Fault | FaultMode] | None = None) -> float:
        """Largest magnitude along ``direction`` [rad, in the plane, from its first DOF toward
        its second] with the yaw moment held (when yaw is controlled and not in the plane)."""
        return float(np.hypot(*self._max_point(direction, yaw_moment, self.in_force(faults))))

    def scale(self, tau, faults: Mapping[str, Fault | FaultMode] | None = None) -> float:
        """The largest lambda with lambda * tau attainable ([X, Y, Z, K, M, N]; uncontrolled DOFs
        ignored): a request is attainable when this is at least 1."""
        return self.reach(tau, faults)[0]

    def reach(self, tau, faults: Mapping[str, Fault | FaultMode] | None = None, speed: float | None = None,
              voltage: float | None = None, power: PowerRule | None = None) -> tuple[float, np.ndarray]:
        """(lambda, wrench): the largest lambda with lambda * tau attainable (uncontrolled DOFs
        of tau ignored; inf for a zero request) at a surge speed and supply voltage (None: the
        analysis' speed, the nominal voltage), and the whole wrench [X, Y, Z, K, M, N] the
        actuators give there (in the uncontrolled DOFs what they give on the way). ``power``:
        the power rule in force (:meth:`reach_forces`)."""
        magnitude, force = self.reach_forces(tau, faults, speed, voltage, power)
        return magnitude, self.model.t_e @ force

    def reach_forces(self, tau, faults: Mapping[str, Fault | FaultMode] | None = None, speed: float | None = None,
                     voltage: float | None = None, power: PowerRule | None = None) -> tuple[float, np.ndarray]:
        """(lambda, f): lambda as :meth:`reach` gives it and the extended forces f (m, the model's
        columns) that give lambda * tau (zeros for a zero request).

        With ``power`` (the budget and the limit in force, docs/power.md) every source stays
        within its available power as the allocator keeps it: with the power rows of a method
        that solves with them (the same chords and weights, :mod:`~allocator_pkg.methods.power_block`)
        in the linear programme, else inside the proportional bounds of the limit."""
        request = np.asarray(tau, dtype=float)[self.model.dof_index]
        if not np.any(request):
            return math.inf, np.zeros(self.model.m)
        conditions = self.in_force(faults, speed, voltage)
        low, high = conditions.low, conditions.high
        zero = np.zeros(self.model.n)
        solve = self._pseudo_inverse_limit if self.sides is None else self._linear_programme
        if power is None:
            return solve(request, zero, conditions, low, high)
        limit = power[1]
        bound = np.where(limit.limited, limit.bound, np.inf)
        low, high = np.clip(low, -bound, bound), np.clip(high, -bound, bound)
        if limit.rows is None or self.sides is None or not limit.rows.short().any():
            return solve(request, zero, conditions, low, high)
        self._power = limit.rows
        try:
            return solve(request, zero, conditions, low, high)
        finally:
            self._power = None

    def in_force(self, faults: Mapping[str, Fault | FaultMode] | FaultSet | None = None, speed: float | None = None,
                 voltage: float | None = None) -> Conditions:
        """What ``faults`` put in force at a surge speed and supply voltage (None: the analysis'
        speed, the nominal voltage), by the allocator's rule: the static force ranges, the sides
        of fixed thrusters a zone closes, the rotations with the flushing zones that follow the
        working thrusters and the [3.11.4] losses, inside the drive limits."""
        faults = faults if isinstance(faults, FaultSet) else FaultSet.of(self.vehicle, faults)
        conditions = Conditions.of(self.vehicle, faults, self.speed if speed is None else speed, voltage)
        return within_drive_limits(conditions, DrivePower.of(self.vehicle).degraded(faults.command_efficiency))

    def attains(self, tau, multiple: float, first: int = 0) -> tuple[bool, int]:
        """Whether ``multiple`` (> 0) times tau is attainable, as ``reach(tau)[0] >= multiple``,
        and the index of the combination of convex pieces that attains it (-1: none, or a method
        without pieces). Stops at the first combination that does, trying ``first`` before the
        others: the same answer as :meth:`reach` with fewer linear programmes."""
        request = np.asarray(tau, dtype=float)[self.model.dof_index]
        if self.sides is None or not np.any(request):
            return self.reach(tau)[0] >= multiple, -1
        conditions = self.in_force()
        low, high = conditions.low, conditions.high
        combinations = list(itertools.product(*(self._pieces(i, conditions, low[i], high[i]) for i in self.model.rot)))
        order = sorted(range(len(combinations)), key=lambda k: k != first)          # ``first`` first
        zero = np.zeros(self.model.n)
        for k in order:
            if self._solve(request, zero, low, high, combinations[k], self.sides)[0] >= multiple:
                return True, k
        return False, -1

    def combination_forces(self, tau, index: int) -> tuple[float, np.ndarray]:
        """(lambda, f) as :meth:`reach_forces` gives them (no power rule) where the ``index``-th
        combination of convex pieces (in :meth:`attains`' order) is the first that reaches
        furthest: its programme alone solved."""
        request = np.asarray(tau, dtype=float)[self.model.dof_index]
        conditions = self.in_force()
        low, high = conditions.low, conditions.high
        combinations = itertools.product(*(self._pieces(i, conditions, low[i], high[i]) for i in self.model.rot))
        pieces = next(itertools.islice(combinations, index, None))
        magnitude, force = self._solve(request, np.zeros(self.model.n), low, high, pieces, self.sides)
        return (magnitude, force) if magnitude > 0.0 else (0.0, np.zeros(self.model.m))

    def envelope(self, step_deg: float = 5.0, yaw_moment: float = 0.0,
                 faults: Mapping[str, Fault | FaultMode] | None = None) -> Envelope:
        directions = np.radians(np.arange(0.0, 360.0, step_deg))
        conditions = self.in_force(faults)
        points = np.array([self._max_point(angle, yaw_moment, conditions) for angle in directions])
        return Envelope(directions=directions, points=points)

    # -- one direction --------------------------------------------------------------------

    def _request(self, direction: float, yaw_moment: float) -> tuple[np.ndarray, np.ndarray]:
        """(unit request per unit of magnitude, fixed part) on the controlled DOFs."""
        unit = np.zeros(self.model.n)
        unit[self._plane_rows] = self.axis_scale * np.array([math.cos(direction), math.sin(direction)])
        fixed = np.zeros(self.model.n)
        if "yaw" in self.vehicle.dofs and "yaw" not in self.plane:
            fixed[list(self.vehicle.dofs).index("yaw")] = yaw_moment
        return unit, fixed

    def _max_point(self, direction: float, yaw_moment: float, conditions: Conditions) -> np.ndarray:
        unit, fixed = self._request(direction, yaw_moment)
        solve = self._pseudo_inverse_limit if self.sides is None else self._linear_programme
        magnitude = solve(unit, fixed, conditions, conditions.low, conditions.high)[0]
        return magnitude * self.axis_scale * np.array([math.cos(direction), math.sin(direction)])

    def _linear_programme(self, unit: np.ndarray, fixed: np.ndarray, conditions: Conditions, low: np.ndarray,
                          high: np.ndarray) -> tuple[float, np.ndarray]:
        """The largest magnitude over every combination of convex pieces (the zones and losses of
        ``conditions``, the ranges ``low``, ``high``), and its extended forces."""
        model = self.model
        choices = [self._pieces(i, conditions, low[i], high[i]) for i in model.rot]
        best, force = 0.0, np.zeros(model.m)
        for combination in itertools.product(*choices):
            magnitude, solution = self._solve(unit, fixed, low, high, combination, self.sides)
            if magnitude > best:
                best, force = magnitude, solution
        return best, force

    def available(self, name: str, angle: float) -> float:
        """The thrust [N] a rotatable thruster can give along ``angle`` [rad]: its profile's
        :meth:`~.thrust_profile.ForceProfile.available` of its range, else its ``thrust_max``."""
        actuator = self.vehicle.actuator(name)
        profile = self.profiles.get(name)
        if profile is None:
            return actuator.thrust_max
        return profile.available(angle, actuator.thrust_min, actuator.thrust_max)

    def _pieces(self, index: int, conditions: Conditions, low: float, high: float) -> list[tuple]:
        """The convex pieces of the ``index``-th actuator's forces with the zones and losses in force."""
        name = self.vehicle.actuators[index].name
        return thruster_pieces(conditions.rotations[index], conditions.faults.faults.get(name), low, high,
                       self.profiles.get(name), conditions.losses.get(index, ()))

    def _solve(self, unit, fixed, low, high, pieces, sides) -> tuple[float, np.ndarray]:
        """max F s.t. T_e f = F unit + fixed, boxes, and each rotatable force in its piece."""
        model = self.model
        cost, a_ub, b_ub, a_eq, bounds = self._constraints(unit, low, high, pieces, sides)
        result = self._programme(cost, a_ub, b_ub, a_eq, fixed, bounds, pieces)
        if not result.usable:
            return 0.0, np.zeros(model.m)
        return float(result.x[model.m]), result.x[:model.m]

    def _constraints(self, unit, low, high, pieces, sides) -> tuple:
        """(cost, inequality rows, their bounds, equality rows, column bounds) of :meth:`_solve`'s
        programme, with the power rows of ``self._power`` after lambda's column
        (:func:`.envelope_power.with_power_rows`); the equality rows' right-hand side is the
        fixed part of the request. Each inequality row of the pieces belongs to one rotatable
        thruster (its columns only) and its bound is the piece's radius times a number of the
        piece's shape, or 0."""
        model = self.model
        columns = model.m + 1
        bounds = [(None, None)] * model.m + [(0.0, None)]
        for i, column in zip(model.scalar, model.scalar_columns):
            bounds[column] = (low[i], high[i])
        a_ub, b_ub = [], []
        polygons = [(sides, self.apothem)]
        if self.apothem > math.cos(math.pi / sides) + 1e-12:       # reaches beyond the circle: cut by it
            polygons.append((CIRCLE_SIDES, math.cos(math.pi / CIRCLE_SIDES)))
        faces = [(math.cos(TWO_PI * k / count), math.sin(TWO_PI * k / count), apothem)
                 for count, apothem in polygons for k in range(count)]
        for (c1, c2), piece in zip(model.rot_columns, pieces):
            start, end, radius, line, chords = piece
            if radius <= 0.0:
                bounds[c1] = bounds[c2] = (0.0, 0.0)
                continue
            for nx, ny, apothem in () if line else faces:          # the method's polygon of the radius
                row = np.zeros(columns)
                row[c1], row[c2] = nx, ny
                a_ub.append(row)
                b_ub.append(radius * apothem)
            for angle, sign in ((start, -1.0), (end, 1.0)):         # the cone [start, end]
                row = np.zeros(columns)
                row[c1], row[c2] = sign * -math.sin(angle), sign * math.cos(angle)
                a_ub.append(row)
                b_ub.append(0.0)
                if line:
                    a_ub.append(-row)
                    b_ub.append(0.0)
            for nx, ny, offset in chords:                          # the profile's chords
                row = np.zeros(columns)
                row[c1], row[c2] = nx, ny
                a_ub.append(row)
                b_ub.append(radius * offset)
            if line:                                                # a stuck thruster: both ways
                continue
            middle = 0.5 * (start + end)
            row = np.zeros(columns)
            row[c1], row[c2] = -math.cos(middle), -math.sin(middle)
            a_ub.append(row)                                        # pointed: along the middle, not against
            b_ub.append(0.0)
        a_eq = np.hstack([model.t_ec, -unit.reshape(-1, 1)])
        cost = np.zeros(columns)
        cost[-1] = -1.0
        if self._power is not None:
            return with_power_rows(model, self._power, cost, a_ub, b_ub, a_eq, bounds)
        return cost, a_ub, b_ub, a_eq, bounds

    def _programme(self, cost, a_ub, b_ub, a_eq, b_eq, bounds, pieces) -> Solution:
        """:meth:`_solve`'s programme on HiGHS (a subclass may add rows, and columns after its own)."""
        return solve_linear_programme(cost, bounds, np.array(a_ub) if a_ub else None,
                                      np.array(b_ub) if b_ub else None, a_eq, b_eq)

    def _pseudo_inverse_limit(self, unit: np.ndarray, fixed: np.ndarray, conditions: Conditions, low: np.ndarray,
                              high: np.ndarray) -> tuple[float, np.ndarray]:
        """Largest F whose pseudo-inverse forces stay within every limit (the zones and losses of
        ``conditions``, the ranges ``low``, ``high``) (bisection), and those forces."""
        model, faults = self.model, conditions.faults
        excluded = (low == 0.0) & (high == 0.0)
        lines = {int(i): faults.stuck[int(i)] for i in model.rot if int(i) in faults.stuck}
        gain = PseudoInverseGains(model).gain(excluded, lines)

        def feasible(magnitude: float) -> bool:
            force = gain @ (magnitude * unit + fixed)
            if np.max(np.abs(model.t_ec @ force - magnitude * unit - fixed)) > 1e-6 * max(1.0, magnitude):
                return False
            for i, column in zip(model.scalar, model.scalar_columns):
                if not low[i] - 1e-9 <= force[column] <= high[i] + 1e-9:
                    return False
            for i, (c1, c2) in zip(model.rot, model.rot_columns):
                magnitude_i, angle = math.hypot(force[c1], force[c2]), math.atan2(force[c2], force[c1])
                loss = min((dead.factor(angle) for dead in conditions.losses.get(int(i), ())), default=1.0)
                if magnitude_i > max(high[i], -low[i]) * loss + 1e-9:
                    return False
                if magnitude_i > 1e-9 and not can_push_along(conditions.rotations[i], angle):
                    return False
            return True

        if not feasible(0.0):
            return 0.0, gain @ fixed
        upper = 2.0 * float(np.sum(np.maximum(high, -low) * np.abs(model.t_ec[:, model.starts]).max(axis=0)))
        lower = 0.0
        for _ in range(60):
            middle = 0.5 * (lower + upper)
            lower, upper = (middle, upper) if feasible(middle) else (lower, middle)
        return lower, gain @ (lower * unit + fixed)


def default_plane(vehicle: Vehicle) -> tuple[str, str]:
    """Surge and sway when both are controlled (the DP plot); else the first two controlled DOFs."""
    if "surge" in vehicle.dofs and "sway" in vehicle.dofs:
        return ("surge", "sway")
    if len(vehicle.dofs) < 2:
        raise ValueError("capability needs two controlled DOFs")
    return (vehicle.dofs[0], vehicle.dofs[1])


def region(vehicle: Vehicle, method: str) -> tuple:
    """What decides a method's capability: the polygon it puts on a rotatable thruster (sides and
    apothem; none on a vehicle without one), or None when it cannot redistribute force."""
    sides = METHODS[method].thrust_region_sides(vehicle)
    if sides is None:
        return (None,)
    if not vehicle.has_rotatable:
        return ("box",)
    return (sides, round(METHODS[method].thrust_region_apothem(vehicle), 12))


def reachable(vehicle: Vehicle) -> Vehicle:
    """``vehicle`` as far as what it can attain goes: the saturation mode and DOF priorities
    decide how an unattainable request is answered, and the thrust bias how an attainable one
    is, not what can be attained, so they are not held against a method here (a
    pseudo-inverse's reach with ``saturation: direct`` is :func:`region`'s)."""
    return replace(vehicle, saturation="weighted", priorities=(), bias=replace(vehicle.bias, enabled=False))


def unmodelled(method: str, vehicle: Vehicle) -> list[str]:
    """Why ``method``'s constraints cannot describe ``vehicle`` (its actuators, a file it
    needs); empty when they can (:func:`reachable`)."""
    return METHODS[method].problems(reachable(vehicle))


def differing_methods(vehicle: Vehicle, method: str) -> list[list[str]]:
    """Groups of the registered methods that can serve ``vehicle`` with the same capability,
    other than ``method``'s, each in registry order."""
    groups: dict[tuple, list[str]] = {}
    for name in METHODS:
        if not unmodelled(name, vehicle):
            groups.setdefault(region(vehicle, name), []).append(name)
    mine = region(vehicle, method)
    return [names for key, names in groups.items() if key != mine]
