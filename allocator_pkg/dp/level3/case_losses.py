"""The thrust losses of a Level 3 case's simulated thrusters, those of the static analysis the
search rests on, as plain data for the simulation (:class:`~...simulation.thrust_losses.ThrustLosses`):

- a thruster with the particulars' Level 2 loss tables (``level2.thrust_loss``): its speed
  factor at the condition's current and its direction table (:class:`~..level2.Level2`);
- any other: Level 1's beta_misc [3.9.3] times the ventilation loss beta_vent [3.9.4] of the
  condition and heading, forward and reversed, and by thrust direction the losses flushing the
  case's dead thrusters [3.11.4] and skegs [3.11.5] (:class:`~..level1.Level1`);
- either: after a group's loss, a thruster fed in part by a lost source on the share^(2/3) of its
  thrust its remaining feeds give ([3.9.2], [3.12]).

Each factor is the analysis' thrust range over its nominal thrust, so that the simulation's
thruster delivers its command times that share. The [3.11.3] zones are the allocator's
(``flushing_zones: dnv`` in the case, :mod:`.dp_system`), and so is its own loss onto a dead
thruster ([3.11.4], :mod:`allocator_pkg.allocation.dead_flushing`).
"""

from __future__ import annotations

import math

from ...simulation.thrust_losses import LossCase, ThrustLosses
from ...vehicle.config import Vehicle
from ..inputs.particulars import Particulars
from ..level1 import Level1
from ..level2 import Level2
from ..standard.weather import WeatherCondition


def case_losses(vehicle: Vehicle, particulars: Particulars, condition: WeatherCondition, direction: float,
                lost: tuple[str, ...] = ()) -> ThrustLosses:
    """The losses of a case: intact, and with ``lost`` (a group's actuators and sources) lost
    when it names any; ``direction`` [rad] where the environment comes from, 0 ahead."""
    level1, level2 = Level1(vehicle, particulars), Level2(vehicle, particulars)
    cases = [_case(level1, level2, condition, direction, ())]
    if any(name in level1.actuators for name in lost):
        cases.append(_case(level1, level2, condition, direction, lost))
    return ThrustLosses(tuple(cases), describe(cases))


def _case(level1: Level1, level2: Level2, condition: WeatherCondition, direction: float,
          lost: tuple[str, ...]) -> LossCase:
    """One case's losses with ``lost`` out: per working actuator, the forward and reverse factors
    (the thrust range of Level 2 where the particulars give its thrust-loss table, Level 1
    otherwise, over the nominal thrust), and the thrust profiles of the same analysis."""
    dead = tuple(name for name in level1.actuators if name in lost)
    tables = level1.particulars.thrust_loss
    forward, reverse = {}, {}
    for name, unit in level1.actuators.items():
        if name in dead:
            continue
        analysis = level2 if name in tables else level1
        low, high = analysis.thrust_range(name, condition, direction, lost)
        config = unit.config
        nominal_forward = config.thrust_max if name in tables else unit.forward
        nominal_reverse = -config.thrust_min if name in tables else unit.reverse
        if nominal_forward > 0.0:
            forward[name] = high / nominal_forward
        if nominal_reverse > 0.0:
            reverse[name] = -low / nominal_reverse
    standard = {name: profile for name, profile in level1.thrust_profiles(dead).items() if name not in tables}
    own = {name: profile for name, profile in level2.thrust_profiles(dead).items() if name in tables}
    return LossCase(frozenset(dead), forward, reverse, {**standard, **own})


def describe(cases: list[LossCase]) -> str:
    """The loss factors of each case in a sentence, for the report."""
    parts = []
    for case in cases:
        factors = ", ".join(f"{name} {case.forward.get(name, math.nan):.3f}"
                            + (f"/{case.reverse[name]:.3f}" if name in case.reverse else "")
                            for name in sorted({*case.forward, *case.reverse}))
        profiles = ", ".join(sorted(case.profiles)) or "none"
        parts.append(f"{', '.join(sorted(case.dead)) + ' dead' if case.dead else 'intact'}: {factors}; "
                     f"by direction: {profiles}")
    return ("thrust losses of the static analysis in the simulated thrusters (forward/reverse factor: "
            "beta_misc beta_vent [3.9.3]-[3.9.4] or the Level 2 speed table, times the power share^(2/3) after a "
            "loss; by direction [3.11.4]-[3.11.5] or the Level 2 direction table): " + ". ".join(parts))
