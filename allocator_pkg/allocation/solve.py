"""The method stage of a sample: the configured method, with the weighted pseudo-inverse
answering whenever it fails, fed forward the drag of the control surfaces (1.56)-(1.58); the
cache of methods set up for this configuration; and the check that a method can serve a
vehicle."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from ..effectiveness.power_rows import PowerRows
from ..effectiveness.weighted_inverse import PseudoInverseGains
from ..methods import METHODS, AllocationMethod
from ..methods.base import MethodOutput
from ..methods.pseudoinverse import PseudoInverseAllocation
from ..solvers import BackendFactory
from ..solvers.outcome import Outcome
from ..vehicle.config import DOF_NAMES, ConfigError, Vehicle
from .conditions import Conditions

SURGE = DOF_NAMES.index("surge")

DRAG_PASSES = 4
"""Solves per sample for the drag feed-forward (1.56)-(1.58): the request plus the drag of the
last pass's deflections, until the drag stops changing (two or three passes in practice)."""


def check_method(method: str, vehicle: Vehicle) -> None:
    """Raise ConfigError when ``method`` cannot serve ``vehicle`` (its reasons), or the vehicle
    orders its DOFs or asks for thrust bias and the method does not implement it."""
    unfit = METHODS[method].problems(vehicle)
    if unfit:
        raise ConfigError([("method", f"'{method}' cannot serve this vehicle: {'; '.join(unfit)}")])
    if vehicle.priority_levels and not METHODS[method].implements_priorities:
        able = ", ".join(name for name, kind in METHODS.items() if kind.implements_priorities)
        raise ConfigError([("priorities", f"method '{method}' does not implement DOF priorities; methods that do: "
                                          f"{able}")])
    if vehicle.bias.enabled and not METHODS[method].implements_bias:
        able = ", ".join(name for name, kind in METHODS.items() if kind.implements_bias)
        raise ConfigError([("bias.enabled", f"method '{method}' does not implement thrust bias; methods that do: "
                                            f"{able}")])


def within(limits: SampleLimits, bound: np.ndarray) -> SampleLimits:
    """``limits`` inside the thrust magnitudes ``bound`` [N]: the power rule of a method
    without rows (the proportional bounds, docs/power.md), for the fallback of one with rows."""
    azimuth = [replace(lim, thrust_low=min(max(lim.thrust_low, -bound[i]), bound[i]),
                       thrust_high=min(max(lim.thrust_high, -bound[i]), bound[i]),
                       physical_max=min(lim.physical_max, bound[i]))
               for i, lim in zip(limits.rot.tolist(), limits.azimuth)]
    return replace(limits, low=np.clip(limits.low, -bound, bound), high=np.clip(limits.high, -bound, bound),
                   azimuth=azimuth, version=-1)


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
        self._power = None
        self._power_bound: np.ndarray | None = None

    def configure(self, model: Model, name: str, inverse: PseudoInverseGains) -> None:
        """Take a new configuration and use the method ``name``; ``inverse`` is the
        configuration's pseudo-inverse gains, for the fallback. A cached method goes with a new
        structure, or when it cannot serve the new vehicle (it is set up again, with its reason
        checked, if chosen later)."""
        stale = [key for key, method in self.methods.items()
                 if method.structure != model.structure or METHODS[key].problems(model.vehicle)]
        for key in stale:
            self._retired_setups += self.methods.pop(key).setups
        self.fallback = PseudoInverseAllocation(model, self.backend, inverse)
        self.model = model
        rows = np.flatnonzero(model.dof_index == SURGE)
        self._drag_row = int(rows[0]) if rows.size and model.surfaces.size else None
        self._surfaces = model.surfaces
        self._surface_columns = model.starts[model.surfaces]
        self._power = None                          # the next refresh gives the new configuration's rows
        self.choose(name)

    def choose(self, name: str) -> None:
        """Use the method ``name`` from now on."""
        method = self.methods.get(name)
        if method is None:
            method = self.methods[name] = METHODS[name](self.model, self.backend)
        elif method.model is not self.model or method is not self.method:
            method.update_model(self.model)
        method.set_power(self._power)
        self.method = method

    def refresh(self, conditions: Conditions) -> None:
        """The control surfaces' lift and drag gains at the speed in force, for the drag
        feed-forward."""
        self._lift = conditions.lift[self._surfaces]
        self._lifting = self._lift > 0.0
        self._drag = conditions.drag[self._surfaces]
        self._deflection = np.zeros(self._surfaces.size)
        self.set_power(conditions.power)
        self._power_bound = conditions.power_bound

    def set_power(self, rows: PowerRows | None) -> None:
        """The power rows in force, for the method (values only, docs/power.md)."""
        self._power = rows
        self.method.set_power(rows)

    @property
    def setups(self) -> int:
        """Solver set-ups of every method this stage has made."""
        return self._retired_setups + sum(method.setups for method in self.methods.values())

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> tuple[MethodOutput, float]:
        """The method's extended force for ``tau`` (the pseudo-inverse's when it fails) and the
        surge drag X_cs (1.57) of the control surfaces it deflects. With control surfaces and
        surge controlled, the drag is fed forward (1.56)-(1.58): solved again with the surge
        request grown by the drag of the last pass's deflections until the drag settles; the
        output counts every pass's iterations."""
        output = self.method.solve(tau, limits)
        if output.outcome is Outcome.FAILED:
            output = self._fallback(tau, limits, output)
        surge = self._drag_row
        if surge is None:
            return output, 0.0
        low, high = limits.low[self._surfaces], limits.high[self._surfaces]
        drag, new_drag = 0.0, self._surface_drag(output.force, low, high)
        iterations = output.iterations
        for _ in range(DRAG_PASSES):
            if abs(new_drag - drag) <= 1e-9 * max(1.0, abs(tau[surge])):
                break
            drag = new_drag
            compensated = tau.copy()
            compensated[surge] += drag
            output = self.method.solve(compensated, limits)
            if output.outcome is Outcome.FAILED:
                output = self._fallback(compensated, limits, output)
            iterations += output.iterations
            new_drag = self._surface_drag(output.force, low, high)
        if iterations != output.iterations:
            output = replace(output, iterations=iterations)
        return output, new_drag

    def _fallback(self, tau: np.ndarray, limits: SampleLimits, failed: MethodOutput) -> MethodOutput:
        """The pseudo-inverse's extended force for ``tau``, as the answer of a method that
        ``failed`` (``Outcome.FALLBACK``, the failed status as its ``reason``)."""
        self.fallbacks += 1
        fallback = self.fallback.solve(tau, self.fallback_limits(limits))
        return replace(fallback, status=f"fallback: pseudoinverse ({failed.status})", iterations=failed.iterations,
                       outcome=Outcome.FALLBACK, reason=failed.status)

    def fallback_limits(self, limits: SampleLimits) -> SampleLimits:
        """The limits the fallback answers within and is actuated in: with power rows in force,
        inside the proportional power bounds (docs/power.md)."""
        return limits if self._power_bound is None else within(limits, self._power_bound)

    def _surface_drag(self, force: np.ndarray, low: np.ndarray, high: np.ndarray) -> float:
        """X_cs of (1.57): the added resistance of all control surfaces at the deflections
        ``force`` gives them, clipped to this sample's limits (``low``, ``high`` of the
        surfaces) as actuation clips it."""
        thrust = np.minimum(np.maximum(force[self._surface_columns], low), high)
        deflection = np.divide(thrust, self._lift, out=self._deflection, where=self._lifting)
        return float(np.sum(self._drag * deflection * deflection))
