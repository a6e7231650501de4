"""Durham's direct method (section 4.3), ``saturation: direct``, shared by the methods that
implement it (``qp``, ``lp``, ``pseudoinverse``).

The set of wrenches the actuators can give this sample is convex; along the request's
direction it ends at lambda* tau, with lambda* the largest scale the limits allow. The
linear programme

    maximise lambda  subject to  T_e f_e = lambda tau,  0 <= lambda <= 1,  f_e within this sample's limits

finds it, and the simplex method stops at a vertex: n - 1 actuators strictly inside their
limits and every other one at a limit, which is Durham's unique solution on a facet of the
attainable set (for actuators in general position; where several solutions reach lambda*,
the cheapest in the weighted 1-norm is taken). For an unattainable request (lambda* < 1) that
vertex is the answer: lambda* tau, the request scaled back into the attainable set along its
own direction. An attainable request (lambda* = 1) keeps the method's own minimum-norm answer
when it is within the limits; the pseudo-inverse, which is not always, takes this programme's
solution at lambda = 1 then (the request met exactly, with the least weighted 1-norm).

Rotatable thrusters: the circle |f| <= B as the inscribed polygon of 4N sides (N =
``azimuth_polygon_sides``), so that lambda* tau is met without any thrust being clipped (the
direction is kept exactly) at the cost of at most 1 - cos(pi / 4N) of a thruster's force
(0.48 % for N = 8); sectors and rate limits as in ``lp``.
"""

from __future__ import annotations

import math

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from .base import MethodOutput
from .sample_lp import SampleLP

SIDES_FACTOR = 4
"""The direct method's polygon has this many times ``azimuth_polygon_sides`` sides."""


def direct_sides(sides: int) -> int:
    return SIDES_FACTOR * sides


class DirectSolution:
    """The largest scale of a request this sample's limits allow, and the forces on the
    boundary of the attainable set that give it (see the module)."""

    def __init__(self, model: Model):
        sides = direct_sides(model.vehicle.azimuth_polygon_sides)
        self._lp = SampleLP(model, sides, math.cos(math.pi / sides), "scale", scale_max=1.0)

    def update_model(self, model: Model) -> None:
        self._lp.update_model(model)

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        """The boundary solution for ``tau`` (the request itself when attainable); ``status``
        names lambda*."""
        solution = self._lp.solve(tau, limits)
        status = f"direct: lambda {self._lp.scale(solution):.6g}" if solution.usable else f"direct: {solution.status}"
        return MethodOutput(force=self._lp.force(solution), status=status, iterations=solution.iterations,
                            outcome=solution.outcome)
