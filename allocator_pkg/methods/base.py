"""The interface every allocation method implements (after PX4's ControlAllocation: one
``allocate`` per method, the effectiveness matrices and the glue elsewhere).

A method is constructed once per configuration structure with the configuration-time
arrays (:class:`~allocator_pkg.effectiveness.model.Model`) and a solver backend factory, takes new values
of the same structure through :meth:`update_model`, and each sample turns the controlled
part of tau and this sample's limits into the extended force vector (1.16). Thrust and angle
per actuator, command maps, the fallback and the achieved wrench are the allocator's.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from ..effectiveness.power_rows import PowerRows
from ..solvers import BackendFactory
from ..solvers.outcome import Outcome
from ..vehicle.config import Vehicle

CIRCLE_SIDES = 256
"""The thrust circle |f| <= f_max as a polygon for the capability analysis of a method that
keeps the circle itself at rest (within 1 - cos(pi/256) = 0.008 %)."""


@dataclass(slots=True, kw_only=True)
class MethodOutput:
    """A method's answer: the extended force vector (1.16), and how the solve went (its
    ``outcome``, ``usable`` unless that is FAILED). ``residual`` is the solver's primal
    residual where it reports one; ``reason`` why a fallback answered (the failed method's
    status). ``angle`` optionally proposes the angle of each actuator (nonlinear method);
    ``turn`` the angle toward which an idle rotatable thruster (by actuator index) turns instead
    of its limits' goal (the nonlinear method's descent direction)."""

    force: np.ndarray
    status: str
    iterations: int = 0
    outcome: Outcome = Outcome.SOLVED
    angle: np.ndarray | None = None
    turn: dict[int, float] | None = None
    residual: float | None = None
    reason: str = ""

    @property
    def usable(self) -> bool:
        return self.outcome is not Outcome.FAILED


class AllocationMethod(ABC):
    """One allocation method. ``setups`` counts the solver set-ups it has made (the tests
    check that faults and value changes add none).

    ``implements_priorities`` says whether :meth:`solve` honours the vehicle's DOF
    priorities (``Vehicle.priority_levels``: an unattainable request meets a higher level as
    far as it can before a lower one gets anything). False by default, so that a new method
    is safe: the configuration check refuses ``priorities`` with a method that does not
    declare them, and a subclass does not inherit the declaration."""

    name: ClassVar[str]
    saturation_modes: ClassVar[tuple[str, ...]] = ("weighted", "preserve_direction")
    """The values of ``saturation`` this method implements; a configuration with another one
    is refused when it is parsed (:meth:`problems`)."""

    implements_priorities: ClassVar[bool] = False
    power_rows: ClassVar[bool] = False
    """Whether the method solves with the power rows (:meth:`set_power`, docs/power.md); one
    that does not gets the proportional power bounds in its thrust ranges instead."""
    implements_bias: ClassVar[bool] = False
    """Whether :meth:`solve` honours the thrust bias of ``SampleLimits.bias`` (docs/theory.md,
    thrust bias); the configuration check refuses ``bias.enabled`` with a method that does not."""

    def __init_subclass__(cls, **kwargs) -> None:
        """A subclass declares priorities itself: one that overrides a method that implements
        them (its ``solve``) does not inherit the declaration."""
        super().__init_subclass__(**kwargs)
        if "implements_priorities" not in cls.__dict__:
            cls.implements_priorities = False

    def __init__(self, model: Model, backend: BackendFactory):
        self.model = model
        self.backend = backend
        self.setups = 0
        self.power: PowerRows | None = None

    @property
    def structure(self) -> tuple:
        """What fixes the method's solver pattern; another configuration with the same
        structure is taken by :meth:`update_model`, a different one needs a new method."""
        return self.model.structure

    @abstractmethod
    def update_model(self, model: Model) -> None:
        """Take a configuration with the same structure: values only, no new set-up."""

    def set_power(self, rows: PowerRows | None) -> None:
        """Take the power rows' values in force (None: no sources), values only on the same
        pattern. A method without rows (``power_rows`` False) only keeps them (``power``): the
        allocator narrows its thrust ranges instead."""
        self.power = rows

    @abstractmethod
    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        """The extended force vector for the controlled DOFs ``tau`` within ``limits``."""

    @classmethod
    def problems(cls, vehicle: Vehicle) -> list[str]:
        """Why this method cannot serve ``vehicle`` (empty when it can): checked when a
        configuration is parsed, so that a method is refused with its reason."""
        if vehicle.saturation not in cls.saturation_modes:
            return [f"it does not implement saturation '{vehicle.saturation}' (it takes "
                    f"{', '.join(cls.saturation_modes)})"]
        return []

    @classmethod
    @abstractmethod
    def thrust_region_sides(cls, vehicle: Vehicle) -> int | None:
        """Sides of the polygon this method's constraints put on a rotatable thruster's
        force, for the capability analysis; None when the method cannot redistribute force
        and its capability is that of the weighted pseudo-inverse along the request."""

    @classmethod
    def thrust_region_apothem(cls, vehicle: Vehicle) -> float:
        """Distance of the faces of that polygon from its centre, as a fraction of the thrust
        limit: the inscribed polygon, cos(pi/N), unless the method says otherwise. A polygon
        that reaches outside the circle is cut by the circle in the capability analysis: the
        allocator clips every thrust to its limit."""
        sides = cls.thrust_region_sides(vehicle)
        return 1.0 if sides is None else math.cos(math.pi / sides)
