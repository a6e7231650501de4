"""The limits stage of a sample: what each actuator may do this sample.

The static force ranges that faults, speed and voltage leave (``faults.static_ranges``,
recomputed only when one of them changes), narrowed by the rate limits around the last
sample's thrust, and for each rotatable thruster the angles and thrusts ``azimuth.plan``
allows, toward the convex piece the :class:`~.pieces.PiecePlanner` chose when some
thruster's side of a forbidden sector is in question. With thrust bias, the offset b of
:class:`~allocator_pkg.effectiveness.thrust_bias.ThrustBias` for the request goes to the method
in the limits, and the wanted force of every rotatable thruster is moved by it."""

from __future__ import annotations

import numpy as np

from ..effectiveness.model import AzimuthLimits, Model, SampleLimits
from ..effectiveness.sectors import surroundings
from ..effectiveness.thrust_bias import ThrustBias
from ..effectiveness.weighted_inverse import PseudoInverseGains
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
        self._around: list = [None] * len(self._rotations)
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
            around = self._surroundings(state)
            planned = self._planned(tau, state, wanted, stuck, around)
            wanted.update(planned if bias is None else biased(planned, bias, self._rot_pairs))
            for state_k, (i, _), rotation, around_k in zip(state.azimuth, self._rot_pairs, self._rotations, around):
                limits_k = plan(rotation, state_k, self._angle_step[i], (self._low_list[i], self._high_list[i]),
                                self._thrust_step[i], wanted[i], self._hold[i], stuck.get(i), around_k)
                azimuth.append(limits_k)
                low[i], high[i] = limits_k.thrust_low, limits_k.thrust_high
        return SampleLimits(low, high, model.rot, azimuth, state.angle, state.thrust, range_low=self.low,
                            range_high=self.high, bias=bias)

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
