"""The simulated vehicle: a hull model, its thrusters and the environment, advanced one
controller step at a time by fourth-order Runge-Kutta with the thrusters' force held over
each sub-step."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .environment import Environment
from .rov import Rov
from .thrusters import Thrusters
from .vessel import Vessel

PLANAR = [0, 1, 5]
"""Surge, sway and yaw among the six DOFs."""


@dataclass
class Pose:
    """Position [north, east, down] [m], attitude [roll, pitch, yaw] [rad], body velocity
    [u, v, w] [m/s] and angular velocity [p, q, r] [rad/s]."""

    position: np.ndarray
    attitude: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray


class Plant:
    def __init__(self, hull: Vessel | Rov, thrusters: Thrusters, environment: Environment,
                 position: np.ndarray, attitude: np.ndarray, substeps: int = 2):
        self.hull = hull
        self.thrusters = thrusters
        self.environment = environment
        self.substeps = substeps
        if hull.dofs == 3:
            self.eta = np.array([position[0], position[1], attitude[2]], dtype=float)
        else:
            self.eta = np.concatenate([position, attitude]).astype(float)
        self.nu = np.zeros(hull.dofs)

    @property
    def planar(self) -> bool:
        return self.hull.dofs == 3

    def body_wrench(self, load: np.ndarray | None = None) -> np.ndarray:
        """The force on the hull in its own DOFs: thrusters plus wind and wave drift (``load``:
        the environment's hull load at the heading now, when known)."""
        wrench = self.thrusters.wrench()
        if self.planar:
            return wrench[PLANAR] + (self.environment.hull_load(self.eta[2]) if load is None else load)
        return wrench

    def environment_force(self) -> np.ndarray:
        """The force the mean environment puts on the hull at rest on its pose now, in its own
        DOFs: the current through the hull's damping, wind and wave drift, and for an ROV its
        net weight and restoring moments."""
        current = self.environment.mean_current()
        rest = np.zeros(self.hull.dofs)
        if self.planar:
            _, nu_dot = self.hull.derivative(self.eta, rest, np.zeros(3), current[:2])
            return self.hull.mass @ nu_dot + self.environment.hull_load(self.eta[2], mean=True)
        _, nu_dot = self.hull.derivative(self.eta, rest, np.zeros(6), current)
        return self.hull.mass @ nu_dot

    def _derivative(self, state: np.ndarray, tau: np.ndarray, current: np.ndarray) -> np.ndarray:
        n = self.hull.dofs
        eta_dot, nu_dot = self.hull.derivative(state[:n], state[n:], tau, current)
        return np.concatenate([eta_dot, nu_dot])

    def step(self, thrust: np.ndarray, angle: np.ndarray, dt: float) -> None:
        """Advance ``dt`` [s] with the commanded thrusts [N] and angles [rad]."""
        self.environment.step(dt)
        current = self.environment.current()
        if self.planar:
            current = current[:2]
        load = self.environment.hull_load(self.eta[2]) if self.planar else None    # the same in every sub-step
        h = dt / self.substeps
        if self.planar:
            self._step_planar(thrust, angle, h, current.tolist(), load)
            return
        state = np.concatenate([self.eta, self.nu])
        for _ in range(self.substeps):
            self.thrusters.step(thrust, angle, h)
            tau = self.body_wrench(load)
            k1 = self._derivative(state, tau, current)
            k2 = self._derivative(state + 0.5 * h * k1, tau, current)
            k3 = self._derivative(state + 0.5 * h * k2, tau, current)
            k4 = self._derivative(state + h * k3, tau, current)
            state = state + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        n = self.hull.dofs
        self.eta, self.nu = state[:n], state[n:]

    def _step_planar(self, thrust: np.ndarray, angle: np.ndarray, h: float, current: list[float],
                     load: np.ndarray) -> None:
        """:meth:`step`'s sub-steps of a 3-DOF hull on floats (:meth:`.Vessel.rates`): the same
        Runge-Kutta, each element's operations those of the vector form in the same order."""
        rates = self.hull.rates
        state = (*self.eta.tolist(), *self.nu.tolist())
        half = 0.5 * h
        sixth = h / 6.0
        for _ in range(self.substeps):
            self.thrusters.step(thrust, angle, h)
            tau = self.body_wrench(load).tolist()
            k1 = rates(state, tau, current)
            k2 = rates(_along(state, half, k1), tau, current)
            k3 = rates(_along(state, half, k2), tau, current)
            k4 = rates(_along(state, h, k3), tau, current)
            state = _along(state, sixth, [a + 2.0 * b + 2.0 * c + d for a, b, c, d in zip(k1, k2, k3, k4)])
        self.eta, self.nu = np.array(state[:3]), np.array(state[3:])

    def pose(self) -> Pose:
        if self.planar:
            north, east, yaw = self.eta
            u, v, r = self.nu
            return Pose(np.array([north, east, 0.0]), np.array([0.0, 0.0, yaw]), np.array([u, v, 0.0]),
                        np.array([0.0, 0.0, r]))
        return Pose(self.eta[:3].copy(), self.eta[3:].copy(), self.nu[:3].copy(), self.nu[3:].copy())


def _along(state: tuple[float, ...], step: float, rate) -> tuple[float, ...]:
    """state + step * rate of the six floats of a 3-DOF hull, element by element."""
    x0, x1, x2, x3, x4, x5 = state
    r0, r1, r2, r3, r4, r5 = rate
    return (x0 + step * r0, x1 + step * r1, x2 + step * r2, x3 + step * r3, x4 + step * r4, x5 + step * r5)
