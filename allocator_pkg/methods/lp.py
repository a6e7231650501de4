"""Allocation method ``lp``: the survey's linear programme (section 5.3), weighted force
magnitudes against the magnitudes of the wrench error, on one warm-started HiGHS problem.

A rotatable thruster's magnitude is the 1-norm of its x/y components and its circle (1.46) the
survey's polygon of ``azimuth_polygon_sides`` sides; sectors and rate limits are those of
``qp`` (:class:`~.sample_lp.SampleLP` holds the programme). Answers are vertices: sparse, and
jumping where the QP's change smoothly. ``saturation: direct`` answers an unattainable request
with Durham's boundary solution. docs/theory.md (section `lp`) has the criterion, the polygon's
error and the sparsity; docs/performance.md the cost.
"""

from __future__ import annotations

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from ..effectiveness.power_rows import PowerRows
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
    power_rows = True

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

    def set_power(self, rows: PowerRows | None) -> None:
        """The power rows' values in the programme (values only)."""
        self.power = rows
        self._lp.set_power(rows)

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
