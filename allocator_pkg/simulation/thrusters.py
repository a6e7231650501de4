"""The actuators as the water sees them: each thrust follows its command as a first-order lag
with the configured rate limit, inside the force range the supply voltage gives; each azimuth
turns toward its commanded angle at the configured turning rate, the short way round. A
FAILED actuator gives no force, a STUCK one keeps its angle, a DEGRADED one a share of its
force. A drive's power limit (``cap``, the thrust it leaves [N]; the simulated power plant's load
reduction) holds the thrust under it at once. Their wrench is T(alpha) f (survey (1.9)) at the
angles reached."""

from __future__ import annotations

import math

import numpy as np

from ..effectiveness.configuration_matrix import actuator_direction, configuration_matrix, force_column
from ..effectiveness.faults import thrust_limits
from ..vehicle.angles import wrap
from ..vehicle.config import Vehicle

PHYSICAL_MODES = ("nominal", "failed", "stuck", "degraded")


class Thrusters:
    """Thrust [N] and angle [rad] of every actuator, in configuration order."""

    def __init__(self, vehicle: Vehicle, time_constant: float, voltage: float | None = None):
        if not (math.isfinite(time_constant) and time_constant > 0.0):
            raise ValueError(f"thruster_time_constant: a finite number > 0, not {time_constant!r}")
        self.vehicle = vehicle
        self.time_constant = time_constant
        actuators = vehicle.actuators
        self.thrust = np.zeros(len(actuators))
        self.angle = np.array([a.rotation.initial if a.rotatable else 0.0 for a in actuators])
        self.rate = np.array([a.thrust_rate_max if a.thrust_rate_max > 0.0 else np.inf for a in actuators])
        self.turn_rate = np.array([a.rotation.rate_max if a.rotatable else 0.0 for a in actuators])
        self.efficiency = np.ones(len(actuators))
        self.stuck = np.zeros(len(actuators), dtype=bool)
        self.cap = np.full(len(actuators), np.inf)
        self._rotatable = [i for i, a in enumerate(actuators) if a.rotatable]
        self._matrix = configuration_matrix(actuators, self.angle)
        self._matrix_angles = self.angle.tolist()
        self._voltage = voltage
        self.low, self.high = thrust_limits(vehicle, voltage)

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
        if mode == "stuck" and self.vehicle.actuators[i].rotatable:
            self.angle[i] = value

    def start_at(self, thrust: np.ndarray, angle: np.ndarray) -> None:
        """Start where the commands ``thrust`` [N] and ``angle`` [rad] hold them: the thrust they
        give (inside the force ranges, times the efficiencies), the angles of the rotatable
        actuators."""
        self.thrust = np.clip(np.asarray(thrust, dtype=float), self.low, self.high) * self.efficiency
        rotatable = np.array([a.rotatable for a in self.vehicle.actuators])
        self.angle = np.where(rotatable, np.asarray(angle, dtype=float), self.angle)

    def clear_faults(self) -> None:
        self.efficiency[:] = 1.0
        self.stuck[:] = False

    def step(self, thrust: np.ndarray, angle: np.ndarray, dt: float) -> None:
        """Move ``dt`` [s] toward the commanded thrust and angles."""
        target = _clip(thrust, self.low, self.high) * self.efficiency
        change = (target - self.thrust) * (1.0 - math.exp(-dt / self.time_constant))
        self.thrust = _clip(self.thrust + _clip(change, -self.rate * dt, self.rate * dt), -self.cap, self.cap)
        turn = np.array([wrap(a - b) for a, b in zip(np.asarray(angle, dtype=float).tolist(), self.angle.tolist())])
        turn = _clip(turn, -self.turn_rate * dt, self.turn_rate * dt)
        self.angle = np.where(self.stuck, self.angle, self.angle + turn)

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
