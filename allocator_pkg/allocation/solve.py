"""The method stage of a sample: the configured method, with the weighted pseudo-inverse
answering whenever it fails, and the cache of methods set up for this configuration."""

from __future__ import annotations

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from ..effectiveness.weighted_inverse import PseudoInverseGains
from ..methods import METHODS, AllocationMethod
from ..methods.base import MethodOutput
from ..methods.pseudoinverse import PseudoInverseAllocation
from ..solvers import BackendFactory
from ..solvers.outcome import Outcome
from ..vehicle.config import Vehicle


def check_method(method: str, vehicle: Vehicle) -> None:
    """Raise ValueError when ``method`` cannot serve ``vehicle`` (its reasons) or the vehicle
    orders its DOFs and the method does not implement it."""
    unfit = METHODS[method].problems(vehicle)
    if unfit:
        raise ValueError(f"method '{method}' cannot serve this vehicle: {'; '.join(unfit)}")
    if vehicle.priority_levels and not METHODS[method].implements_priorities:
        able = ", ".join(name for name, kind in METHODS.items() if kind.implements_priorities)
        raise ValueError(f"priorities: method '{method}' does not implement DOF priorities; methods that do: {able}")


class MethodStage:
    """One method in use, the ones used before kept while the solver pattern stays (a switch
    back sets nothing up), and the pseudo-inverse behind them.

    Only the method in use follows each configuration change; a cached one takes the current
    values when it is chosen again (its ``update_model``, which also drops what it kept from the
    samples of its last use)."""

    def __init__(self, backend: BackendFactory):
        self.backend = backend
        self.methods: dict[str, AllocationMethod] = {}
        self.method: AllocationMethod | None = None
        self.fallbacks = 0
        self._retired_setups = 0

    def configure(self, model: Model, name: str) -> None:
        """Take a new configuration and use the method ``name``. A cached method goes with a new
        structure, or when it cannot serve the new vehicle (it is set up again, with its reason
        checked, if chosen later)."""
        stale = [key for key, method in self.methods.items()
                 if method.structure != model.structure or METHODS[key].problems(model.vehicle)]
        for key in stale:
            self._retired_setups += self.methods.pop(key).setups
        self.inverse = PseudoInverseGains(model)
        self.fallback = PseudoInverseAllocation(model, self.backend, self.inverse)
        self.model = model
        self.choose(name)

    def choose(self, name: str) -> None:
        """Use the method ``name`` from now on."""
        method = self.methods.get(name)
        if method is None:
            method = self.methods[name] = METHODS[name](self.model, self.backend)
        elif method.model is not self.model or method is not self.method:
            method.update_model(self.model)
        self.method = method

    @property
    def setups(self) -> int:
        """Solver set-ups of every method this stage has made."""
        return self._retired_setups + sum(method.setups for method in self.methods.values())

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        """The method's extended force for ``tau``, or the pseudo-inverse's when it fails
        (``Outcome.FALLBACK``, the failed status as its ``reason``)."""
        output = self.method.solve(tau, limits)
        if output.outcome is not Outcome.FAILED:
            return output
        self.fallbacks += 1
        fallback = self.fallback.solve(tau, limits)
        fallback.status = f"fallback: pseudoinverse ({output.status})"
        fallback.outcome, fallback.reason = Outcome.FALLBACK, output.status
        fallback.iterations = output.iterations
        return fallback
