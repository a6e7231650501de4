"""Thrust bias: pairs of rotatable thrusters pushing against each other at low load
(docs/theory.md, thrust bias).

A pair (i, j) of rotatable thrusters turning in one plane, with the basis (e1, e2) of
:func:`~.configuration_matrix.rotation_basis`, gets the extended force offset

    b_i = beta d,   b_j = -beta d,   d = P (r_j - r_i) / |P (r_j - r_i)|,

d the unit vector in the plane from thruster i toward thruster j (P the projection on the
plane): each pushes toward the other, its jet away from the other. Its wrench (1.5) is
T_e b = beta [0 ; (r_i - r_j) x d], zero when r_i - r_j lies in the plane (the pair at one
height for azimuths); the configuration refuses a pair whose offset leaves a wrench in a
controlled DOF. The QP is solved about f_e = b instead of 0 (docs/theory.md), so the
thrusters keep most of beta along d and their angles move by about |delta f| / beta where
without bias a small force swings them across the circle.

beta fades with the load L = max_k |tau_k| / authority_k, low-pass filtered with the time
constant ``fade_time_constant``: beta = bias.thrust for L up to ``fade_start``, 0 from
``fade_end`` on, linear between. The filter keeps beta from following the gusts: a beta that
changed with every sample's load would swing the thrusters between the pair's line and the
load's direction, more than the bias saves. A pair whose thruster is failed, stuck or left by a
fault with no more than bias.thrust pushes none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..vehicle.config import ActuatorConfig, Vehicle
from .configuration_matrix import extended_configuration_matrix, rotation_basis
from .model import Model

COINCIDENT = 1e-6
"""[m] Thrusters of a pair closer than this in their plane of rotation have no direction between them."""
WRENCH_TOLERANCE = 1e-9
"""A pair's offset of 1 N may leave at most this [N, N m] in a controlled DOF."""


@dataclass(frozen=True)
class BiasPair:
    """One pair: the actuator indices and the unit direction (in the first thruster's basis
    e1, e2) along which the first pushes; the second pushes the opposite way."""

    first: int
    second: int
    direction: tuple[float, float]


def pair_direction(first: ActuatorConfig, second: ActuatorConfig) -> tuple[float, float] | None:
    """The unit direction (e1, e2 components) from ``first`` toward ``second`` in their plane of
    rotation; None when they stand at one point of it."""
    e1, e2 = rotation_basis(first.type)
    offset = np.asarray(second.position, dtype=float) - np.asarray(first.position, dtype=float)
    components = np.array([offset @ e1, offset @ e2])
    length = float(np.hypot(*components))
    if length < COINCIDENT:
        return None
    return float(components[0] / length), float(components[1] / length)


def pair_wrench(first: ActuatorConfig, second: ActuatorConfig, direction: tuple[float, float]) -> np.ndarray:
    """The wrench [X, Y, Z, K, M, N] of 1 N along ``direction`` on ``first`` and -1 N on
    ``second``: T_e b for beta = 1."""
    t_e = extended_configuration_matrix((first, second))
    return t_e @ np.array([direction[0], direction[1], -direction[0], -direction[1]])


def bias_pairs(vehicle: Vehicle) -> tuple[BiasPair, ...]:
    """The configured pairs with their directions (the configuration has checked them)."""
    index = {name: k for k, name in enumerate(vehicle.names)}
    pairs = []
    for first, second in vehicle.bias.pairs:
        i, j = index[first], index[second]
        pairs.append(BiasPair(i, j, pair_direction(vehicle.actuators[i], vehicle.actuators[j])))
    return tuple(pairs)


def fade(load: float, start: float, end: float) -> float:
    """The share of the bias at ``load``: 1 up to ``start``, 0 from ``end``, linear between."""
    if load <= start:
        return 1.0
    if load >= end:
        return 0.0
    return (end - load) / (end - start)


class ThrustBias:
    """The extended force offset b of each sample (:meth:`offsets`), from the configuration
    (:meth:`configure`), the faults in force (:meth:`refresh`: which pairs can push) and the
    load, low-pass filtered (``load``: its value so far, None before the first sample with the
    bias on)."""

    def __init__(self) -> None:
        self.load: float | None = None

    def configure(self, model: Model) -> None:
        """The pairs (none unless bias.enabled), their columns, the yardstick of the load
        (``Model.dof_scale``) and its filter's gain per sample; the filtered load carries over
        while the bias stays on."""
        settings = model.vehicle.bias
        self.thrust = settings.thrust
        self.fade_start, self.fade_end = settings.fade_start, settings.fade_end
        self.pairs = bias_pairs(model.vehicle) if settings.enabled else ()
        self._columns = [(int(model.starts[p.first]), int(model.starts[p.second])) for p in self.pairs]
        self._scale = 1.0 / model.dof_scale
        self._gain = 1.0 - math.exp(-model.dt / settings.fade_time_constant) if settings.fade_time_constant > 0.0 \
            else 1.0
        self._m = model.m
        self._available: list[int] = []
        if not self.pairs:
            self.load = None

    def refresh(self, high: np.ndarray, stuck: dict[int, float]) -> None:
        """The pairs that can push under the faults in force: neither thruster stuck, and both
        able to give more than bias.thrust (``high``: each actuator's largest force)."""
        self._available = [k for k, p in enumerate(self.pairs)
                           if p.first not in stuck and p.second not in stuck
                           and min(high[p.first], high[p.second]) > self.thrust]

    def offsets(self, tau: np.ndarray) -> np.ndarray | None:
        """b for the controlled request ``tau``: every available pair's opposed forces, faded
        by the filtered load; None when there is no bias this sample."""
        if not self.pairs:
            return None
        load = float(np.max(np.abs(tau) * self._scale))
        self.load = load if self.load is None else self.load + self._gain * (load - self.load)
        if not self._available:
            return None
        beta = self.thrust * fade(self.load, self.fade_start, self.fade_end)
        if beta == 0.0:
            return None
        offset = np.zeros(self._m)
        for k in self._available:
            (x, y), (first, second) = self.pairs[k].direction, self._columns[k]
            offset[first:first + 2] = beta * x, beta * y
            offset[second:second + 2] = -beta * x, -beta * y
        return offset
