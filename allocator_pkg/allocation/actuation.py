"""The actuation stage of a sample: from the method stage's extended force to what each
actuator is commanded, and what that gives: the sample's :class:`~.result.AllocationResult`.

Thrust and angle of every actuator inside every limit whatever the solver returned
(:func:`~allocator_pkg.effectiveness.resolve.resolve` and a clip); a force inside a dead band
snapped to zero or the band's edge; command maps to set-points (a reversed thruster's
mirrored); the achieved wrench from T_e of what is commanded, less the surge drag of the
control surfaces the method stage fed forward (1.56)-(1.58); the unallocated rest, the DOFs
short, the limit flags and the power estimate (1.44; each drive's forward or reverse coefficient,
a DEGRADED one's power on its set-point: :mod:`.drive_power`). A thruster pushing onto a dead one is
commanded the thrust that gives its force after the [3.11.4] loss."""

from __future__ import annotations

import math
import time

import numpy as np

from ..effectiveness.actuators import CommandMaps, command_map, deadband_forces
from ..effectiveness.model import AT_LIMIT, Model, SampleLimits
from ..effectiveness.resolve import resolve
from ..methods.base import MethodOutput
from ..solvers.outcome import Outcome
from ..vehicle.angles import TWO_PI
from ..vehicle.config import DOF_NAMES
from .conditions import Conditions
from .drive_power import DrivePower
from .result import AllocationResult
from .state import ActuatorState

SURGE = DOF_NAMES.index("surge")

DEADBAND_EDGE = 1e-12
"""[N] Rounding allowed when a dead band's edge is checked against this sample's limits."""


class ActuationStage:
    """Per-configuration constants and the values that speed, voltage and faults decide, and
    one sample's :meth:`actuate`."""

    def __init__(self, model: Model):
        self.configure(model)

    def configure(self, model: Model) -> None:
        """Per-configuration constants, as the types the per-sample path reads fastest."""
        self.model = model
        vehicle = model.vehicle
        edges = [(0.0, 0.0) if a.is_surface else deadband_forces(a.command) for a in vehicle.actuators]
        self._deadband_index = np.array([i for i, (low, high) in enumerate(edges) if high > 0.0], dtype=int)
        self._deadband_edges = np.array([edges[i] for i in self._deadband_index]).reshape(-1, 2)
        near = 1.0 - AT_LIMIT
        thrusters = ~np.isin(np.arange(model.r), model.surfaces)
        self._thrust_rated = [(int(i), float(model.thrust_step[i]) * near)
                              for i in np.flatnonzero(thrusters & np.isfinite(model.thrust_step))]
        self._surface_rated = [(int(i), float(model.thrust_step[i]) * near)
                               for i in model.surfaces[np.isfinite(model.thrust_step[model.surfaces])]]
        self._angle_rated = [(int(i), float(model.angle_step[i]) * near) for i in model.rot
                             if math.isfinite(model.angle_step[i]) and model.angle_step[i] > 0.0]
        self._any_rated = bool(self._thrust_rated or self._surface_rated or self._angle_rated)
        self._never = np.zeros(model.r, dtype=bool)
        self._never.flags.writeable = False
        self._dof_index = model.dof_index
        self._all_dofs = model.n == len(DOF_NAMES)
        self._dofs = vehicle.dofs
        self._t_e = model.t_e
        self._drive = DrivePower.of(vehicle)
        self._power = self._drive.forward.tolist()
        self._power_reverse = self._drive.reverse.tolist()
        self._tolerance = model.dof_tolerance.tolist()
        self._rot_pairs = [(int(i), (int(c1), int(c2))) for i, (c1, c2) in zip(model.rot, model.rot_columns)]
        self._continuous = [vehicle.actuators[i].rotation.continuous for i in model.rot]
        self._hold = model.hold.tolist()

    def set_voltage(self, voltage: float | None) -> None:
        """The command maps at ``voltage``: actuators with the same map share it (one
        vectorised call)."""
        maps: dict = {}
        actuators = self.model.vehicle.actuators
        self.maps = CommandMaps([None if a.is_surface else maps.setdefault(a.command, command_map(a.command, voltage))
                                 for a in actuators], [not a.is_surface and a.command.reversed for a in actuators])

    def refresh(self, conditions: Conditions) -> None:
        """What faults, speed and voltage decide: dead bands, where a thrust counts as at its
        limit, availability, the command efficiency, the control surfaces' lift gains."""
        model = self.model
        fault_set, low, high = conditions.faults, conditions.low, conditions.high
        self._lift = conditions.lift
        self._lift_list = self._lift.tolist()
        if self._deadband_index.size:
            self._deadband = self._deadband_edges * fault_set.command_efficiency[self._deadband_index, None]
        # Where a thrust counts as at its limit (an end of zero is no limit to report).
        self._at_high = np.where(high > 0.0, high * (1.0 - AT_LIMIT), np.inf)
        self._at_low = np.where(low < 0.0, low * (1.0 - AT_LIMIT), -np.inf)
        available = fault_set.efficiency > 0.0
        available[model.surfaces] &= self._lift[model.surfaces] > 0.0
        available.flags.writeable = False
        self.available = available
        fault_set.modes.flags.writeable = False
        self.modes = fault_set.modes
        efficiency = fault_set.command_efficiency
        self._command_efficiency = None if np.all(efficiency == 1.0) else efficiency
        drive = self._drive.degraded(efficiency)                # a DEGRADED drive draws its set-point's power
        self._power, self._power_reverse = drive.forward.tolist(), drive.reverse.tolist()
        self._losses = list(conditions.losses.items())

    def actuate(self, requested: np.ndarray, tau: np.ndarray, limits: SampleLimits, output: MethodOutput,
                drag: float, state: ActuatorState, method: str, start: float) -> AllocationResult:
        """The sample's result from the method stage's ``output`` for the controlled request
        ``tau`` and the surge ``drag`` it fed forward; ``state`` is the one the sample started
        from."""
        thrust, angle, extended = self.resolve(output, limits)
        if self._deadband_index.size:
            self._snap_deadband(thrust, extended, limits)
        achieved = self._t_e @ extended
        if drag:
            achieved[SURGE] -= drag
        miss = (achieved if self._all_dofs else achieved[self._dof_index]) - tau
        short = ()
        misses = miss.tolist()
        if any(abs(m) > tolerance for m, tolerance in zip(misses, self._tolerance)):
            short = tuple(dof for dof, m, tolerance in zip(self._dofs, misses, self._tolerance) if abs(m) > tolerance)
        if self._all_dofs:
            unallocated = -miss
        else:
            unallocated = np.zeros(6)
            unallocated[self._dof_index] = -miss
        efficiency = self._command_efficiency if not self._losses else self._flushing_efficiency(thrust, angle)
        command = self.maps.commands(thrust, efficiency, self._lift)
        at_thrust, at_rate = self._limit_flags(thrust, angle, state)
        power = sum((p if t >= 0.0 else q) * abs(t) ** 1.5
                    for p, q, t in zip(self._power, self._power_reverse, thrust.tolist()))
        return AllocationResult(thrust=thrust, azimuth=angle, command=command, achieved=achieved, requested=requested,
                                saturated=bool(short), status=output.status, iterations=output.iterations,
                                solve_time=time.perf_counter() - start, power=power, method=method, mode=self.modes,
                                available=self.available, unallocated=unallocated, at_thrust_limit=at_thrust,
                                at_rate_limit=at_rate, drag=drag, outcome=output.outcome, short=short,
                                residual=output.residual, reason=output.reason)

    def _flushing_efficiency(self, thrust: np.ndarray, angle: np.ndarray) -> np.ndarray:
        """The command efficiency with each thruster that pushes onto a dead one losing its
        [3.11.4] factor along the direction it pushes: its command asks for the thrust that
        still gives the force allocated, as a degraded thruster's does."""
        base = self._command_efficiency
        efficiency = np.ones(self.model.r) if base is None else base.copy()
        for i, losses in self._losses:
            direction = float(angle[i]) + (math.pi if thrust[i] < 0.0 else 0.0)
            efficiency[i] *= min(loss.factor(direction) for loss in losses)
        return efficiency

    def stop(self, state: ActuatorState, method: str) -> AllocationResult:
        """Zero thrust, the angles held."""
        r = self.model.r
        thrust = np.zeros(r)
        command = self.maps.commands(thrust, self._command_efficiency, self._lift)
        return AllocationResult(thrust=thrust, azimuth=state.angle, command=command, achieved=np.zeros(6),
                                requested=np.zeros(6), saturated=False, status="stopped", iterations=0, solve_time=0.0,
                                power=0.0, method=method, mode=self.modes, available=self.available,
                                unallocated=np.zeros(6), at_thrust_limit=np.zeros(r, dtype=bool),
                                at_rate_limit=np.zeros(r, dtype=bool), outcome=Outcome.STOPPED)

    def resolve(self, output: MethodOutput, limits: SampleLimits) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Per-actuator thrust and angle from the extended force, inside every limit, and the
        extended force (1.18) they give."""
        model = self.model
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
        model = self.model
        for k in np.flatnonzero(inside):
            i = int(index[k])
            f = float(force[k])
            edge = float(high_edge[k] if f > 0.0 else low_edge[k])
            fits = limits.low[i] - DEADBAND_EDGE <= edge <= limits.high[i] + DEADBAND_EDGE
            new = edge if fits and abs(edge - f) < abs(f) else 0.0
            thrust[i] = new
            start = int(model.starts[i])
            if model.rotatable[i]:
                extended[start:start + 2] *= new / f
            else:
                extended[start] = new

    def _limit_flags(self, thrust: np.ndarray, angle: np.ndarray,
                     state: ActuatorState) -> tuple[np.ndarray, np.ndarray]:
        """Which actuators sit at an end of their force range in force, and which moved by a
        full rate step (thrust, a control surface's deflection, or angle) this sample."""
        at_thrust = (thrust >= self._at_high) | (thrust <= self._at_low)
        if not self._any_rated:
            return at_thrust, self._never
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
