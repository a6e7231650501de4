"""What a method's solve gives back: the extended force vector and how the solve went."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(slots=True)
class MethodOutput:
    """A method's answer: the extended force vector (1.16), and how the solve went.
    ``angle`` optionally proposes the angle of each actuator (nonlinear method); ``turn``
    the angle toward which an idle rotatable thruster (by actuator index) turns instead of its
    limits' goal (the nonlinear method's descent direction)."""

    force: np.ndarray
    status: str
    iterations: int = 0
    solve_time: float = 0.0
    solved: bool = True
    angle: np.ndarray | None = None
    turn: dict[int, float] | None = None
