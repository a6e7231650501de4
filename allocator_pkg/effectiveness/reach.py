"""Which directions the actuators reach: rank tests on the extended configuration matrix T_e
(1.17), which only the geometry decides, for the operator's warnings and notes; and, under
faults, which of those the working actuators no longer reach."""

from __future__ import annotations

import numpy as np

from ..vehicle.config import DOF_NAMES, ActuatorConfig
from .configuration_matrix import NEGLIGIBLE, actuator_direction, extended_configuration_matrix, force_column
from .faults import FaultMode, FaultSet
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


def working_columns(model: Model, faults: FaultSet) -> np.ndarray:
    """The controlled rows of the columns the working actuators can still vary (n x k): none of a
    failed actuator or of a stuck control surface (pinned at its deflection's force), one of a
    rotatable thruster stuck at its azimuth (its T(alpha) column there), every extended column
    of the others (a degraded one keeps its directions)."""
    rows = [DOF_NAMES.index(dof) for dof in model.vehicle.dofs]
    columns = []
    for i, actuator in enumerate(model.vehicle.actuators):
        if faults.modes[i] == FaultMode.FAILED or (i in faults.stuck and not actuator.rotatable):
            continue
        if i in faults.stuck:
            columns.append(force_column(actuator.position, actuator_direction(actuator, faults.stuck[i]))[rows])
        else:
            columns += list(model.t_ec[:, model.extended_owner == i].T)
    return np.column_stack(columns) if columns else np.zeros((len(rows), 0))


def _rank(matrix: np.ndarray) -> int:
    return int(np.linalg.matrix_rank(matrix, tol=RANK_TOLERANCE)) if matrix.size else 0


def lost_reach(model: Model, faults: FaultSet) -> list[str]:
    """What the working actuators (:func:`working_columns`) no longer reach that every actuator
    does, in words: the controlled DOFs none of them produces, then, when fewer independent
    directions are left than those DOFs explain, the DOFs they produce only together with
    others (a DOF reached alone is a unit wrench in the span of the columns). Empty without
    faults or with no loss."""
    if not faults.faults:
        return []
    dofs = model.vehicle.dofs
    working = working_columns(model, faults)
    lost = [dof for k, dof in enumerate(dofs)
            if np.any(np.abs(model.t_ec[k]) > 1e-12) and not np.any(np.abs(working[k]) > 1e-12)]
    lines = [f"after the faults no working actuator produces {dof}; requests in it will always be saturated"
             for dof in lost]
    rank, intact = _rank(working), _rank(model.t_ec)
    unit = np.eye(len(dofs))
    alone = [dof for k, dof in enumerate(dofs) if dof not in lost
             and _rank(np.column_stack([model.t_ec, unit[k]])) == intact
             and _rank(np.column_stack([working, unit[k]])) > rank]
    if alone or rank + len(lost) < intact:            # more lost than the DOFs no actuator produces
        together = f"; {', '.join(alone)} only together with other DOFs" if alone else ""
        lines.append(f"after the faults the working actuators reach {rank} independent direction"
                     f"{'' if rank == 1 else 's'} of the "
                     f"{len(dofs)} controlled DOFs ({', '.join(dofs)}), {intact} with every actuator{together}; "
                     "some combinations will be saturated")
    return lines
