"""Which directions the actuators reach: rank tests on the extended configuration matrix T_e
(1.17), which only the geometry decides, for the operator's warnings and notes."""

from __future__ import annotations

import numpy as np

from ..vehicle.config import DOF_NAMES, ActuatorConfig
from .configuration_matrix import NEGLIGIBLE, extended_configuration_matrix
from .model import Model

PLANE = ("surge", "sway", "yaw")
"""The horizontal plane, in which a vehicle is under-actuated if its actuators cannot give
independent forces in all three."""

RANK_TOLERANCE = 1e-9
"""Singular values of T_e below this count as zero in the rank tests."""

WEAK_SHARE = 0.01
"""A controlled DOF whose authority is below this share of the strongest other one is weak: a
request of a few per cent of the others' capability saturates it. Authorities compare as
forces, a moment divided by the vehicle's largest lever (the farthest actuator from the
origin), so that the share does not depend on the units."""

FORCES = ("surge", "sway", "heave")
"""The DOFs whose authority is a force; the others' is a moment."""


def unreachable_dofs(actuators: tuple[ActuatorConfig, ...], dofs: tuple[str, ...]) -> list[str]:
    """Controlled DOFs that no actuator can produce at any angle: a zero row of T(alpha) for every
    allowed alpha, with every actuator nominal.

    The row of T_e (1.17) decides it: a fixed thruster or a control surface adds its single
    column (a surface's force at any deflection is a multiple of it, (1.48)), and a rotatable
    thruster's entry in T(alpha) is cos(alpha) c1 + sin(alpha) c2 of its two columns, nonzero at
    all but two angles per turn if c1 or c2 is, so at some angle of any allowed arc of positive
    width (the loader refuses narrower ones).
    """
    t_e = extended_configuration_matrix(actuators)
    return [dof for dof in dofs if not np.any(np.abs(t_e[DOF_NAMES.index(dof)]) > NEGLIGIBLE)]


def weak_dofs(model: Model) -> list[tuple[str, float]]:
    """Controlled DOFs that can be produced but only weakly (WEAK_SHARE), each with its share of
    the strongest other DOF's authority (moments divided by the largest lever)."""
    dofs = model.vehicle.dofs
    lever = max((float(np.linalg.norm(a.position)) for a in model.vehicle.actuators), default=0.0) or 1.0
    comparable = np.array([value if dof in FORCES else value / lever for dof, value in zip(dofs, model.authority)])
    weak = []
    for k, dof in enumerate(dofs):
        others = np.delete(comparable, k)
        strongest = float(np.max(others, initial=0.0))
        if comparable[k] > 0.0 and strongest > 0.0 and comparable[k] < WEAK_SHARE * strongest:
            weak.append((dof, float(comparable[k] / strongest)))
    return weak


def reachability_warnings(model: Model) -> list[str]:
    """Controlled DOFs, or combinations of them, that no actuator can produce, and DOFs that
    the actuators produce only weakly (:func:`weak_dofs`)."""
    warnings = []
    dofs = model.vehicle.dofs
    for k, dof in enumerate(dofs):
        if not np.any(np.abs(model.t_ec[k]) > 1e-12):
            warnings.append(f"no actuator can produce {dof}; requests in it will always be saturated")
    rank = np.linalg.matrix_rank(model.t_ec, tol=RANK_TOLERANCE)
    if rank < model.n and not warnings:
        warnings.append(f"the actuators reach only {rank} independent directions of the {model.n} controlled DOFs "
                        f"({', '.join(dofs)}); some combinations will be saturated")
    for dof, share in weak_dofs(model):
        warnings.append(f"{dof} is weak: its authority is {100.0 * share:.2g} % of the strongest other DOF's "
                        f"(moments per metre of the largest lever); requests in it saturate early")
    return warnings


def actuation_notes(model: Model) -> list[str]:
    """Whether the actuators give independent forces in surge, sway and yaw, the plane every
    marine vehicle moves in; if not, and the configuration leaves some of them to the vehicle,
    it is under-actuated by design (a controlled DOF out of reach is a warning instead)."""
    left = [dof for dof in PLANE if dof not in model.vehicle.dofs]
    plane = [DOF_NAMES.index(dof) for dof in PLANE]
    rank = int(np.linalg.matrix_rank(model.t_e[plane], tol=RANK_TOLERANCE))
    if not left or rank == len(plane):
        return []
    return [f"under-actuated: the actuators give {rank} independent directions in {', '.join(PLANE)}; "
            f"{', '.join(left)} is left to the vehicle's dynamics"]
