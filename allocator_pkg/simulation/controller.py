"""A station-keeping controller a user would run: nonlinear PD plus integral action in the
body frame (Fossen 2021, the nonlinear PID for DP),

    tau = -Kp R^T e - Ki R^T z - Kd nu,   z' = e,

with e the position and attitude error in NED (angles wrapped), R the rotation of the position
DOFs from body to NED (the attitude DOFs are left as they are), the gains per body DOF, and
conditional integration as anti-windup: a body axis stops integrating while the allocator
reports that part of the request it could not give (``AllocationStatus.unallocated``) points
the way integrating would push the request further.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..vehicle.angles import wrap
from .kinematics import rotation


@dataclass(frozen=True)
class Gains:
    """Per held DOF (3: north, east, heading; 6: north, east, down, roll, pitch, yaw): Kp
    [N/m, N m/rad], Kd [N s/m, N m s/rad], Ki [N/(m s), N m/(rad s)]."""

    kp: tuple[float, ...]
    kd: tuple[float, ...]
    ki: tuple[float, ...]
    unallocated_threshold: tuple[float, ...] = ()
    """Per DOF, the unallocated force or moment [N, N m] above which the DOF counts as short
    (empty: any nonzero amount)."""

    def __post_init__(self) -> None:
        sizes = {len(self.kp), len(self.kd), len(self.ki)}
        if len(sizes) != 1 or sizes.pop() not in (3, 6):
            raise ValueError("controller: kp, kd and ki need 3 (north, east, heading) or 6 "
                             "(north, east, down, roll, pitch, yaw) values each")
        if self.unallocated_threshold and len(self.unallocated_threshold) != len(self.kp):
            raise ValueError("controller.unallocated_threshold: one value per DOF")
        for name in ("kp", "kd", "ki", "unallocated_threshold"):
            if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v >= 0.0
                       for v in getattr(self, name)):
                raise ValueError(f"controller.{name}: finite numbers >= 0")


class StationKeeping:
    """The controller's state (the integral z) and its law."""

    def __init__(self, gains: Gains):
        self.gains = gains
        self.dofs = len(gains.kp)
        self.kp, self.kd, self.ki = (np.array(v, dtype=float) for v in (gains.kp, gains.kd, gains.ki))
        self.threshold = np.array(gains.unallocated_threshold or [0.0] * self.dofs)
        self.integral = np.zeros(self.dofs)
        self._last: tuple | None = None

    def error(self, eta: np.ndarray, setpoint: np.ndarray) -> np.ndarray:
        """eta - setpoint with the angles wrapped."""
        error = np.asarray(eta, dtype=float) - setpoint
        for i in ((2,) if self.dofs == 3 else (3, 4, 5)):
            error[i] = wrap(error[i])
        return error

    def _to_body(self, eta: np.ndarray) -> np.ndarray:
        """The matrix that turns a NED error vector into body axes (attitude DOFs unchanged)."""
        if self.dofs == 3:
            c, s = math.cos(eta[2]), math.sin(eta[2])
            return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
        result = np.eye(self.dofs)
        result[:3, :3] = rotation(eta[3], eta[4], eta[5]).T
        return result

    def _error_in_body(self, eta: np.ndarray, setpoint: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(:meth:`error`, :meth:`_to_body`) at ``eta`` and ``setpoint``, kept for the next call
        at the same values, bit for bit (a step's wrench and its integral share them)."""
        key = (np.asarray(eta, dtype=float).tobytes(), np.asarray(setpoint, dtype=float).tobytes())
        if self._last is None or self._last[0] != key:
            self._last = (key, self.error(eta, setpoint), self._to_body(eta))
        return self._last[1], self._last[2]

    def wrench(self, eta: np.ndarray, nu: np.ndarray, setpoint: np.ndarray) -> np.ndarray:
        """The body-frame request [X, Y, N] or [X, Y, Z, K, M, N] for this step."""
        e, to_body = self._error_in_body(eta, setpoint)
        return -self.kp * (to_body @ e) - self.ki * (to_body @ self.integral) - self.kd * np.asarray(nu)

    def settle(self, eta: np.ndarray, force: np.ndarray) -> None:
        """Start in equilibrium with a body ``force`` on the vehicle: the integral set so that
        its term alone answers -force (DOFs without integral gain left at zero)."""
        share = np.divide(np.asarray(force, dtype=float), self.ki, out=np.zeros(self.dofs), where=self.ki > 0.0)
        self.integral = self._to_body(eta).T @ share

    def integrate(self, eta: np.ndarray, setpoint: np.ndarray, dt: float,
                  unallocated: np.ndarray | None = None) -> None:
        """z += e dt, less its part along a body axis whose unallocated request (as the status
        gives it, in this controller's DOFs) is above its threshold and would grow by integrating."""
        e, to_body = self._error_in_body(eta, setpoint)
        step = to_body @ (e * dt)
        if unallocated is not None:
            short = np.asarray(unallocated, dtype=float)
            frozen = (np.abs(short) > self.threshold) & (short * (-self.ki * step) > 0.0)
            step = np.where(frozen, 0.0, step)
        self.integral += to_body.T @ step
