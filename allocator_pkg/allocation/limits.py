"""The limits stage of a sample: what each actuator may do this sample.

The static force ranges that faults, speed and voltage leave (``faults.static_ranges``,
recomputed only when one of them changes), narrowed by the rate limits around the last
sample's thrust, and for each rotatable thruster the angles and thrusts ``azimuth.plan``
allows, toward the convex piece the :class:`~.pieces.PiecePlanner` chose when some
thruster's side of a forbidden sector is in question. The sectors are those in force: a
flushing zone lifts with the thruster it protects and returns with it, and a thruster pushing
onto a dead one has its thrust cut by the [3.11.4] loss, or leaves the loss sector alone where
its edge gives more (:mod:`~.dead_flushing`). With thrust bias, the offset b of
:class:`~allocator_pkg.effectiveness.thrust_bias.ThrustBias` for the request goes to the method
in the limits, and the wanted force of every rotatable thruster is moved by it."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..effectiveness.model import AzimuthLimits, Model, SampleLimits
from ..effectiveness.sectors import surroundings
from ..effectiveness.thrust_bias import ThrustBias
from ..effectiveness.weighted_inverse import PseudoInverseGains
from . import dead_flushing
from .azimuth import piece_in_question, plan
from .conditions import Conditions
from .pieces import PiecePlanner
from .state import ActuatorState


class LimitsStage:
    """This sample's :class:`SampleLimits` from the configuration, the faults, speed and
    voltage in force, and the state the sample starts from."""

    def __init__(self, model: Model, inverse: PseudoInverseGains):
        self.planner = PiecePlanner(model)
        self.bias = ThrustBias()
        self.version = 0
        self.configure(model, inverse)

    def configure(self, model: Model, inverse: PseudoInverseGains) -> None:
        """Per-configuration constants, as the types the per-sample path reads fastest;
        ``inverse``, the configuration's pseudo-inverse gains, plans the rotatable thrusters."""
        if self.planner.model is not model:
            self.planner.update_model(model)
        self.model = model
        self._inverse = inverse
        self._rate_limited = bool(np.isfinite(model.thrust_step).any())
        self._rot_pairs = [(int(i), (int(c1), int(c2))) for i, (c1, c2) in zip(model.rot, model.rot_columns)]
        self._rotations = [model.vehicle.actuators[i].rotation for i in model.rot]
        self._in_force = list(self._rotations)
        self._around: list = [None] * len(self._rotations)
        self._losses: list = []
        self._angle_step = model.angle_step.tolist()
        self._thrust_step = model.thrust_step.tolist()
        self._hold = model.hold.tolist()
        self.bias.configure(model)

    def refresh(self, conditions: Conditions) -> None:
        """What faults, speed and voltage decide, taken when they change (never per sample):
        the static force ranges, the pseudo-inverse gain that plans rotatable thrusters, and
        the limits of a vehicle whose limits never change between samples."""
        model = self.model
        self.fault_set = conditions.faults
        self.low, self.high = conditions.low, conditions.high
        self._low_list, self._high_list = self.low.tolist(), self.high.tolist()
        self._lift = conditions.lift
        self.version += 1
        rotations = [conditions.rotations[i] for i in model.rot]
        if rotations != self._rotations:                  # zones lifted or returned: values only
            self._in_force = rotations
            self._use_rotations(list(rotations))
        self._losses = [(k, conditions.losses[i], [False] * len(conditions.losses[i]))
                        for k, (i, _) in enumerate(self._rot_pairs) if i in conditions.losses]
        self.bias.refresh(self.high, self.fault_set.stuck)
        if model.rot.size:
            excluded = (self.low == 0.0) & (self.high == 0.0)
            self._desired_gain = self._inverse.gain(excluded, {})
        if model.surfaces.size:
            gain = self._lift[model.surfaces]
            self._surface_step = np.multiply(gain, model.thrust_step[model.surfaces], out=np.zeros(gain.size),
                                             where=gain > 0.0)
        self._static = None if (model.rot.size or model.surfaces.size or self._rate_limited) else SampleLimits(
            self.low, self.high, model.rot, [], np.zeros(model.r), np.zeros(model.r), self.version, self.low,
            self.high)

    def sample(self, tau: np.ndarray, state: ActuatorState) -> SampleLimits:
        """The limits of a sample that starts from ``state`` and requests ``tau`` (controlled
        DOFs)."""
        if self._static is not None:
            self._static.angle, self._static.thrust = state.angle, state.thrust
            return self._static
        model = self.model
        previous, step = state.thrust, model.thrust_step
        surfaces = model.surfaces
        if surfaces.size:
            previous = previous.copy()
            previous[surfaces] = self._lift[surfaces] * state.deflection[surfaces]
            step = step.copy()
            step[surfaces] = self._surface_step
        low = np.minimum(np.maximum(previous - step, self.low), self.high)
        high = np.minimum(np.maximum(previous + step, self.low), self.high)
        azimuth: list[AzimuthLimits] = []
        bias = self.bias.offsets(tau)
        if model.rot.size:
            stuck = self.fault_set.stuck
            desired = (self._desired_gain @ tau if bias is None else self._desired_gain @ tau + bias).tolist()
            wanted = {i: (desired[c1], desired[c2]) for i, (c1, c2) in self._rot_pairs}
            if self._losses:
                self._close_loss_sectors(wanted, stuck)
            around = self._surroundings(state)
            planned = self._planned(tau, state, wanted, stuck, around)
            wanted.update(planned if bias is None else biased(planned, bias, self._rot_pairs))
            for state_k, (i, _), rotation, around_k in zip(state.azimuth, self._rot_pairs, self._rotations, around):
                limits_k = plan(rotation, state_k, self._angle_step[i], (self._low_list[i], self._high_list[i]),
                                self._thrust_step[i], wanted[i], self._hold[i], stuck.get(i), around_k)
                azimuth.append(limits_k)
                low[i], high[i] = limits_k.thrust_low, limits_k.thrust_high
            for k, losses, closed in self._losses:
                i = self._rot_pairs[k][0]
                if any(closed) and i not in stuck:
                    self._leave_loss_sectors(k, i, losses, closed, state, tau, wanted[i], azimuth)
                low[i], high[i] = dead_flushing.cut(azimuth[k], losses, self._low_list[i], self._high_list[i])
        return SampleLimits(low, high, model.rot, azimuth, state.angle, state.thrust, range_low=self.low,
                            range_high=self.high, rotations=self._rotations, bias=bias)

    def _use_rotations(self, rotations: list) -> None:
        """Plan with these rotations (per rotatable thruster) from now on: values only."""
        self._rotations = rotations
        self._around = [None] * len(rotations)
        every = [None] * self.model.r
        for (i, _), rotation in zip(self._rot_pairs, rotations):
            every[i] = rotation
        self.planner.use_rotations(every)

    def _close_loss_sectors(self, wanted: dict[int, tuple[float, float]], stuck: dict[int, float]) -> None:
        """Which [3.11.4] loss sectors each thruster leaves alone this sample
        (:func:`~.dead_flushing.closed`); a closed one is a forbidden sector of its rotation. A
        stuck or reversing thruster's stay open."""
        changed = False
        for k, losses, closed in self._losses:
            i = self._rot_pairs[k][0]
            if i in stuck or (self._in_force[k].reversible and self._low_list[i] < 0.0):
                continue
            radius, hold = self._high_list[i], self._hold[i]
            now = [dead_flushing.closed(loss, wanted[i], radius, hold, was) for loss, was in zip(losses, closed)]
            if now != closed:
                closed[:] = now
                changed = True
        if changed:
            rotations = list(self._in_force)
            for k, losses, closed in self._losses:
                shut = tuple(loss.sector for loss, flag in zip(losses, closed) if flag)
                if shut:
                    rotations[k] = replace(rotations[k], forbidden_sectors=rotations[k].forbidden_sectors + shut)
            self._use_rotations(rotations)

    def _leave_loss_sectors(self, k: int, i: int, losses, closed: list[bool], state: ActuatorState, tau: np.ndarray,
                            wanted: tuple[float, float], azimuth: list[AzimuthLimits]) -> None:
        """A thruster pushing inside a closed loss sector leaves it by rate steps at the thrust
        the loss leaves (:func:`~.dead_flushing.exit_limits`), not at zero thrust, toward the
        side the piece planner sends it to (its wanted direction without the planner)."""
        state_k = state.azimuth[k]
        if abs(state_k.thrust) <= self._hold[i]:
            return
        for loss, flag in zip(losses, closed):
            if flag and loss.inside(state_k.angle):
                if self.planner.needed:
                    wanted = self.planner.targets(tau, self.low, self.high, self.fault_set.stuck,
                                                  state.angle).get(i, wanted)
                state_k.turning = 0
                azimuth[k] = dead_flushing.exit_limits(loss, self._in_force[k], state_k, wanted, self._angle_step[i],
                                                       (self._low_list[i], self._high_list[i]), self._thrust_step[i])
                return

    def _surroundings(self, state: ActuatorState) -> list:
        """Each rotatable thruster's `sectors.surroundings`, kept while its angle stays."""
        cache = self._around
        for k, (state_k, rotation) in enumerate(zip(state.azimuth, self._rotations)):
            if cache[k] is None or cache[k][0] != state_k.angle:
                cache[k] = (state_k.angle, surroundings(rotation, state_k.angle))
        return [entry[1] for entry in cache]

    def _planned(self, tau: np.ndarray, state: ActuatorState, wanted: dict[int, tuple[float, float]],
                 stuck: dict[int, float], around: list) -> dict[int, tuple[float, float]]:
        """Where the piece planner sends each rotatable thruster, when some thruster's side of
        a forbidden sector (or the feasible sector's end) is in question, and while a crossing
        it decided is under way; else nothing (the pseudo-inverse's wish stands)."""
        planner = self.planner
        if not planner.needed:
            return {}
        question = any(
            i not in stuck and self._high_list[i] > self._low_list[i] and not state_k.turning
            and piece_in_question(rotation, state_k.angle, self._angle_step[i], wanted[i], self._hold[i], around_k)
            for state_k, (i, _), rotation, around_k in zip(state.azimuth, self._rot_pairs, self._rotations, around))
        if question:
            return planner.targets(tau, self.low, self.high, stuck, state.angle)
        if any(state_k.turning for state_k in state.azimuth):
            return planner.last_targets
        return {}


def biased(targets: dict[int, tuple[float, float]], bias: np.ndarray,
           columns: list[tuple[int, tuple[int, int]]]) -> dict[int, tuple[float, float]]:
    """The piece planner's force ``targets`` with the thrust bias's offset added: the optimum
    about b is b plus the optimum about 0 while no limit binds (docs/theory.md, thrust bias)."""
    return {i: (targets[i][0] + bias[c1], targets[i][1] + bias[c2]) for i, (c1, c2) in columns if i in targets}
