"""The thrust bias in method ``qp``'s objective (docs/theory.md, thrust bias): the effort term
f'Wf of (1.35) taken about the offset b of :mod:`~allocator_pkg.effectiveness.thrust_bias`,

    (f - b)' W (f - b) = f'Wf - 2 b'W f + const,

a linear term q = -P b (P = 2W, the problem's diagonal) and nothing else: the rows, bounds
and P stay, so the solver takes a new q, never a new set-up. A rotatable thruster's columns
hold its force in the frame turned to the direction d it pushes in (u along d, v across, as
:mod:`~.qp` writes them), so its offset is turned too: (u, v)-terms -P R(d)' b_i.
"""

from __future__ import annotations

import numpy as np

from .qp_problem import QPProblem


def biased_objective(problem: QPProblem, bias: np.ndarray | None, rot_columns: list[tuple[int, int]]) -> None:
    """Send ``problem`` the linear term of this sample's ``bias`` (None: the problem's own q
    again, once, after a biased sample); nothing when neither this nor the last sample is biased."""
    if bias is None and not problem.biased:
        return
    q = problem.q.copy()
    if bias is not None:
        p = problem.p_diagonal
        for (c1, c2), cos, sin in zip(rot_columns, problem.cos, problem.sin):
            x, y = bias[c1], bias[c2]
            if x or y:
                q[c1] = -p[c1] * (cos * x + sin * y)
                q[c2] = -p[c2] * (cos * y - sin * x)
    problem.qp.update_objective(q=q)
    problem.biased = bias is not None
