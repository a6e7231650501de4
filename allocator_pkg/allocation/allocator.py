"""The allocator: state, faults, speed and voltage around one allocation method.

Each sample :meth:`Allocator.allocate` runs the pipeline

1. request check: six finite components, the controlled ones taken;
2. limits (:class:`~.limits.LimitsStage`): thrust boxes scaled by faults and tightened by rate
   limits, control-surface ranges from the speed (1.48), the allowed angles of every rotatable
   thruster (:func:`~.azimuth.plan`);
3. solve (:class:`~.solve.MethodStage`): the extended force vector from the configured method
   (a key of ``METHODS``), or from the pseudo-inverse if the method fails, with the drag of
   the control surfaces fed forward (1.56)-(1.58);
4. actuation (:class:`~.actuation.ActuationStage`): thrust, angle and command of every
   actuator inside every limit, dead bands, the achieved wrench, the rest, flags and power;
5. commit: the thrust and angles become the state the next sample starts from.

Each stage is given what it needs once per configuration (the ``PseudoInverseGains`` that the
fallback and the azimuth planning share) and once per change of speed, voltage, faults, power or
bus ties (the :class:`~.conditions.Conditions`: static ranges inside the drive limits, lift and
drag gains), never per sample: values only, new bounds for the running solver.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import replace

import numpy as np

from ..effectiveness.configuration_matrix import configuration_matrix
from ..effectiveness.faults import Fault, FaultMode, FaultSet
from ..effectiveness.model import Model
from ..effectiveness.reach import actuation_notes, lost_reach, reachability_warnings
from ..effectiveness.sectors import in_feasible_sector
from ..effectiveness.weighted_inverse import PseudoInverseGains
from ..methods import METHODS
from ..solvers import BACKENDS, DEFAULT_BACKEND, BackendFactory
from ..solvers.outcome import Outcome
from ..vehicle.config import DOF_NAMES, Vehicle
from .actuation import ActuationStage
from .conditions import Conditions
from .drive_power import within_drive_limits
from .limits import LimitsStage
from .power_budget import PowerBudget, PowerLimit
from .power_stage import PowerStage
from .request import checked_request
from .result import AllocationResult, AllocatorStats
from .solve import MethodStage, check_method
from .state import ActuatorState


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
        check_method(method or vehicle.method, vehicle)
        if dt is not None and not (math.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be a positive number of seconds, got {dt}")
        if isinstance(backend, str):
            if backend not in BACKENDS:
                raise ValueError(f"unknown backend '{backend}'; installed: {', '.join(BACKENDS)}")
            backend = BACKENDS[backend]
        self._method_override = method
        self._dt = dt
        self._solver = MethodStage(backend)
        self._speed = 0.0
        self._voltage: float | None = None
        self._samples = 0
        self._fault_set = FaultSet(vehicle)
        self._power = PowerBudget(vehicle)
        self._groups: tuple[str, ...] = ()
        self._configure(vehicle)
        self.reset()

    # -- configuration ----------------------------------------------------------------

    @property
    def vehicle(self) -> Vehicle:
        return self._vehicle

    @property
    def model(self) -> Model:
        """The configuration as arrays (read-only)."""
        return self._model

    @property
    def names(self) -> tuple[str, ...]:
        return self._vehicle.names

    @property
    def dofs(self) -> tuple[str, ...]:
        return self._vehicle.dofs

    @property
    def method(self) -> str:
        return self._solver.method.name

    @property
    def dt(self) -> float:
        return self._model.dt

    @property
    def uncontrolled(self) -> tuple[str, ...]:
        """DOFs this configuration leaves to the vehicle (under-actuated or by choice)."""
        return tuple(d for d in DOF_NAMES if d not in self._vehicle.dofs)

    @property
    def warnings(self) -> list[str]:
        """What the configuration cannot do (DOFs out of reach), for the operator."""
        return list(self._warnings)

    @property
    def lost_reach(self) -> list[str]:
        """What the faults in force took: the controlled DOFs, and combinations of them, the
        working actuators no longer reach (empty: none), computed when the faults or the
        configuration change."""
        return list(self._lost_reach)

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
        check_method(self._method_override or vehicle.method, vehicle)

    def reconfigure(self, vehicle: Vehicle) -> None:
        """Use a new configuration of the same actuators; state and faults carry over.

        Values on the same sparsity pattern update the running solver; only a change of
        structure (DOFs, polygon sides, saturation mode) sets one up again.
        """
        self.check_reconfigure(vehicle)
        if replace(self._vehicle, method=vehicle.method) == vehicle:
            self._vehicle = vehicle                 # another method, nothing else: switch to it
            self._solver.choose(self._method_override or vehicle.method)
            self._refresh()                         # its power: rows, or the proportional bounds
            return
        self._fault_set = self._fault_set.rebound(vehicle)
        self._power = self._power.rebound(vehicle)
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
        inverse = PseudoInverseGains(model)
        self._solver.configure(model, self._method_override or vehicle.method, inverse)
        if previous is None:
            self._limits, self._actuation = LimitsStage(model, inverse), ActuationStage(model)
            self._share = PowerStage(model)
        else:
            self._limits.configure(model, inverse)
            self._actuation.configure(model)
            self._share.configure(model)
        self._model, self._vehicle = model, vehicle
        voltages = vehicle.voltage_range
        if self._voltage is None or (voltages is not None and not voltages[0] <= self._voltage <= voltages[1]):
            self._voltage = vehicle.nominal_voltage
        self._actuation.set_voltage(self._voltage)
        if previous is None or previous.vehicle.dofs != vehicle.dofs or not np.array_equal(previous.t_e, model.t_e):
            self._warnings = reachability_warnings(model)      # rank tests: only the geometry decides
            self._notes = actuation_notes(model)
        self._lost_reach = lost_reach(model, self._fault_set)
        self._refresh()

    @property
    def stats(self) -> AllocatorStats:
        """Counters since the allocator was made (read from the stages when asked)."""
        return AllocatorStats(solver_setups=self._limits.planner.setups + self._solver.setups,
                              samples=self._samples, fallbacks=self._solver.fallbacks)

    # -- state, speed, voltage and faults --------------------------------------------

    def reset(self) -> None:
        """Back to the start-up state: zero thrust, initial angles; faults are kept."""
        self._state = ActuatorState.at_start(self._model)

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
        self._refresh()

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
            self._actuation.set_voltage(volts)
            self._refresh()

    @property
    def faults(self) -> dict[str, Fault]:
        return dict(self._fault_set.faults)

    @property
    def fault_set(self) -> FaultSet:
        """The faults in force, validated, with their per-actuator arrays."""
        return self._fault_set

    def set_fault(self, name: str, mode: FaultMode | int, efficiency: float | None = None,
                  angle: float | None = None) -> None:
        """Set one actuator's fault; it applies from the next sample. Raises ValueError
        (naming the valid choices) for an unknown actuator or mode, an efficiency outside
        (0, 1], or STUCK on an actuator that cannot be stuck or at an angle it cannot take;
        nothing changes then. ``angle`` is the azimuth or deflection [rad] of STUCK."""
        self._fault_set = self._fault_set.with_fault(name, mode, efficiency, angle)
        self._faults_changed()

    def clear_faults(self) -> None:
        """Every actuator back to NOMINAL; the sources of failed redundancy groups back to their
        available power."""
        self._fault_set = self._fault_set.cleared()
        self._power.lost, self._groups = frozenset(), ()
        self._faults_changed()

    def modes(self) -> np.ndarray:
        """FaultMode of every actuator, configuration order."""
        return self._fault_set.modes.copy()

    # -- power per source (allocation/power_budget.py, docs/power.md) ---------------------

    @property
    def power(self) -> PowerBudget:
        """The power sources, feeds and the available power in force (read-only)."""
        return self._power

    @property
    def power_limit(self) -> PowerLimit | None:
        """The power rule in force (None: no sources): the feed weights, the power rows of a
        method that solves with them, the thrust bounds the power sets in the ranges."""
        return self._share.limit

    @property
    def power_bounds(self) -> np.ndarray | None:
        """The thrust bounds [N] the power sets in the ranges (None: no sources): the
        proportional ones for a method without power rows, the derating of a lost feed with
        them (the rows then keep each source within its power)."""
        return self._share.bound

    def set_available_power(self, available: Mapping[str, float]) -> None:
        """Available power [kW] of the sources named, from the next sample (a source a group
        fault took stays at 0). Raises ValueError for an unknown source or a value that is not
        finite and >= 0; nothing changes then. The same values again change nothing."""
        if self._power.report(available):
            self._refresh()

    def reset_available_power(self) -> None:
        """Every source back to its configured capacity."""
        self._power.reported = self._power.capacity.copy()
        self._refresh()

    def set_bus_tie(self, name: str, closed: bool) -> str:
        """Open or close the bus tie ``name`` from the next sample (allocation/bus_ties.py): the reply;
        ValueError naming the ties for an unknown one, nothing changed."""
        if self._power.ties.set(name, closed):
            self._refresh()
        return self._power.ties.reply(name)

    @property
    def group_faults(self) -> tuple[str, ...]:
        """The redundancy groups failed, in the order they failed."""
        return self._groups

    def set_group_fault(self, group: str) -> None:
        """Fail a redundancy group from the next sample: its actuators FAILED, its sources at
        0 kW until :meth:`clear_faults`. Raises ValueError naming the groups for an unknown one."""
        members = self._power.group(group)
        fault_set = self._fault_set
        for name in members.actuators:
            fault_set = fault_set.with_fault(name, FaultMode.FAILED)
        self._fault_set = fault_set
        self._power.lost |= set(members.sources)
        self._groups += () if group in self._groups else (group,)
        self._faults_changed()

    def _faults_changed(self) -> None:
        """The reach the new faults leave (:attr:`lost_reach`), then every stage refreshed."""
        self._lost_reach = lost_reach(self._model, self._fault_set)
        self._refresh()

    def _refresh(self) -> None:
        """What faults, speed, voltage and available power decide, computed once and given to
        every stage."""
        conditions = Conditions.of(self._model.vehicle, self._fault_set, self._speed, self._voltage)
        self._power.settle(self._fault_set.command_efficiency)
        conditions = within_drive_limits(conditions, self._power.in_force)
        state = getattr(self, "_state", None)
        conditions = self._share.refresh(self._power, conditions, None if state is None else state.thrust,
                                         self._model.vehicle.power_phase_back, self._solver.method.power_rows)
        self._conditions = conditions
        self._limits.refresh(conditions)
        self._solver.refresh(conditions)
        self._actuation.refresh(conditions)

    @property
    def ranges(self) -> tuple[np.ndarray, np.ndarray]:
        """Signed force range [low, high] of every actuator in force (faults, speed and voltage;
        before rate limits)."""
        return self._conditions.low.copy(), self._conditions.high.copy()

    def configuration_matrix(self, azimuth: Sequence[float] | None = None) -> np.ndarray:
        """T(alpha), 6 x r, at the given angles or the current ones."""
        angles = self._state.angle if azimuth is None else np.asarray(azimuth, dtype=float)
        if angles.shape != (self._model.r,):
            raise ValueError(f"azimuth needs {self._model.r} angles, got shape {angles.shape}")
        return configuration_matrix(self._vehicle.actuators, angles)

    # -- one sample -------------------------------------------------------------------

    def allocate(self, tau: Sequence[float]) -> AllocationResult:
        """Allocate the generalised force [X, Y, Z, K, M, N]; uncontrolled DOFs are ignored."""
        requested = checked_request(tau)
        start = time.perf_counter()
        model, state, share = self._model, self._state, self._share
        controlled = requested if model.n == len(DOF_NAMES) else requested[model.dof_index]
        if self._power.advance(model.dt):       # power.restore_ramp: the power in use rises a sample's worth
            self._refresh()
        if share.ramping_sources is not None:           # power.phase_back false: down at the rate limit
            self._solver.set_power(share.ramp_rows(state.thrust))
        elif share.ramping_actuators is not None:
            conditions = share.ramp(state.thrust)
            self._limits.refresh(conditions)
            self._actuation.refresh(conditions)
        limits = self._limits.sample(controlled, state)
        if share.opening is not None:                   # a drop of power wins over the rate limit
            limits = share.opened(limits)
        output, drag = self._solver.solve(controlled, limits)
        if output.outcome is Outcome.FALLBACK:          # actuated inside the bounds it answered in
            limits = self._solver.fallback_limits(limits)
        result = self._actuation.actuate(requested, controlled, limits, output, drag, state,
                                         self._solver.method.name, start)
        state.commit(model, result.thrust, result.azimuth, self._conditions.lift)
        self._samples += 1
        return result

    def stop(self) -> AllocationResult:
        """Zero thrust at once, angles held (watchdog and shutdown); bypasses rate limits."""
        result = self._actuation.stop(self._state, self._solver.method.name)
        self._state.commit(self._model, result.thrust, result.azimuth, self._conditions.lift)
        return result

