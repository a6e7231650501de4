"""The DP control system of a closed-loop run: what it measures, how it estimates, what it
requests. Without an observer the controller (:mod:`.controller`) acts on the vessel's true
pose and velocity, as a plain simulation does; with one, as a vessel's DP system does: the
position and heading measured with the wave-frequency motion and noise on them
(:mod:`.measurement`), the nonlinear passive observer (:mod:`.observer`) estimating the
low-frequency pose, velocity and bias from them, and the controller acting on the estimate.
Wind feed-forward adds to the request minus the wind load an anemometer's wind gives on the
hull (:meth:`~.environment.Environment.wind_feedforward`) through a first-order low-pass filter
of time constant ``wind_filter`` (Fossen 2021, ch. 12, wind feed-forward); the controller's
integral then holds the rest of the environment."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .controller import Gains, StationKeeping
from .measurement import Measurement, MeasurementNoise
from .observer import ObserverTuning, PassiveObserver
from .plant import PLANAR, Plant
from .scenario_keys import scenario_default


@dataclass(frozen=True)
class ControlSystem:
    """The observer's tuning (None: the controller on the true state), the measurement noise
    and the wind feed-forward (on or off, its filter's time constant [s])."""

    observer: ObserverTuning | None = None
    noise: MeasurementNoise = field(default_factory=MeasurementNoise)
    wind_feedforward: bool = scenario_default("controller.wind_feedforward")
    wind_filter: float = scenario_default("controller.wind_filter")

    def __post_init__(self) -> None:
        if not (math.isfinite(self.wind_filter) and self.wind_filter > 0.0):
            raise ValueError(f"controller.wind_filter: a finite number > 0, not {self.wind_filter!r}")

    def describe(self) -> str:
        """The control system in a sentence, for a report."""
        if self.observer is None:
            estimate = "the controller on the true position and velocity"
        else:
            estimate = (f"the controller on the estimate of a {self.observer.describe()}, from position and "
                        f"heading measured with the wave-frequency motion and white noise (sigma "
                        f"{self.noise.position_sigma:g} m, {math.degrees(self.noise.heading_sigma):g} deg)")
        wind = (f"wind feed-forward through a {self.wind_filter:g} s low-pass filter" if self.wind_feedforward
                else "no wind feed-forward")
        return f"{estimate}; {wind}"


class DpControl:
    """The controller with what it acts on, stepped by the closed loop: :meth:`wrench` for the
    step's request, :meth:`advance` once the allocator has answered."""

    def __init__(self, system: ControlSystem, gains: Gains, plant: Plant, seed: int):
        if (system.observer is not None or system.wind_feedforward) and not plant.planar:
            raise ValueError("observer and controller.wind_feedforward: for the dp_vessel model only")
        self.system, self.plant = system, plant
        self.controller = StationKeeping(gains)
        self.dofs = PLANAR if plant.planar else list(range(6))
        self.observer = None
        if system.observer is not None:
            hull = plant.hull
            self.observer = PassiveObserver(system.observer, hull.mass, hull.linear_damping, hull.parameters.mass,
                                            hull.parameters.length)
        self.measurement = Measurement(system.noise, seed)
        self.measured = plant.eta.copy()
        self.feedforward = np.zeros(len(self.dofs))
        self.settled = np.zeros(len(self.dofs))
        """The force the integral answers (its term alone gives minus it)."""
        self.request = np.zeros(6)

    @property
    def eta(self) -> np.ndarray:
        """The pose the controller acts on."""
        return self.plant.eta if self.observer is None else self.observer.eta

    @property
    def nu(self) -> np.ndarray:
        """The velocity the controller acts on."""
        return self.plant.nu if self.observer is None else self.observer.nu

    def measure(self) -> None:
        """This step's position and heading measurement (with an observer)."""
        if self.observer is not None:
            self.measured = self.measurement.sample(self.plant.eta, self.plant.environment.wave_motion())

    def settle(self) -> None:
        """Start on station in equilibrium: the feed-forward at the wind now, the integral holding
        the rest of the mean environment's force, the observer on the first measurement with the
        bias at that rest (NED; the measured wind is an input of its model)."""
        force = self.plant.environment_force()
        self.measure()
        if self.system.wind_feedforward:
            self.feedforward = -self.plant.environment.wind_feedforward(self.measured[2])
        self.settled = force + self.feedforward
        self.controller.settle(self.plant.eta, self.settled)
        if self.observer is not None:
            c, s = math.cos(self.plant.eta[2]), math.sin(self.plant.eta[2])
            self.observer.start(self.measured, np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
                                @ (force + self.feedforward))

    def balance(self, delivered: np.ndarray) -> None:
        """Take up in the integral what the thrusters' wrench ``delivered`` (in the controller's
        DOFs) falls short of the equilibrium, minus the mean environment's force."""
        self.settled = self.settled - (-self.plant.environment_force() - delivered)
        self.controller.settle(self.plant.eta, self.settled)

    def wrench(self, setpoint: np.ndarray) -> np.ndarray:
        """The request [X, Y, Z, K, M, N] for this step (kept for the observer)."""
        self.request = np.zeros(6)
        self.request[self.dofs] = self.controller.wrench(self.eta, self.nu, setpoint) + self.feedforward
        return self.request

    def advance(self, setpoint: np.ndarray, dt: float, unallocated: np.ndarray) -> None:
        """After the allocator's answer: the integral (held where the allocator is short), the
        feed-forward's filter, and the observer one step on with the known forces: what was
        allocated (the request less ``unallocated``, in the controller's DOFs) and, with wind
        feed-forward, the measured wind's load (Fossen 2021, ch. 13: the wind force an input
        of the observer's model)."""
        self.controller.integrate(self.eta, setpoint, dt, unallocated)
        wind = np.zeros(len(self.dofs))
        if self.system.wind_feedforward:
            heading = self.measured[2] if self.observer is not None else self.plant.eta[2]
            wind = self.plant.environment.wind_feedforward(heading)
            self.feedforward += (1.0 - math.exp(-dt / self.system.wind_filter)) * (-wind - self.feedforward)
        if self.observer is not None:
            self.observer.step(self.measured, self.request[self.dofs] - unallocated + wind, dt)
