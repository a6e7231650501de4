"""Configuration-time arrays shared by the allocation methods, and the limits the allocator
hands a method each sample (:class:`SampleLimits`, with :class:`AzimuthLimits` per rotatable
thruster).

A :class:`Model` is computed once per configuration (never per sample): index maps,
the extended configuration matrix T_e restricted to the controlled DOFs, weights and
limits as arrays.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..vehicle.config import ActuatorConfig, RotationConfig, Vehicle
from .actuators import lift_gain
from .configuration_matrix import extended_columns, extended_configuration_matrix

DEFAULT_SLACK_RATIO = 1e6
"""Default Q_k: a wrench error of 1/1000 of DOF k's authority costs as much as every
actuator at full force, sum_i c_i F_i^2 with c_i the effort curvature (W_ii in the qp method)."""

AT_LIMIT = 1e-3
"""An actuator within this fraction of a limit sits at it: a thrust at an end of its range in
force, a change of a full rate step, a thruster at its polygon's bound. The limit flags of a
result, the diagnostics, the markers and the qp method's reading of multipliers all use it."""

SATURATION_TOLERANCE = 1e-3
"""A request counts as met when every controlled DOF is within this fraction of the DOF's
authority of it (Model.dof_scale)."""

HOLD_FRACTION = 1e-4
"""Below this fraction of thrust_max a force is too small to define an angle; the angle holds."""

REFERENCE_FLOW_SPEED = 2.0
"""[m/s] Flow speed at which a control surface's force range sets its numerical scale."""


def _force_scale(actuator: ActuatorConfig, water_density: float) -> float:
    """The order of magnitude of an actuator's force, for scaling the solver's problem."""
    if actuator.is_surface:
        surface = actuator.surface
        speed = max(REFERENCE_FLOW_SPEED, 2.0 * surface.min_control_speed) / (
            surface.wake_speed_factor if surface.flow == "propeller_wake" else 1.0)
        return max(lift_gain(surface, water_density, speed) * surface.deflection_max, 1e-6)
    return max(actuator.thrust_max, -actuator.thrust_min)


@dataclass(frozen=True)
class Model:
    """The configuration as arrays, computed once per configuration (never per sample).

    r actuators, m extended columns (a rotatable thruster has two, (1.16)-(1.18)), n
    controlled DOFs. Per actuator unless said otherwise:

    - ``dof_index`` (n): rows of tau that are controlled, in DOF_NAMES order;
    - ``rotatable`` (bool), ``rot``, ``scalar``, ``surfaces``: which actuators rotate, the
      indices of those that do and of those that do not, and of the control surfaces;
    - ``starts``: first extended column of each actuator; ``scalar_columns``: the column of
      each non-rotating one; ``rot_columns`` (p x 2): the two columns of each rotating one;
      ``extended_owner`` (m): the actuator of each extended column;
    - ``t_e`` (6 x m): the extended configuration matrix (1.17)/(1.22); ``t_ec`` (n x m): its
      controlled rows;
    - ``weight``, ``weight_ext`` (m): W_ii of (1.24)/(1.35), per actuator and per column;
      ``power``: P_i of (1.44);
    - ``thrust_min``, ``thrust_max``: force limits (0 for control surfaces, whose range
      depends on speed); ``thrust_step``: largest force change per sample (a control
      surface: deflection change per sample), inf when not limited; ``angle_step``: largest
      azimuth change per sample (0 for actuators that do not rotate);
    - ``hold``: the force below which a rotatable thruster's angle is undefined and held;
    - ``force_scale``: the order of magnitude of each actuator's force (solver scaling);
    - ``authority`` (n): the largest force or moment all actuators together give in each
      controlled DOF.
    """

    vehicle: Vehicle
    dt: float
    dof_index: np.ndarray
    rotatable: np.ndarray
    rot: np.ndarray
    scalar: np.ndarray
    surfaces: np.ndarray
    starts: np.ndarray
    scalar_columns: np.ndarray
    rot_columns: np.ndarray
    extended_owner: np.ndarray
    t_e: np.ndarray
    t_ec: np.ndarray
    weight: np.ndarray
    weight_ext: np.ndarray
    power: np.ndarray
    thrust_min: np.ndarray
    thrust_max: np.ndarray
    thrust_step: np.ndarray
    angle_step: np.ndarray
    hold: np.ndarray
    force_scale: np.ndarray
    authority: np.ndarray

    def slack_weights(self, curvature: np.ndarray) -> np.ndarray:
        """Q: the configured weights.slack, or the default for an effort curvature c_i per
        actuator (see DEFAULT_SLACK_RATIO)."""
        if self.vehicle.weights.slack:
            return np.array(self.vehicle.weights.slack)
        effort = float(np.sum(curvature * self.force_scale ** 2))
        return DEFAULT_SLACK_RATIO * effort / self.dof_scale ** 2

    @property
    def dof_scale(self) -> np.ndarray:
        """The authority of each controlled DOF, the largest one standing in for a DOF that no
        actuator reaches: the yardstick of wrench errors (slack weights, the saturation flag).
        An authority below 1e-9 of the largest authority or actuator force counts as none, and
        the larger of those two stands in for it."""
        reach = max(float(np.max(self.authority, initial=0.0)), float(np.max(self.force_scale, initial=0.0))) or 1.0
        return np.where(self.authority > 1e-9 * reach, self.authority, reach)

    @property
    def dof_tolerance(self) -> np.ndarray:
        """How far a wrench may miss the request in each controlled DOF and still count as met
        (SATURATION_TOLERANCE of the DOF's authority)."""
        return SATURATION_TOLERANCE * self.dof_scale

    @property
    def r(self) -> int:
        return len(self.vehicle.actuators)

    @property
    def n(self) -> int:
        return len(self.dof_index)

    @property
    def m(self) -> int:
        return self.t_e.shape[1]

    @property
    def structure(self) -> tuple:
        """What fixes the sparsity pattern of the solver matrices; a configuration change
        that keeps it is applied by updating values only."""
        v = self.vehicle
        return (tuple(a.type for a in v.actuators), v.dofs, v.azimuth_polygon_sides, v.saturation,
                bool(v.priority_levels))

    @classmethod
    def build(cls, vehicle: Vehicle, dt: float) -> Model:
        actuators = vehicle.actuators
        rotatable = np.array([a.rotatable for a in actuators], dtype=bool)
        surfaces = np.array([a.is_surface for a in actuators], dtype=bool)
        starts = np.array(extended_columns(actuators), dtype=int)
        t_e = extended_configuration_matrix(actuators)
        dof_index = np.array(vehicle.dof_indices, dtype=int)
        owner = np.concatenate([[i] * (2 if a.rotatable else 1) for i, a in enumerate(actuators)]).astype(int)
        weight = np.array([a.weight for a in actuators])

        def per_second(rate: float) -> float:
            return rate * dt if rate > 0.0 else math.inf

        thrust_step = np.array([
            per_second(a.surface.deflection_rate_max if a.is_surface else a.thrust_rate_max) for a in actuators
        ])
        angle_step = np.array([per_second(a.rotation.rate_max) if a.rotatable else 0.0 for a in actuators])
        thrust_max = np.array([0.0 if a.is_surface else a.thrust_max for a in actuators])
        force_scale = np.array([_force_scale(a, vehicle.water_density) for a in actuators])
        rot = np.flatnonzero(rotatable)
        scalar = np.flatnonzero(~rotatable)
        return cls(
            vehicle=vehicle,
            dt=dt,
            dof_index=dof_index,
            rotatable=rotatable,
            rot=rot,
            scalar=scalar,
            surfaces=np.flatnonzero(surfaces),
            starts=starts,
            scalar_columns=starts[scalar],
            rot_columns=np.stack([starts[rot], starts[rot] + 1], axis=1) if rot.size else np.zeros((0, 2), int),
            extended_owner=owner,
            t_e=t_e,
            t_ec=t_e[dof_index],
            weight=weight,
            weight_ext=weight[owner],
            power=np.array([a.power_coefficient for a in actuators]),
            thrust_min=np.array([0.0 if a.is_surface else a.thrust_min for a in actuators]),
            thrust_max=thrust_max,
            thrust_step=thrust_step,
            angle_step=angle_step,
            hold=HOLD_FRACTION * np.maximum(thrust_max, 1e-6),
            force_scale=force_scale,
            authority=np.abs(t_e[dof_index]) @ force_scale[owner],
        )


FIXED_TOLERANCE = 1e-12
"""Bounds closer than this [N, rad] leave an actuator no freedom."""


@dataclass(slots=True)
class AzimuthLimits:
    """Allowed this sample: angles in [low, high] (absolute; either the whole circle, -inf to
    inf, or at most pi wide, containing the current angle unless a crossing moves it), thrust
    F in [thrust_low, thrust_high] along the angle, on the side sigma (+1 forward, -1
    reverse). ``line`` means the angle is fixed (STUCK) and F may take either sign within its
    bounds. ``goal`` is the angle the wanted force
    points to (on this side): an idle thruster turns toward it. ``physical_max`` is the largest
    thrust magnitude on this side with faults applied, before any rate limit."""

    low: float
    high: float
    sigma: int
    thrust_low: float
    thrust_high: float
    line: bool = False
    goal: float | None = None
    physical_max: float = math.inf

    @property
    def magnitude_max(self) -> float:
        return max(abs(self.thrust_low), abs(self.thrust_high))


@dataclass(slots=True)
class SampleLimits:
    """What one sample allows. ``low``/``high``: signed force bounds of every actuator
    (for rotatable thrusters, along the angle, from their ``azimuth`` limits);
    ``azimuth``: one :class:`AzimuthLimits` per rotatable thruster, at indices ``rot``;
    ``angle``/``thrust``: the state at the start of the sample. ``version`` changes whenever
    ``low``, ``high`` or ``azimuth`` may have: a method keeps what it derives from them
    (pseudo-inverse gains, the solver's box rows) while it stays; -1 means every sample.
    ``range_low``/``range_high``: the static force ranges that faults and speed leave, before
    any rate limit (None: the same as ``low``/``high``). ``rotations``: each rotatable thruster's
    rotation with the sectors in force, flushing zones included (None: the configuration's).
    ``bias``: the thrust bias's extended force offset b of this sample (:mod:`~.thrust_bias`;
    None: no bias), about which a method that implements it allocates. Nothing here is changed
    by a method."""

    low: np.ndarray
    high: np.ndarray
    rot: np.ndarray
    azimuth: list[AzimuthLimits]
    angle: np.ndarray
    thrust: np.ndarray
    version: int = -1
    range_low: np.ndarray | None = None
    range_high: np.ndarray | None = None
    rotations: list[RotationConfig] | None = None
    bias: np.ndarray | None = None

    def fixed(self) -> np.ndarray:
        """Actuators whose force the limits alone decide this sample (a rotatable thruster:
        its angle too, or a thrust that must be zero, where the angle does not matter)."""
        fixed = self.high - self.low <= FIXED_TOLERANCE
        for i, limits in zip(self.rot, self.azimuth):
            fixed[i] = fixed[i] and (limits.high - limits.low <= FIXED_TOLERANCE or limits.magnitude_max == 0.0)
        return fixed
