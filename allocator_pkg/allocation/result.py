"""What one sample gives back, and what an allocator has counted since it was made."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..solvers.outcome import Outcome


@dataclass(slots=True, kw_only=True)
class AllocationResult:
    """One sample's answer; arrays are per actuator in configuration order. ``thrust``,
    ``azimuth``, ``mode``, ``available`` (and ``at_rate_limit`` of a vehicle without rate
    limits) are shared with the allocator and read-only.

    ``outcome`` says what the sample ended as (``status`` says it in words, with the solver's
    own text; ``residual`` is the solver's primal residual where it reports one; ``reason``,
    for a fallback, the failed method's status). ``unallocated`` (6, [X, Y, Z, K, M, N]) is
    requested minus achieved in the controlled DOFs (0 in the others), what a controller needs
    for anti-windup; ``short`` names the controlled DOFs it misses by more than their tolerance
    (those that make it ``saturated``). ``at_thrust_limit`` flags the actuators at an end of
    the force range in force (faults, voltage, speed), ``at_rate_limit`` those that moved
    their thrust (a control surface: its deflection) or their angle by a full rate step this
    sample."""

    thrust: np.ndarray
    azimuth: np.ndarray
    command: np.ndarray
    achieved: np.ndarray
    requested: np.ndarray
    saturated: bool
    status: str
    iterations: int
    solve_time: float
    power: float
    method: str
    mode: np.ndarray
    available: np.ndarray
    unallocated: np.ndarray
    at_thrust_limit: np.ndarray
    at_rate_limit: np.ndarray
    drag: float = 0.0
    outcome: Outcome = Outcome.SOLVED
    short: tuple[str, ...] = ()
    residual: float | None = None
    reason: str = ""


@dataclass
class AllocatorStats:
    """Counters since the allocator was made: solver set-ups, samples, fallbacks (a solve the
    pseudo-inverse answered, counted per solve: the drag feed-forward may solve more than once
    a sample)."""

    solver_setups: int = 0
    samples: int = 0
    fallbacks: int = 0
