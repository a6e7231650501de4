"""The closed loop of a DP system linearised about the set-point, as a joint state space: the
vessel, the thrusters' first-order lag, the controller's PID acting on the nonlinear passive
observer's estimate (:mod:`.observer`), and the wind feed-forward through its low-pass filter
(:mod:`.control_system`). At the set-point heading psi0 = 0 (body axes along NED) the observer is
linear (R(psi_y) = I to first order), so the loop is x' = A x + B w, with the state

    [eta (3), nu (3), tau (3), z (3), f (3, with feed-forward), xi (6), eta^ (3), b^ (3), nu^ (3)]

and the inputs w = [gust force (3), other environmental force (3), wave-frequency motion (3),
measurement noise (3)]:

    eta' = nu,  M nu' = -D nu + tau + F_gust + F_other,  tau' = (eta_l u - tau) / T_thr,
    u = -Kp eta^ - Ki z - Kd nu^ + f,  z' = eta^,  f' = (-F_gust - f) / T_f,
    observer (Fossen and Strand 1999) driven by y = eta + eta_w + v and its model's force
    u + F_gust (the measured wind's load is an input of its model with feed-forward),

M the mass with added mass, D the hull's damping linearised in the mean current (the true
vessel's), the observer's own M and D those of :class:`.vessel.Vessel` (its linear damping),
eta_l the thrusters' loss factor (the thrust delivered over the thrust commanded, one for all:
the allocator and the observer's model do not know it, so it scales the loop's gain).
Without an observer the controller acts on eta and nu (then the loop is
:class:`.frequency_domain.LinearLoop`'s). The excursion's variance per DOF is
int_0^inf (H S H^*)_ii dw over the inputs' one-sided spectra (Fossen 2021, 11.2):

- the measurement noise, white of standard deviation sigma sampled every dt: S = sigma^2 dt / pi
  up to the Nyquist frequency pi / dt;
- the wave-frequency motion: T T^H S_zeta (:func:`.wave_motion.transfer`, JONSWAP S_zeta),
  averaged over the spreading.

The allocator (its distribution of the request, hence a loss that differs between thrusters),
the trips and the sampling's one-step delay are left out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .controller import Gains
from .observer import PassiveObserver
from .spectra import jonswap
from .spreading import spread_mean
from .wave_motion import transfer

PLANT = 15
"""eta, nu, tau, z, f: the states before the observer's."""
INPUTS = 12
"""gust force, other force, wave motion, noise (3 each)."""


@dataclass(frozen=True)
class ObservedLoop:
    """M and D [SI, surge, sway, yaw] of the vessel, the controller's gains, the thrusters' lag
    [s] (> 0), the observer (None: the controller on the true state), the feed-forward
    filter's time constant [s] (None: no wind feed-forward) and the thrusters' loss factor
    (delivered over commanded, in (0, 1])."""

    mass: np.ndarray
    damping: np.ndarray
    gains: Gains
    lag: float
    observer: PassiveObserver | None = None
    wind_filter: float | None = None
    thrust_factor: float = 1.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.lag) and self.lag > 0.0):
            raise ValueError(f"thruster_time_constant: a finite number > 0 for the linear loop, not {self.lag!r}")
        if self.wind_filter is not None and not (math.isfinite(self.wind_filter) and self.wind_filter > 0.0):
            raise ValueError(f"controller.wind_filter: a finite number > 0, not {self.wind_filter!r}")
        if not 0.0 < self.thrust_factor <= 1.0:
            raise ValueError(f"thrust_losses: a loss factor in (0, 1], not {self.thrust_factor!r}")

    def matrices(self) -> tuple[np.ndarray, np.ndarray]:
        """(A, B) of x' = A x + B w; the first three states are the vessel's position."""
        size = PLANT + (15 if self.observer is not None else 0)
        a, b = np.zeros((size, size)), np.zeros((size, INPUTS))
        eye, m_inv = np.eye(3), np.linalg.inv(self.mass)
        kp, kd, ki = (np.diag(np.array(v, dtype=float)) for v in (self.gains.kp, self.gains.kd, self.gains.ki))
        pose, speed = (slice(0, 3), slice(3, 6)) if self.observer is None else (slice(21, 24), slice(27, 30))
        request = np.zeros((3, size))                 # u = request @ x
        request[:, pose], request[:, speed], request[:, 9:12] = -kp, -kd, -ki
        a[0:3, 3:6] = eye
        a[3:6, 3:6], a[3:6, 6:9] = -m_inv @ self.damping, m_inv
        b[3:6, 0:3], b[3:6, 3:6] = m_inv, m_inv
        a[6:9] += self.thrust_factor * request / self.lag
        a[6:9, 6:9] -= eye / self.lag
        a[9:12, pose] = eye
        if self.wind_filter is not None:
            request[:, 12:15] = eye
            a[6:9, 12:15] += self.thrust_factor * eye / self.lag
            a[12:15, 12:15] = -eye / self.wind_filter
            b[12:15, 0:3] = -eye / self.wind_filter
        if self.observer is not None:
            self._observer_rows(a, b, request)
        return a, b

    def _observer_rows(self, a: np.ndarray, b: np.ndarray, request: np.ndarray) -> None:
        """The observer's rows at psi_y = 0: its own A, its gains on y = eta + eta_w + v and its
        model's force u (+ the measured gust with feed-forward)."""
        observer = self.observer
        tuning = observer.tuning
        gain = np.zeros((15, 3))
        gain[0:6], gain[6:9], gain[9:12] = tuning.k1(), tuning.omega_c * np.eye(3), observer.k3
        gain[12:15] = observer.mass_inverse @ observer.k4
        rows = slice(PLANT, PLANT + 15)
        a[rows, rows] = observer.matrices(0.0)
        a[rows, 0:3] = gain
        b[rows, 6:9], b[rows, 9:12] = gain, gain
        a[PLANT + 12:PLANT + 15] += observer.mass_inverse @ request
        if self.wind_filter is not None:
            b[PLANT + 12:PLANT + 15, 0:3] += observer.mass_inverse

    def response(self, omega: np.ndarray) -> np.ndarray:
        """(n, 3, 12) complex transfer from the inputs to the position at ``omega`` [rad/s]."""
        a, b = self.matrices()
        s = 1j * np.asarray(omega, dtype=float)[:, None, None]
        x = np.linalg.solve(s * np.eye(a.shape[0])[None] - a[None], np.broadcast_to(b, (s.shape[0], *b.shape)))
        return x[:, 0:3, :]

    def excursion_std(self, omega: np.ndarray, input_spectrum: np.ndarray) -> np.ndarray:
        """[north/surge [m], east/sway [m], yaw [rad]] standard deviations under the one-sided
        (n, 12, 12) ``input_spectrum`` at the even grid ``omega``."""
        h = self.response(omega)
        response = np.einsum("nij,njk,nlk->nil", h, input_spectrum, h.conj()).real
        variance = np.trapezoid(np.diagonal(response, axis1=1, axis2=2), omega, axis=0)
        return np.sqrt(np.maximum(variance, 0.0))


def noise_spectrum(omega: np.ndarray, sigma: np.ndarray, period: float) -> np.ndarray:
    """(n, 3, 3) one-sided spectrum of white noise of standard deviations ``sigma`` sampled every
    ``period`` [s]: sigma^2 period / pi below the Nyquist frequency pi / period, zero above."""
    omega = np.asarray(omega, dtype=float)
    level = np.where(omega <= math.pi / period, period / math.pi, 0.0)
    return level[:, None, None] * np.diag(np.asarray(sigma, dtype=float) ** 2)[None]


def wave_motion_spectrum(omega: np.ndarray, height: float, period: float, peak_factor: float, direction: float,
                         spreading: float, length: float, beam: float) -> np.ndarray:
    """(n, 3, 3) complex one-sided cross-spectrum of the first-order [surge, sway, yaw] motion of
    a JONSWAP sea (``height`` [m], peak ``period`` [s], ``peak_factor``, 0: the standard's) from
    ``direction`` [rad] off the bow with the ``spreading`` exponent (0: long-crested)."""
    omega = np.asarray(omega, dtype=float)
    sea = jonswap(omega, height, period, peak_factor if peak_factor > 0.0 else None)

    def parts(theta: float) -> np.ndarray:
        t = transfer(omega, direction + theta, length, beam)
        cross = np.einsum("in,jn->nij", t, t.conj())
        return np.stack([cross.real, cross.imag])

    mean = spread_mean(parts, spreading)
    return (mean[0] + 1j * mean[1]) * sea[:, None, None]
