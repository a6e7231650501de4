"""The actuators as the water sees them: each thrust follows its command as a first-order lag
with the configured rate limit, inside the force range the supply voltage gives; each azimuth
turns toward its commanded angle at the configured turning rate, the short way round. A
FAILED actuator gives no force: its thrust falls at its rate limit, or, with ``trip``, drops to
zero at once (a trip, as a breaker opens); a STUCK one keeps its angle, a DEGRADED one a share
of its force. With thrust losses (:mod:`.thrust_losses`) the thrust followed is the command
times the factors of the case of the actuators failed now, at the direction it pushes. A
drive's power limit (``cap``, the thrust range it leaves [N]; the simulated power plant's load
reduction) holds the thrust under it at once. Their wrench is T(alpha) f (survey (1.9)) at the
angles reached."""

from __future__ import annotations

import math

import numpy as np

from ..effectiveness.configuration_matrix import actuator_direction, configuration_matrix, force_column
from ..effectiveness.faults import thrust_limits
from ..vehicle.angles import wrap
from ..vehicle.config import Vehicle
from .thrust_losses import ThrustLosses

PHYSICAL_MODES = ("nominal", "failed", "stuck", "degraded")


class Thrusters:
    """Thrust [N] and angle [rad] of every actuator, in configuration order."""

    def __init__(self, vehicle: Vehicle, time_constant: float, voltage: float | None = None, trip: bool = False,
                 losses: ThrustLosses | None = None):
        if not (math.isfinite(time_constant) and time_constant > 0.0):
            raise ValueError(f"thruster_time_constant: a finite number > 0, not {time_constant!r}")
        if losses is not None and not losses.names() <= set(vehicle.names):
            raise ValueError(f"thrust_losses: {', '.join(sorted(losses.names() - set(vehicle.names)))} not actuators "
                             f"of the vehicle ({', '.join(vehicle.names)})")
        self.vehicle = vehicle
        self.trip, self.losses = trip, losses
        self.time_constant = time_constant
        actuators = vehicle.actuators
        self.thrust = np.zeros(len(actuators))
        self.angle = np.array([a.rotation.initial if a.rotatable else 0.0 for a in actuators])
        self.rate = np.array([a.thrust_rate_max if a.thrust_rate_max > 0.0 else np.inf for a in actuators])
        self.turn_rate = np.array([a.rotation.rate_max if a.rotatable else 0.0 for a in actuators])
        self.efficiency = np.ones(len(actuators))
        self.stuck = np.zeros(len(actuators), dtype=bool)
        self.failed = np.zeros(len(actuators), dtype=bool)
        self._heading = np.array([0.0 if a.rotatable else math.atan2(a.direction[1], a.direction[0])
                                  for a in actuators])
        self._turns = np.array([a.rotatable for a in actuators])
        self._forward = self._reverse = np.ones(len(actuators))
        self._profiles: list = []
        self._losses_now()
        self.cap = (np.full(len(actuators), -np.inf), np.full(len(actuators), np.inf))
        self._rotatable = [i for i, a in enumerate(actuators) if a.rotatable]
        self._matrix = configuration_matrix(actuators, self.angle)
        self._matrix_angles = self.angle.tolist()
        self._voltage = voltage
        self.low, self.high = thrust_limits(vehicle, voltage)
        self._step_dt: float | None = None
        self._step_limits: tuple = ()

    def set_voltage(self, voltage: float | None) -> None:
        """The supply voltage the force ranges follow (None: nominal)."""
        if voltage != self._voltage:
            self.low, self.high = thrust_limits(self.vehicle, voltage)
            self._voltage = voltage

    def set_fault(self, name: str, mode: str, value: float = 0.0) -> None:
        """What an actuator physically does: ``nominal``, ``failed``, ``stuck`` (at its angle
        now, or ``value`` [rad] for a rotatable one) or ``degraded`` (``value``: the share of
        force left)."""
        if name not in self.vehicle.names:
            raise ValueError(f"fault.actuator: {name!r} is not one of {', '.join(self.vehicle.names)}")
        if mode not in PHYSICAL_MODES:
            raise ValueError(f"fault.mode: {mode!r} is not one of {', '.join(PHYSICAL_MODES)}")
        i = self.vehicle.names.index(name)
        self.efficiency[i] = {"failed": 0.0, "degraded": value}.get(mode, 1.0)
        self.stuck[i] = mode == "stuck"
        self.failed[i] = mode == "failed"
        if mode == "stuck" and self.vehicle.actuators[i].rotatable:
            self.angle[i] = value
        if mode == "failed" and self.trip:
            self.thrust[i] = 0.0
        self._losses_now()

    def _losses_now(self) -> None:
        """The loss factors of the case of the actuators failed now (ValueError when the losses
        have no such case)."""
        if self.losses is None:
            return
        names = self.vehicle.names
        case = self.losses.case(frozenset(name for name, failed in zip(names, self.failed) if failed))
        self._forward = np.array([case.forward.get(name, 1.0) for name in names])
        self._reverse = np.array([case.reverse.get(name, 1.0) for name in names])
        self._profiles = [(i, case.profiles[name]) for i, name in enumerate(names) if name in case.profiles]

    def loss_factor(self, thrust: np.ndarray) -> np.ndarray:
        """The factor on each actuator's ``thrust`` [N] at its angle now: its forward or reverse
        factor times its profile's along the direction the thrust pushes (1 without losses)."""
        factor = np.where(thrust >= 0.0, self._forward, self._reverse)
        for i, profile in self._profiles:
            direction = self._heading[i] + (self.angle[i] if self._turns[i] else 0.0) + (math.pi if thrust[i] < 0.0
                                                                                          else 0.0)
            factor[i] *= profile.factor(direction)
        return factor

    def start_at(self, thrust: np.ndarray, angle: np.ndarray) -> None:
        """Start where the commands ``thrust`` [N] and ``angle`` [rad] hold them: the angles of the
        rotatable actuators, the thrust they give (inside the force ranges, times the efficiencies
        and the loss factors there)."""
        self.angle = np.where(self._turns, np.asarray(angle, dtype=float), self.angle)
        self.thrust = np.clip(np.asarray(thrust, dtype=float), self.low, self.high) * self.efficiency
        if self.losses is not None:
            self.thrust *= self.loss_factor(self.thrust)

    def clear_faults(self) -> None:
        self.efficiency[:] = 1.0
        self.stuck[:] = False
        self.failed[:] = False
        self._losses_now()

    def step(self, thrust: np.ndarray, angle: np.ndarray, dt: float) -> None:
        """Move ``dt`` [s] toward the commanded thrust and angles."""
        target = _clip(thrust, self.low, self.high) * self.efficiency
        if self.losses is not None:
            target = target * self.loss_factor(target)
        lag, fall, rise, back, ahead = self._per_step(dt)
        change = (target - self.thrust) * lag
        self.thrust = self.thrust + _clip(change, fall, rise)
        if self._capped:
            self.thrust = _clip(self.thrust, *self._cap)
        turn = np.array([wrap(a - b) for a, b in zip(np.asarray(angle, dtype=float).tolist(), self.angle.tolist())])
        turn = _clip(turn, back, ahead)
        self.angle = np.where(self.stuck, self.angle, self.angle + turn)

    @property
    def cap(self) -> tuple[np.ndarray, np.ndarray]:
        """(astern, ahead): the thrust range [N] each drive's power limit leaves (-inf, inf: none)."""
        return self._cap

    @cap.setter
    def cap(self, value: tuple[np.ndarray, np.ndarray]) -> None:
        self._cap = value
        self._capped = not bool(np.all(value[0] == -np.inf) and np.all(value[1] == np.inf))

    def _per_step(self, dt: float) -> tuple[float, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Of a step ``dt`` [s]: the lag's share 1 - exp(-dt / T) and the thrust's and the angle's
        largest change down and up (kept for the last ``dt``)."""
        if self._step_dt != dt:
            self._step_dt = dt
            self._step_limits = (1.0 - math.exp(-dt / self.time_constant), -self.rate * dt, self.rate * dt,
                                 -self.turn_rate * dt, self.turn_rate * dt)
        return self._step_limits

    def wrench(self) -> np.ndarray:
        """[X, Y, Z, K, M, N] of the actuators in body FRD: T(alpha) f, the column of each
        rotatable actuator made again when its angle has changed."""
        actuators, matrix, known = self.vehicle.actuators, self._matrix, self._matrix_angles
        angles = self.angle.tolist()
        for i in self._rotatable:
            if angles[i] != known[i]:
                matrix[:, i] = force_column(actuators[i].position, actuator_direction(actuators[i], angles[i]))
                known[i] = angles[i]
        return matrix @ self.thrust


def _clip(values: np.ndarray, low, high) -> np.ndarray:
    """``np.clip`` (the same values) without its wrapper's overhead."""
    return np.minimum(np.maximum(values, low), high)
