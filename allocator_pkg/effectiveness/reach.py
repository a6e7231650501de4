"""Which directions the actuators reach: rank tests on the extended configuration matrix T_e
(1.17), which only the geometry decides, for the operator's warnings and notes."""

from __future__ import annotations

import numpy as np

from ..vehicle.config import DOF_NAMES
from .model import Model

PLANE = ("surge", "sway", "yaw")
"""The horizontal plane, in which a vehicle is under-actuated if its actuators cannot give
independent forces in all three."""

RANK_TOLERANCE = 1e-9
"""Singular values of T_e below this count as zero in the rank tests."""


def reachability_warnings(model: Model) -> list[str]:
    """Controlled DOFs, or combinations of them, that no actuator can produce."""
    warnings = []
    dofs = model.vehicle.dofs
    for k, dof in enumerate(dofs):
        if not np.any(np.abs(model.t_ec[k]) > 1e-12):
            warnings.append(f"no actuator can produce {dof}; requests in it will always be saturated")
    rank = np.linalg.matrix_rank(model.t_ec, tol=RANK_TOLERANCE)
    if rank < model.n and not warnings:
        warnings.append(f"the actuators reach only {rank} independent directions of the {model.n} controlled DOFs "
                        f"({', '.join(dofs)}); some combinations will be saturated")
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
