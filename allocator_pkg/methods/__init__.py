"""Allocation methods, one module each (``qp`` builds its problems in ``qp_problem``,
``explicit`` takes its law from ``explicit_law``), and the registry everything else derives
from.

``METHODS`` maps each configuration name to its :class:`~.base.AllocationMethod`: the
allocator's construction, ``allocator-capability --method``, the benchmarks and the tests'
parameter lists all read it; the schema offers its names from
:data:`~allocator_pkg.vehicle.config.METHOD_NAMES` (test/configuration/test_schema.py holds the two equal). A
new method is one module with a subclass of :class:`~.base.AllocationMethod`, one line here,
its name in METHOD_NAMES, its tests and a section in docs/theory.md.

- ``qp``: the constrained QP (1.35) on one warm-started solver problem;
- ``pseudoinverse``: the weighted generalised inverse (1.29)/(1.33) with clipping or scaling;
- ``nonlinear``: the nonlinear problem (1.44) by sequential linearised QPs (1.45);
- ``lp``: the survey's linear programme (section 5.3) on HiGHS, warm-started from the last basis;
- ``dynamic``: a control-Lyapunov update law whose equilibrium is the optimum (section 5.1);
- ``svd_filter``: azimuths steered by a filter, thrusts by a damped least-squares inverse (5.4);
- ``explicit``: the piecewise-affine law of (1.35) (section 4.1), region by region, for
  actuators of fixed direction.
"""

from __future__ import annotations

from .base import AllocationMethod
from .dynamic import DynamicAllocation
from .explicit import ExplicitAllocation
from .lp import LPAllocation
from .nonlinear import NonlinearAllocation
from .pseudoinverse import PseudoInverseAllocation
from .qp import QPAllocation
from .svd_filter import SVDFilterAllocation

METHODS: dict[str, type[AllocationMethod]] = {
    QPAllocation.name: QPAllocation,
    PseudoInverseAllocation.name: PseudoInverseAllocation,
    NonlinearAllocation.name: NonlinearAllocation,
    LPAllocation.name: LPAllocation,
    DynamicAllocation.name: DynamicAllocation,
    SVDFilterAllocation.name: SVDFilterAllocation,
    ExplicitAllocation.name: ExplicitAllocation,
}

__all__ = ["METHODS", "AllocationMethod"]
