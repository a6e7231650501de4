"""Linear programming allocation (section 5.3): the survey's criterion, a weighted sum of
force magnitudes against the magnitudes of the wrench error,

    minimise   sum_i w_i |f_i| + sum_j w_j (|f_xj| + |f_yj|) + sum_k q_k |s_k|
    subject to T_e f_e - s = tau, and this sample's limits,

with each rotatable thruster's magnitude as the 1-norm of its x/y components and its thrust
circle (1.46) as the survey's polygon of N = ``azimuth_polygon_sides`` sides (octagon by
default) between the inscribed and circumscribed ones, whose magnitude error is
+-tan^2(pi/2N), +-3.96 % for the octagon; sectors and rate limits as in ``qp``
(:class:`~.sample_lp.SampleLP`). q_k is ``weights.slack`` when configured, else 1e4 times the
effort of all actuators at full force per unit of the DOF's authority: an exact penalty, so
that s = 0 whenever the request is attainable.

One HiGHS problem per configuration; each sample changes bounds and a few coefficients and
the dual simplex starts from the last basis. A vertex of the LP has at most as many actuators
strictly between their limits as there are controlled DOFs: the answer is sparse (fewer
actuators working than the QP's, which spreads the load), and it jumps from one vertex to
another where the QP's changes smoothly.

``saturation: direct``: an unattainable request (a slack above 1e-6 of its DOF's authority)
is answered by Durham's boundary solution instead (:mod:`~.direct`).
"""

from __future__ import annotations

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from ..solvers import BackendFactory
from ..vehicle.config import Vehicle
from .base import AllocationMethod, MethodOutput
from .direct import DirectSolution
from .sample_lp import SampleLP, survey_apothem

SATURATION_SLACK = 1e-6
"""Slack, as a fraction of its DOF's authority, above which a request counts as unattainable."""


class LPAllocation(AllocationMethod):
    """Allocation method ``lp``."""

    name = "lp"
    saturation_modes = ("weighted", "direct")

    def __init__(self, model: Model, backend: BackendFactory):
        super().__init__(model, backend)
        sides = model.vehicle.azimuth_polygon_sides
        self._lp = SampleLP(model, sides, survey_apothem(sides), "effort")
        self._direct = DirectSolution(model) if model.vehicle.saturation == "direct" else None
        self.setups += 1 if self._direct is None else 2

    @classmethod
    def thrust_region_sides(cls, vehicle: Vehicle) -> int | None:
        return vehicle.azimuth_polygon_sides

    @classmethod
    def thrust_region_apothem(cls, vehicle: Vehicle) -> float:
        return survey_apothem(vehicle.azimuth_polygon_sides)

    def update_model(self, model: Model) -> None:
        """Take a configuration with the same structure: values only, no new set-up."""
        self.model = model
        self._lp.update_model(model)
        if self._direct is not None:
            self._direct.update_model(model)

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        solution = self._lp.solve(tau, limits)
        output = MethodOutput(force=self._lp.force(solution), status=solution.status, iterations=solution.iterations,
                              outcome=solution.outcome)
        if self._direct is None or not solution.usable:
            return output
        if np.all(np.abs(self._lp.slack(solution)) <= SATURATION_SLACK * self.model.dof_scale):
            return output
        boundary = self._direct.solve(tau, limits)
        boundary.iterations += output.iterations
        return boundary if boundary.usable else output
