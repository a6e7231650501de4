"""The allocator: state, faults and speed around one allocation method.

Each sample :meth:`Allocator.allocate` turns the requested generalised force into:

1. this sample's limits: thrust boxes scaled by faults and tightened by rate limits,
   control-surface ranges from the speed (1.48), and the allowed angles of every
   rotatable thruster (:func:`allocator_pkg.allocation.azimuth.plan`);
2. an extended force vector from the configured method (a key of ``METHODS``), or from the
   pseudo-inverse if the method fails;
3. thrust, angle and command of every actuator, inside every limit whatever the solver
   returned, with the drag of the control surfaces compensated (1.56)-(1.58): the surge
   request grows by the drag of the deflections and is solved again, until the drag settles;
4. a force that a linear or quadratic map's dead band cannot give snapped to zero or the
   band's edge, whichever is nearer;
5. the achieved wrench, the unallocated rest, saturation and limit flags, the power estimate.

The supply voltage (:meth:`Allocator.set_voltage`), like the speed and the faults, changes
values only: the command maps at that voltage and the thrust limits they leave, sent to the
running solver as new bounds.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from ..effectiveness.actuators import CommandMaps, command_map, deadband_forces, drag_gain
from ..effectiveness.configuration_matrix import configuration_matrix
from ..effectiveness.faults import Fault, FaultMode, FaultSet, lift_gains, static_ranges
from ..effectiveness.model import AzimuthLimits, Model, SampleLimits
from ..effectiveness.sectors import in_feasible_sector, surroundings
from ..methods import METHODS, AllocationMethod
from ..methods.pseudoinverse import PseudoInverseAllocation, PseudoInverseGains
from ..solvers import BACKENDS, DEFAULT_BACKEND, BackendFactory
from ..solvers.outcome import MethodOutput
from ..vehicle.angles import TWO_PI
from ..vehicle.config import DOF_NAMES, Vehicle
from .azimuth import AzimuthState, piece_in_question, plan, resolve
from .pieces import PiecePlanner

LIMIT_FRACTION = 1e-3
"""An actuator within this fraction of a limit sits at it (thrust range, rate step)."""

_SURGE = DOF_NAMES.index("surge")
PLANE = ("surge", "sway", "yaw")
"""The horizontal plane, in which a vehicle is under-actuated if its actuators cannot give
independent forces in all three."""

DRAG_PASSES = 4
"""Solves per sample for the drag feed-forward (1.56)-(1.58): the request plus the drag of the
last pass's deflections, until the drag stops changing (two or three passes in practice)."""


@dataclass(slots=True)
class AllocationResult:
    """One sample's answer; arrays are per actuator in configuration order. ``thrust``,
    ``azimuth``, ``mode``, ``available`` (and ``at_rate_limit`` of a vehicle without rate
    limits) are shared with the allocator and read-only.

    ``unallocated`` (6, [X, Y, Z, K, M, N]) is requested minus achieved in the controlled DOFs
    (0 in the others), what a controller needs for anti-windup; ``at_thrust_limit`` flags
    the actuators at an end of the force range in force (faults, voltage, speed),
    ``at_rate_limit`` those that moved their thrust (a control surface: its deflection) or
    their angle by a full rate step this sample."""

    thrust: np.ndarray
    azimuth: np.ndarray
    command: np.ndarray
    achieved: np.ndarray
    requested: np.ndarray
    saturated: bool
    status: str
    iterations: int
    solve_time: float
    power: float
    method: str
    mode: np.ndarray
    available: np.ndarray
    unallocated: np.ndarray
    at_thrust_limit: np.ndarray
    at_rate_limit: np.ndarray
    drag: float = 0.0


@dataclass
class AllocatorStats:
    """Counters since the allocator was made: solver set-ups, samples, fallbacks."""

    solver_setups: int = 0
    samples: int = 0
    fallbacks: int = 0


@dataclass
class _State:
    thrust: np.ndarray
    angle: np.ndarray
    deflection: np.ndarray
    azimuth: list[AzimuthState] = field(default_factory=list)


class Allocator:
    """Thrust allocation for one vehicle; see the module docstring for a sample's steps.

    ``method`` overrides the configuration's method, ``dt`` its sample time 1/rate_hz;
    ``backend`` names the QP solver behind the methods (a key of
    :data:`allocator_pkg.solvers.BACKENDS`) or is a backend factory.
    """

    def __init__(self, vehicle: Vehicle, method: str | None = None, dt: float | None = None,
                 backend: str | BackendFactory = DEFAULT_BACKEND):
        if method is not None and method not in METHODS:
            raise ValueError(f"unknown method '{method}'; choose from {', '.join(METHODS)}")
        _check_method(method or vehicle.method, vehicle)
        if dt is not None and not (math.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be a positive number of seconds, got {dt}")
        if isinstance(backend, str):
            if backend not in BACKENDS:
                raise ValueError(f"unknown backend '{backend}'; installed: {', '.join(BACKENDS)}")
            backend = BACKENDS[backend]
        self._method_override = method
        self._dt = dt
        self._backend = backend
        self._methods: dict[str, AllocationMethod] = {}
        self._retired_setups = 0
        self._speed = 0.0
        self._voltage: float | None = None
        self._version = 0
        self._stats = AllocatorStats()
        self._fault_set = FaultSet(vehicle)
        self._configure(vehicle)
        self.reset()

    # -- configuration ----------------------------------------------------------------

    @property
    def vehicle(self) -> Vehicle:
        return self._vehicle

    @property
    def names(self) -> tuple[str, ...]:
        return self._vehicle.names

    @property
    def dofs(self) -> tuple[str, ...]:
        return self._vehicle.dofs

    @property
    def method(self) -> str:
        return self._method.name

    @property
    def dt(self) -> float:
        return self._model.dt

    @property
    def faults(self) -> dict[str, Fault]:
        return dict(self._fault_set.faults)

    @property
    def fault_set(self) -> FaultSet:
        """The faults in force, validated, with their per-actuator arrays."""
        return self._fault_set

    @property
    def uncontrolled(self) -> tuple[str, ...]:
        """DOFs this configuration leaves to the vehicle (under-actuated or by choice)."""
        return tuple(d for d in DOF_NAMES if d not in self._vehicle.dofs)

    @property
    def warnings(self) -> list[str]:
        """What the configuration cannot do (DOFs out of reach), for the operator."""
        return list(self._warnings)

    @property
    def notes(self) -> list[str]:
        """What the operator should know but is by design (an under-actuated vehicle)."""
        return list(self._notes)

    @property
    def dof_tolerance(self) -> np.ndarray:
        """How far the achieved wrench may miss the request in each controlled DOF (``dofs``
        order) before a sample counts as saturated."""
        return self._model.dof_tolerance

    def check_reconfigure(self, vehicle: Vehicle) -> None:
        """Raise ValueError if :meth:`reconfigure` cannot take ``vehicle``."""
        old = self._vehicle
        if [(a.name, a.type) for a in vehicle.actuators] != [(a.name, a.type) for a in old.actuators]:
            raise ValueError("reconfigure keeps the actuators (names and types); build a new Allocator instead")
        _check_method(self._method_override or vehicle.method, vehicle)

    def reconfigure(self, vehicle: Vehicle) -> None:
        """Use a new configuration of the same actuators; state and faults carry over.

        Values on the same sparsity pattern update the running solver; only a change of
        structure (DOFs, polygon sides, saturation mode) sets one up again.
        """
        self.check_reconfigure(vehicle)
        if replace(self._vehicle, method=vehicle.method) == vehicle:
            self._vehicle = vehicle                 # another method, nothing else: switch to it
            self._choose_method(self._method_override or vehicle.method)
            return
        self._fault_set = self._fault_set.rebound(vehicle)
        self._configure(vehicle)
        angle = self._state.angle.copy()
        for state, i in zip(self._state.azimuth, self._model.rot):
            rotation = vehicle.actuators[i].rotation
            if not in_feasible_sector(rotation, state.angle):
                state.angle = angle[i] = min(max(state.angle, rotation.azimuth_min), rotation.azimuth_max)
        self._state.angle = angle

    def _configure(self, vehicle: Vehicle) -> None:
        previous = getattr(self, "_model", None)
        model = Model.build(vehicle, self._dt if self._dt is not None else 1.0 / vehicle.rate_hz)
        name = self._method_override or vehicle.method
        # a cached method goes with a new structure, or when it cannot serve the new vehicle
        # (it is set up again, with its reason checked, if chosen later)
        stale = [key for key, method in self._methods.items()
                 if method.structure != model.structure or METHODS[key].problems(vehicle)]
        for key in stale:
            self._retired_setups += self._methods.pop(key).setups
        self._inverse = PseudoInverseGains(model)
        self._fallback = PseudoInverseAllocation(model, self._backend, self._inverse)
        if getattr(self, "_planner", None) is None:
            self._planner = PiecePlanner(model)
        else:
            self._planner.update_model(model)
        self._model = model
        self._vehicle = vehicle
        self._choose_method(name)
        voltages = vehicle.voltage_range
        if self._voltage is None or (voltages is not None and not voltages[0] <= self._voltage <= voltages[1]):
            self._voltage = vehicle.nominal_voltage
        self._build_maps()
        edges = [(0.0, 0.0) if a.is_surface else deadband_forces(a.command) for a in vehicle.actuators]
        self._deadband_index = np.array([i for i, (low, high) in enumerate(edges) if high > 0.0], dtype=int)
        self._deadband_edges = np.array([edges[i] for i in self._deadband_index]).reshape(-1, 2)
        thrusters = ~np.isin(np.arange(model.r), model.surfaces)
        # (actuator, the change that counts as a full rate step) of each rate-limited one
        near = 1.0 - LIMIT_FRACTION
        self._thrust_rated = [(int(i), float(model.thrust_step[i]) * near)
                              for i in np.flatnonzero(thrusters & np.isfinite(model.thrust_step))]
        self._surface_rated = [(int(i), float(model.thrust_step[i]) * near)
                               for i in model.surfaces[np.isfinite(model.thrust_step[model.surfaces])]]
        self._angle_rated = [(int(i), float(model.angle_step[i]) * near) for i in model.rot
                             if math.isfinite(model.angle_step[i]) and model.angle_step[i] > 0.0]
        self._any_rated = bool(self._thrust_rated or self._surface_rated or self._angle_rated)
        self._never = np.zeros(model.r, dtype=bool)
        self._never.flags.writeable = False
        if previous is None or previous.vehicle.dofs != vehicle.dofs or not np.array_equal(previous.t_e, model.t_e):
            self._warnings = _reachability_warnings(model)      # rank tests: only the geometry decides
            self._notes = _actuation_notes(model)
        rows = np.flatnonzero(model.dof_index == _SURGE)
        self._drag_row = int(rows[0]) if rows.size and model.surfaces.size else None
        self._rate_limited = bool(np.isfinite(model.thrust_step).any())
        # Per-configuration constants of the per-sample path, as the types it reads fastest.
        self._dof_index = model.dof_index
        self._all_dofs = model.n == len(DOF_NAMES)
        self._t_e = model.t_e
        self._power = model.power.tolist()
        self._tolerance = self.dof_tolerance.tolist()
        self._rot_pairs = [(int(i), (int(c1), int(c2))) for i, (c1, c2) in zip(model.rot, model.rot_columns)]
        self._rotations = [vehicle.actuators[i].rotation for i in model.rot]
        self._continuous = [rotation.continuous for rotation in self._rotations]
        self._around: list = [None] * len(self._rotations)
        self._angle_step = model.angle_step.tolist()
        self._thrust_step_list = model.thrust_step.tolist()
        self._hold = model.hold.tolist()
        self._apply_speed()

    def _choose_method(self, name: str) -> None:
        """Use the method ``name``. Only the method in use follows each change; a cached one
        (whose solver pattern is all that decides whether it can serve) takes the current
        values when it is chosen again (its update_model, which also drops what it kept from
        the samples of its last use)."""
        method = self._methods.get(name)
        if method is None:
            method = self._methods[name] = METHODS[name](self._model, self._backend)
        elif method.model is not self._model or method is not getattr(self, "_method", None):
            method.update_model(self._model)
        self._method = method

    @property
    def stats(self) -> AllocatorStats:
        """Counters since the allocator was made (solver set-ups counted when read)."""
        self._stats.solver_setups = (self._retired_setups + self._planner.setups
                                     + sum(m.setups for m in self._methods.values()))
        return self._stats

    # -- state, speed and faults ------------------------------------------------------

    def reset(self) -> None:
        """Back to the start-up state: zero thrust, initial angles; faults are kept."""
        model = self._model
        angle = np.zeros(model.r)
        for i in model.rot:
            angle[i] = self._vehicle.actuators[i].rotation.initial
        self._state = _State(thrust=np.zeros(model.r), angle=angle, deflection=np.zeros(model.r),
                             azimuth=[AzimuthState(angle=float(angle[i])) for i in model.rot])

    @property
    def thrust(self) -> np.ndarray:
        return self._state.thrust.copy()

    @property
    def azimuth(self) -> np.ndarray:
        return self._state.angle.copy()

    @property
    def speed(self) -> float:
        return self._speed

    def set_speed(self, speed: float) -> None:
        """Surge speed [m/s] for the flow over control surfaces (1.48); values only."""
        speed = float(speed)
        if not math.isfinite(speed):
            raise ValueError(f"speed must be finite, got {speed}")
        self._speed = speed
        self._apply_speed()

    @property
    def voltage(self) -> float | None:
        """The supply voltage the command maps and thrust limits follow [V] (None: the
        configuration has no nominal_voltage)."""
        return self._voltage

    def set_voltage(self, volts: float) -> None:
        """Supply voltage [V]: tables measured at several voltages are interpolated at it and
        the thrust limits follow them; values only (new bounds for the running solver).
        Raises ValueError for a voltage that is not finite and positive or outside a table's
        voltages; nothing changes then."""
        volts = float(volts)
        if not (math.isfinite(volts) and volts > 0.0):
            raise ValueError(f"voltage must be finite and positive, got {volts}")
        covered = self._vehicle.voltage_range
        if covered is not None and not covered[0] <= volts <= covered[1]:
            raise ValueError(f"voltage {volts:g} V is outside the thrust tables ({covered[0]:g} to {covered[1]:g} V)")
        if volts == self._voltage:
            return
        self._voltage = volts
        if covered is not None:
            self._build_maps()
            self._refresh_ranges()

    def _build_maps(self) -> None:
        """The command maps at the current voltage: actuators with the same map share it (one
        vectorised call)."""
        maps: dict = {}
        actuators = self._vehicle.actuators
        self._maps = CommandMaps([None if a.is_surface else maps.setdefault(a.command, command_map(a.command,
                                                                                                  self._voltage))
                                  for a in actuators], [not a.is_surface and a.command.reversed for a in actuators])

    @property
    def ranges(self) -> tuple[np.ndarray, np.ndarray]:
        """Signed force range [low, high] of every actuator in force (faults, speed and voltage;
        before rate limits)."""
        return self._range_low.copy(), self._range_high.copy()

    def _apply_speed(self) -> None:
        v = self._vehicle
        self._lift = lift_gains(v, self._speed)
        self._lift_list = self._lift.tolist()
        self._drag = np.array([drag_gain(a.surface, v.water_density, self._speed) if a.is_surface else 0.0
                               for a in v.actuators])
        self._refresh_ranges()

    def set_fault(self, name: str, mode: FaultMode | int, efficiency: float | None = None,
                  angle: float | None = None) -> None:
        """Set one actuator's fault; it applies from the next sample. Raises ValueError
        (naming the valid choices) for an unknown actuator or mode, an efficiency outside
        (0, 1], or STUCK on an actuator that cannot be stuck or at an angle it cannot take;
        nothing changes then. ``angle`` is the azimuth or deflection [rad] of STUCK."""
        self._fault_set = self._fault_set.with_fault(name, mode, efficiency, angle)
        self._refresh_ranges()

    def clear_faults(self) -> None:
        """Every actuator back to NOMINAL."""
        self._fault_set = self._fault_set.cleared()
        self._refresh_ranges()

    def modes(self) -> np.ndarray:
        """FaultMode of every actuator, configuration order."""
        return self._fault_set.modes.copy()

    def configuration_matrix(self, azimuth: Sequence[float] | None = None) -> np.ndarray:
        """T(alpha), 6 x r, at the given angles or the current ones."""
        angles = self._state.angle if azimuth is None else np.asarray(azimuth, dtype=float)
        if angles.shape != (self._model.r,):
            raise ValueError(f"azimuth needs {self._model.r} angles, got shape {angles.shape}")
        return configuration_matrix(self._vehicle.actuators, angles)

    # -- one sample -------------------------------------------------------------------

    def allocate(self, tau: Sequence[float]) -> AllocationResult:
        """Allocate the generalised force [X, Y, Z, K, M, N]; uncontrolled DOFs are ignored."""
        requested = np.array(tau, dtype=float)
        if requested.shape != (6,):
            requested = requested.reshape(-1)
            if requested.shape != (6,):
                raise ValueError(f"tau needs 6 components [X, Y, Z, K, M, N], got {requested.size}")
        if not all(map(math.isfinite, requested.tolist())):
            raise ValueError(f"tau must be finite, got {requested.tolist()}")
        start = time.perf_counter()
        tau_c = requested if self._all_dofs else requested[self._dof_index]
        limits = self._limits(tau_c)
        output = self._solve(tau_c, limits)
        thrust, angle, extended = self._resolve(output, limits)
        drag = 0.0
        if self._drag_row is not None:
            output, thrust, angle, extended, drag = self._compensate_drag(tau_c, limits, output, thrust, angle,
                                                                          extended)
        if self._deadband_index.size:
            self._snap_deadband(thrust, extended, limits)
        achieved = self._t_e @ extended
        if drag:
            achieved[_SURGE] -= drag
        miss = (achieved if self._all_dofs else achieved[self._dof_index]) - tau_c
        saturated = any(abs(m) > tolerance for m, tolerance in zip(miss.tolist(), self._tolerance))
        if self._all_dofs:
            unallocated = -miss
        else:
            unallocated = np.zeros(6)
            unallocated[self._dof_index] = -miss
        command = self._maps.commands(thrust, self._command_efficiency, self._lift)
        at_thrust, at_rate = self._limit_flags(thrust, angle)
        self._commit(thrust, angle)
        self._stats.samples += 1
        return AllocationResult(thrust, angle, command, achieved, requested, saturated, output.status,
                                output.iterations, time.perf_counter() - start,
                                sum(p * abs(t) ** 1.5 for p, t in zip(self._power, thrust.tolist())),
                                self._method.name, self._fault_set.modes, self._availability, unallocated, at_thrust,
                                at_rate, drag)

    def stop(self) -> AllocationResult:
        """Zero thrust at once, angles held (watchdog and shutdown); bypasses rate limits."""
        thrust = np.zeros(self._model.r)
        angle = self._state.angle
        command = self._maps.commands(thrust, self._command_efficiency, self._lift)
        self._commit(thrust, angle)
        return AllocationResult(thrust, angle, command, np.zeros(6), np.zeros(6), False, "stopped", 0, 0.0, 0.0,
                                self._method.name, self._fault_set.modes, self._availability, np.zeros(6),
                                np.zeros(self._model.r, dtype=bool), np.zeros(self._model.r, dtype=bool))

    def _refresh_ranges(self) -> None:
        """What faults and speed decide, computed when they change (never per sample): the
        static force ranges, availability, the pseudo-inverse gain used to plan rotatable
        thrusters, and the limits of a vehicle whose limits never change between samples."""
        model = self._model
        self._range_low, self._range_high = static_ranges(self._vehicle, self._fault_set, self._speed, self._voltage)
        if self._deadband_index.size:
            self._deadband = self._deadband_edges * self._fault_set.command_efficiency[self._deadband_index, None]
        # Where a thrust counts as at its limit (an end of zero is no limit to report).
        self._at_high = np.where(self._range_high > 0.0, self._range_high * (1.0 - LIMIT_FRACTION), np.inf)
        self._at_low = np.where(self._range_low < 0.0, self._range_low * (1.0 - LIMIT_FRACTION), -np.inf)
        self._range_low_list, self._range_high_list = self._range_low.tolist(), self._range_high.tolist()
        available = self._fault_set.efficiency > 0.0
        available[model.surfaces] &= self._lift[model.surfaces] > 0.0
        available.flags.writeable = False
        self._availability = available
        self._fault_set.modes.flags.writeable = False
        efficiency = self._fault_set.command_efficiency
        self._command_efficiency = None if np.all(efficiency == 1.0) else efficiency
        self._version += 1
        if model.rot.size:
            excluded = (self._range_low == 0.0) & (self._range_high == 0.0)
            self._desired_gain = self._inverse.gain(excluded, {})
        if model.surfaces.size:
            lift = self._lift[model.surfaces]
            self._surface_step = np.multiply(lift, model.thrust_step[model.surfaces], out=np.zeros(lift.size),
                                             where=lift > 0.0)
        self._static = None if (model.rot.size or model.surfaces.size or self._rate_limited) else SampleLimits(
            self._range_low, self._range_high, model.rot, [], np.zeros(model.r), np.zeros(model.r), self._version,
            self._range_low, self._range_high)

    def _limits(self, tau: np.ndarray) -> SampleLimits:
        state = self._state
        if self._static is not None:
            self._static.angle, self._static.thrust = state.angle, state.thrust
            return self._static
        model = self._model
        range_low, range_high = self._range_low, self._range_high
        previous, step = state.thrust, model.thrust_step
        surfaces = model.surfaces
        if surfaces.size:
            previous = previous.copy()
            previous[surfaces] = self._lift[surfaces] * state.deflection[surfaces]
            step = step.copy()
            step[surfaces] = self._surface_step
        low = np.minimum(np.maximum(previous - step, range_low), range_high)
        high = np.minimum(np.maximum(previous + step, range_low), range_high)
        azimuth: list[AzimuthLimits] = []
        if model.rot.size:
            stuck = self._fault_set.stuck
            desired = (self._desired_gain @ tau).tolist()
            wanted = {i: (desired[c1], desired[c2]) for i, (c1, c2) in self._rot_pairs}
            around = self._surroundings()
            wanted.update(self._planned(tau, wanted, stuck, around))
            for state_k, (i, _), rotation, around_k in zip(state.azimuth, self._rot_pairs, self._rotations, around):
                limits_k = plan(rotation, state_k, self._angle_step[i], (self._range_low_list[i],
                                self._range_high_list[i]), self._thrust_step_list[i], wanted[i], self._hold[i],
                                stuck.get(i), around_k)
                azimuth.append(limits_k)
                low[i], high[i] = limits_k.thrust_low, limits_k.thrust_high
        return SampleLimits(low, high, model.rot, azimuth, state.angle, state.thrust, range_low=range_low,
                            range_high=range_high)

    def _surroundings(self) -> list:
        """Each rotatable thruster's `sectors.surroundings`, kept while its angle stays."""
        cache = self._around
        for k, (state_k, rotation) in enumerate(zip(self._state.azimuth, self._rotations)):
            if cache[k] is None or cache[k][0] != state_k.angle:
                cache[k] = (state_k.angle, surroundings(rotation, state_k.angle))
        return [entry[1] for entry in cache]

    def _planned(self, tau: np.ndarray, wanted: dict[int, tuple[float, float]], stuck: dict[int, float],
                 around: list) -> dict[int, tuple[float, float]]:
        """Where the piece planner sends each rotatable thruster, when some thruster's side of
        a forbidden sector (or the feasible sector's end) is in question, and while a crossing
        it decided is under way; else nothing (the pseudo-inverse's wish stands)."""
        planner = self._planner
        if not planner.needed:
            return {}
        state = self._state
        question = any(
            i not in stuck and self._range_high_list[i] > self._range_low_list[i] and not state_k.turning
            and piece_in_question(rotation, state_k.angle, self._angle_step[i], wanted[i], self._hold[i], around_k)
            for state_k, (i, _), rotation, around_k in zip(state.azimuth, self._rot_pairs, self._rotations, around))
        if question:
            return planner.targets(tau, self._range_low, self._range_high, stuck, state.angle)
        if any(state_k.turning for state_k in state.azimuth):
            return planner.last_targets
        return {}

    def _solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        output = self._method.solve(tau, limits)
        if not output.solved:
            self._stats.fallbacks += 1
            fallback = self._fallback.solve(tau, limits)
            fallback.status = f"fallback: pseudoinverse ({output.status})"
            fallback.iterations = output.iterations
            output = fallback
        return output

    def _resolve(self, output: MethodOutput, limits: SampleLimits) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Per-actuator thrust and angle from the extended force, inside every limit, and the
        extended force (1.18) they give."""
        model = self._model
        if not model.rot.size:
            thrust = np.minimum(np.maximum(output.force, limits.low), limits.high)
            return thrust, limits.angle, thrust
        force = output.force
        thrust = np.minimum(np.maximum(force[model.starts], limits.low), limits.high)
        angle = limits.angle.copy()
        extended = thrust[model.extended_owner]
        proposals, turns = output.angle, output.turn or {}
        for k, (i, (c1, c2)) in enumerate(self._rot_pairs):
            thrust_i, angle_i = resolve(limits.azimuth[k], float(angle[i]), (float(force[c1]), float(force[c2])),
                                        self._hold[i], self._continuous[k],
                                        None if proposals is None else float(proposals[i]), turns.get(i))
            thrust[i], angle[i] = thrust_i, angle_i
            extended[c1], extended[c2] = thrust_i * math.cos(angle_i), thrust_i * math.sin(angle_i)
        return thrust, angle, extended

    def _compensate_drag(self, tau: np.ndarray, limits: SampleLimits, output: MethodOutput, thrust: np.ndarray,
                         angle: np.ndarray, extended: np.ndarray):
        """The drag feed-forward (1.56)-(1.58): solve again with the surge request grown by the
        drag of the last pass's deflections until the drag settles."""
        drag = 0.0
        surge = self._drag_row
        for _ in range(DRAG_PASSES):
            new_drag = self._surface_drag(thrust)
            if abs(new_drag - drag) <= 1e-9 * max(1.0, abs(tau[surge])):
                break
            drag = new_drag
            compensated = tau.copy()
            compensated[surge] += drag
            again = self._solve(compensated, limits)
            again.iterations += output.iterations
            output = again
            thrust, angle, extended = self._resolve(output, limits)
        return output, thrust, angle, extended, self._surface_drag(thrust)

    def _snap_deadband(self, thrust: np.ndarray, extended: np.ndarray, limits: SampleLimits) -> None:
        """A force inside a dead band (between zero and the force at the band's edge) cannot
        be commanded: it becomes zero or the edge, whichever is nearer and within this
        sample's limits (zero when neither is, or on a tie). In place, the extended force
        with it."""
        index = self._deadband_index
        force = thrust[index]
        low_edge, high_edge = self._deadband[:, 0], self._deadband[:, 1]
        inside = (force != 0.0) & (force > low_edge) & (force < high_edge)
        if not inside.any():
            return
        model = self._model
        for k in np.flatnonzero(inside):
            i = int(index[k])
            f = float(force[k])
            edge = float(high_edge[k] if f > 0.0 else low_edge[k])
            fits = limits.low[i] - 1e-12 <= edge <= limits.high[i] + 1e-12
            new = edge if fits and abs(edge - f) < abs(f) else 0.0
            thrust[i] = new
            start = int(model.starts[i])
            if model.rotatable[i]:
                extended[start:start + 2] *= new / f
            else:
                extended[start] = new

    def _limit_flags(self, thrust: np.ndarray, angle: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Which actuators sit at an end of their force range in force, and which moved by a
        full rate step (thrust, a control surface's deflection, or angle) this sample."""
        at_thrust = (thrust >= self._at_high) | (thrust <= self._at_low)
        if not self._any_rated:
            return at_thrust, self._never
        state = self._state
        now, before = thrust.tolist(), state.thrust.tolist()
        at_rate = [False] * len(now)
        for i, step in self._thrust_rated:
            at_rate[i] = abs(now[i] - before[i]) >= step
        if self._surface_rated:
            lift, deflection = self._lift_list, state.deflection.tolist()
            for i, step in self._surface_rated:
                at_rate[i] = abs((now[i] / lift[i] if lift[i] > 0.0 else 0.0) - deflection[i]) >= step
        if self._angle_rated:
            turned_to, turned_from = angle.tolist(), state.angle.tolist()
            for i, step in self._angle_rated:
                at_rate[i] = at_rate[i] or abs(math.remainder(turned_to[i] - turned_from[i], TWO_PI)) >= step
        return at_thrust, np.array(at_rate)

    def _surface_drag(self, thrust: np.ndarray) -> float:
        """X_cs of (1.57): the added resistance of all deflected control surfaces."""
        surfaces = self._model.surfaces
        lift = self._lift[surfaces]
        deflection = np.divide(thrust[surfaces], lift, out=np.zeros(surfaces.size), where=lift > 0.0)
        return float(np.sum(self._drag[surfaces] * deflection * deflection))

    def _commit(self, thrust: np.ndarray, angle: np.ndarray) -> None:
        """This sample's thrust and angles become the state (shared with the result, so both
        are made read-only)."""
        state = self._state
        model = self._model
        thrust.setflags(write=False)
        angle.setflags(write=False)
        state.thrust, state.angle = thrust, angle
        surfaces = model.surfaces
        if surfaces.size:
            lift = self._lift[surfaces]
            state.deflection[surfaces] = np.divide(thrust[surfaces], lift, out=np.zeros(surfaces.size),
                                                   where=lift > 0.0)
        for azimuth_state, (i, _) in zip(state.azimuth, self._rot_pairs):
            azimuth_state.angle = float(angle[i])
            azimuth_state.thrust = float(thrust[i])


def _check_method(method: str, vehicle: Vehicle) -> None:
    """Raise ValueError when ``method`` cannot serve ``vehicle`` (its reasons) or the vehicle
    orders its DOFs and the method does not implement it."""
    unfit = METHODS[method].problems(vehicle)
    if unfit:
        raise ValueError(f"method '{method}' cannot serve this vehicle: {'; '.join(unfit)}")
    if vehicle.priority_levels and not METHODS[method].implements_priorities:
        able = ", ".join(name for name, kind in METHODS.items() if kind.implements_priorities)
        raise ValueError(f"priorities: method '{method}' does not implement DOF priorities; methods that do: {able}")


def _reachability_warnings(model: Model) -> list[str]:
    """Controlled DOFs, or combinations of them, that no actuator can produce."""
    warnings = []
    dofs = model.vehicle.dofs
    for k, dof in enumerate(dofs):
        if not np.any(np.abs(model.t_ec[k]) > 1e-12):
            warnings.append(f"no actuator can produce {dof}; requests in it will always be saturated")
    rank = np.linalg.matrix_rank(model.t_ec, tol=1e-9)
    if rank < model.n and not warnings:
        warnings.append(f"the actuators reach only {rank} independent directions of the {model.n} controlled DOFs "
                        f"({', '.join(dofs)}); some combinations will be saturated")
    return warnings


def _actuation_notes(model: Model) -> list[str]:
    """Whether the actuators give independent forces in surge, sway and yaw, the plane every
    marine vehicle moves in; if not, and the configuration leaves some of them to the vehicle,
    it is under-actuated by design (a controlled DOF out of reach is a warning instead)."""
    left = [dof for dof in PLANE if dof not in model.vehicle.dofs]
    plane = [DOF_NAMES.index(dof) for dof in PLANE]
    rank = int(np.linalg.matrix_rank(model.t_e[plane], tol=1e-9))
    if not left or rank == len(plane):
        return []
    return [f"under-actuated: the actuators give {rank} independent directions in {', '.join(PLANE)}; "
            f"{', '.join(left)} is left to the vehicle's dynamics"]
