"""The DP vessel's state estimator: the nonlinear passive observer of Fossen and Strand (1999,
"Passive nonlinear observer design for ships using Lyapunov methods: full-scale experiments with
a supply vessel", Automatica 35(1)), as Fossen 2021 (Handbook of Marine Craft Hydrodynamics and
Motion Control, 2nd ed., ch. 13, the nonlinear passive observer for DP) gives it. From the
measured position and heading y (the low-frequency motion plus the first-order wave-frequency
motion plus noise) it estimates the low-frequency position and heading eta, the body velocity
nu, the bias b (slowly varying loads, NED) and the wave-frequency motion C_w xi:

    xi'  = A_w xi + K1 y~                          A_w = [[0, I], [-Omega^2, -2 Lambda Omega]]
    eta' = R(psi_y) nu + K2 y~                     C_w = [0, I]
    b'   = -T^-1 b + K3 y~
    M nu' = -D nu + R(psi_y)^T b + tau + R(psi_y)^T K4 y~
    y~ = y - eta - C_w xi   (the heading part wrapped)

with R(psi_y) the rotation at the measured heading, M and D the hull's mass and linear damping,
tau the thrusters' wrench (the allocated request). The gains are Fossen's:
K1 = [diag(-2 (zeta_n - lambda) omega_c / omega_o); diag(2 omega_o (zeta_n - lambda))],
K2 = diag(omega_c), so that each DOF's position loop is the notch
(s^2 + 2 lambda omega_o s + omega_o^2) / ((s^2 + 2 zeta_n omega_o s + omega_o^2)(s + omega_c))
at the wave frequency omega_o, and K3, K4 positive with the passivity relations
1/T_i << K3_i / K4_i < omega_o < omega_c, which with zeta_n > lambda make the loop transfer
h0(s) hB(s), hB = K4 (s + 1/T + K3/K4) / (s + 1/T), strictly positive real (the observer
error dynamics passive, hence exponentially stable). The values: lambda 0.1, zeta_n 1 and
T = 1000 s as Fossen's example (MSS ``ExPassiveObs.m``); omega_c = 1.5 omega_o and
K3 = 0.02 K4 [1/s] in place of its 1.1 / 0.8976 and 0.1, whose loop dips 4-6 deg past -90 deg
just below omega_o: with these h0 hB stays within +-90 deg for peak periods of 3 to 25 s (the
tests check it). K4 = diag(5, 5, 0.4) in the bis system (forces per metre scaled by m g / L,
moments per radian by m g L, m the rigid-body mass, L the length), 50 and 40 times the
example's 0.1, 0.1, 0.01: the velocity estimate then corrects a force it does not know within
about K2 M_ii / K4_i = 3 s (DP vessel, Tp 8 s), not five minutes, so that the controller's
damping acts on a velocity close to the vessel's, at the cost of a shallower notch: at most
0.14 of the wave motion passes at omega_o over Table 2-1's peak periods (3.5 to 12 s), where
the example's values pass 0.083.

Each step integrates the observer one period by fourth-order Runge-Kutta with the measurement,
the heading's rotation and tau held over it (the estimate a step uses is the one of the data up
to the step before, as a DP computer's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..vehicle.angles import wrap
from .scenario_keys import scenario_default

GRAVITY = 9.81
"""[m/s^2] of the bis system."""
STATES = 15
"""xi (6), eta (3), b (3), nu (3)."""


@dataclass(frozen=True)
class ObserverTuning:
    """The observer's tuning, the same for surge, sway and yaw but K4: the wave period [s]
    (omega_o = 2 pi / period), the wave model's relative damping lambda and the notch's zeta_n,
    omega_c / omega_o, the bias time constant T [s], K4 in the bis system per DOF and K3 / K4 [1/s]."""

    wave_period: float
    wave_damping: float = scenario_default("observer.wave_damping")
    notch_damping: float = scenario_default("observer.notch_damping")
    cutoff_ratio: float = scenario_default("observer.cutoff_ratio")
    bias_time_constant: float = scenario_default("observer.bias_time_constant")
    k4_bis: tuple[float, float, float] = scenario_default("observer.k4_bis")
    k3_ratio: float = scenario_default("observer.k3_ratio")

    def __post_init__(self) -> None:
        if len(self.k4_bis) != 3:
            raise ValueError("observer.k4_bis: 3 values (surge, sway, yaw)")
        for name in ("wave_period", "wave_damping", "notch_damping", "cutoff_ratio", "bias_time_constant",
                     "k3_ratio", *(f"k4_bis[{i}]" for i in range(3))):
            value = self.k4_bis[int(name[-2])] if name.startswith("k4_bis") else getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                    math.isfinite(value) and value > 0.0):
                raise ValueError(f"observer.{name}: a finite number > 0, not {value!r}")
        if not self.wave_damping < self.notch_damping:
            raise ValueError(f"observer.wave_damping: below notch_damping (lambda < zeta_n), not "
                             f"{self.wave_damping:g} >= {self.notch_damping:g}")
        if not self.cutoff_ratio > 1.0:
            raise ValueError(f"observer.cutoff_ratio: omega_c / omega_o > 1, not {self.cutoff_ratio:g}")
        if not self.k3_ratio < self.omega_o:
            raise ValueError(f"observer.k3_ratio: K3 / K4 below omega_o = {self.omega_o:.4g} rad/s (Fossen's "
                             f"1/T << K3/K4 < omega_o), not {self.k3_ratio:g}")
        if not 1.0 / self.bias_time_constant <= 0.1 * self.k3_ratio:
            raise ValueError(f"observer.bias_time_constant: 1/T << K3/K4, taken as 1/T at most K3/K4 / 10 "
                             f"(T >= {10.0 / self.k3_ratio:g} s), not T = {self.bias_time_constant:g} s")

    @property
    def omega_o(self) -> float:
        """[rad/s] the wave model's and the notch's frequency."""
        return 2.0 * math.pi / self.wave_period

    @property
    def omega_c(self) -> float:
        """[rad/s] the position loop's cut-off."""
        return self.cutoff_ratio * self.omega_o

    def k1(self) -> np.ndarray:
        """K1 (6 x 3): [diag(-2 (zeta_n - lambda) omega_c / omega_o); diag(2 omega_o (zeta_n - lambda))]."""
        gap = self.notch_damping - self.wave_damping
        return np.vstack([-2.0 * gap * self.cutoff_ratio * np.eye(3), 2.0 * self.omega_o * gap * np.eye(3)])

    def k4(self, mass: float, length: float) -> np.ndarray:
        """K4 [N/m, N/m, N m/rad] from the bis values: m g / L for forces, m g L for the moment."""
        surge, sway, yaw = self.k4_bis
        return np.diag([surge * mass * GRAVITY / length, sway * mass * GRAVITY / length,
                        yaw * mass * GRAVITY * length])

    def describe(self) -> str:
        """The tuning in one sentence, for a report."""
        return (f"nonlinear passive observer (Fossen and Strand 1999; Fossen 2021 ch. 13): wave model at "
                f"omega_o = {self.omega_o:.3f} rad/s (Tp {self.wave_period:g} s), lambda {self.wave_damping:g}, "
                f"notch zeta_n {self.notch_damping:g}, omega_c = {self.cutoff_ratio:g} omega_o = "
                f"{self.omega_c:.3f} rad/s, bias time constant {self.bias_time_constant:g} s, "
                f"K4 = diag({', '.join(f'{k:g}' for k in self.k4_bis)}) (bis), K3 = {self.k3_ratio:g} K4")


class PassiveObserver:
    """The observer's state and its update, for a hull of mass matrix ``mass`` and linear damping
    ``damping`` (3 x 3, surge, sway, yaw), rigid-body mass ``rigid_mass`` [kg] and length [m]
    (the bis scaling of K4)."""

    def __init__(self, tuning: ObserverTuning, mass: np.ndarray, damping: np.ndarray, rigid_mass: float,
                 length: float):
        self.tuning = tuning
        omega, lam = tuning.omega_o, tuning.wave_damping
        k1, k2 = tuning.k1(), tuning.omega_c * np.eye(3)
        self.k4 = tuning.k4(rigid_mass, length)
        self.k3 = tuning.k3_ratio * self.k4
        self.mass_inverse = np.linalg.inv(np.asarray(mass, dtype=float))
        self._minus_md = -self.mass_inverse @ np.asarray(damping, dtype=float)
        a = np.zeros((STATES, STATES))
        a[0:3, 3:6] = np.eye(3)
        a[3:6, 0:3] = -omega ** 2 * np.eye(3)
        a[3:6, 3:6] = -2.0 * lam * omega * np.eye(3)
        gain = np.zeros((STATES, 3))                 # the gains on y~ of every state but nu
        gain[0:6], gain[6:9], gain[9:12] = k1, k2, self.k3
        a[:, 3:6] -= gain                             # y~ = y - eta - xi_2
        a[:, 6:9] -= gain
        a[9:12, 9:12] -= np.eye(3) / tuning.bias_time_constant
        a[12:15, 12:15] = self._minus_md
        self._base, self._gain = a, gain
        self.state = np.zeros(STATES)

    @property
    def eta(self) -> np.ndarray:
        """[north, east, heading] low-frequency estimate."""
        return self.state[6:9]

    @property
    def nu(self) -> np.ndarray:
        """[u, v, r] estimate."""
        return self.state[12:15]

    @property
    def bias(self) -> np.ndarray:
        """[N, N, N m] bias estimate (NED)."""
        return self.state[9:12]

    @property
    def wave(self) -> np.ndarray:
        """[north, east, heading] wave-frequency estimate C_w xi."""
        return self.state[3:6]

    def start(self, measured: np.ndarray, bias: np.ndarray | None = None) -> None:
        """Start at rest on the measurement, no wave motion, the bias ``bias`` [N, N, N m] (NED)."""
        self.state = np.zeros(STATES)
        self.state[6:9] = measured
        if bias is not None:
            self.state[9:12] = bias

    def matrices(self, heading: float) -> np.ndarray:
        """A(psi_y): the observer's system matrix at the measured heading (x' = A x + B u)."""
        c, s = math.cos(heading), math.sin(heading)
        rotation = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        a = self._base.copy()
        a[6:9, 12:15] = rotation
        to_body = self.mass_inverse @ rotation.T
        a[12:15, 9:12] = to_body
        k4 = to_body @ self.k4
        a[12:15, 3:6] -= k4
        a[12:15, 6:9] -= k4
        return a

    def step(self, measured: np.ndarray, tau: np.ndarray, dt: float) -> None:
        """One period ``dt`` [s] on with the measurement [north, east, heading] and the wrench
        ``tau`` [X, Y, N] held over it."""
        heading = float(measured[2])
        y = np.array(measured, dtype=float)
        y[2] = self.state[8] + self.state[5] + wrap(heading - self.state[8] - self.state[5])   # unwrapped near y^
        a = self.matrices(heading)
        c, s = math.cos(heading), math.sin(heading)
        b = np.zeros(STATES)
        b[:12] = self._gain[:12] @ y
        b[12:15] = self.mass_inverse @ (np.asarray(tau, dtype=float) + np.array([[c, s, 0.0], [-s, c, 0.0],
                                                                                 [0.0, 0.0, 1.0]]) @ (self.k4 @ y))
        x = self.state
        k1 = a @ x + b
        k2 = a @ (x + 0.5 * dt * k1) + b
        k3 = a @ (x + 0.5 * dt * k2) + b
        k4 = a @ (x + dt * k3) + b
        self.state = x + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        self.state[8] = wrap(self.state[8])
