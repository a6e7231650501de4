"""The DP system and the thrusters of a Level 3 case, as a vessel has them and as the static
analysis models them:

- the controller acts on the estimate of the nonlinear passive observer (Fossen and Strand;
  :mod:`allocator_pkg.simulation.observer`) tuned to the condition's peak period, from the
  position and heading measured with the sea's first-order wave motion and white noise
  (:data:`NOISE`, unless the base scenario gives its own), with wind feed-forward;
- a failed group trips: its thrusters' thrust drops to zero at once (``fault_trip``);
- the thrusters suffer the static analysis' losses (:mod:`.case_losses`), and the allocator keeps the
  [3.11.3] zones and its own [3.11.4] loss onto a dead thruster (``flushing_zones: dnv``) when
  every azimuth thruster of the vehicle file has a diameter.

The base scenario's observer tuning (``observer``) is kept but for its wave period, the
condition's; its gains, its thruster time constant and the feed-forward's filter too.
"""

from __future__ import annotations

import math
from dataclasses import replace

from ...simulation.control_system import ControlSystem
from ...simulation.measurement import MeasurementNoise
from ...simulation.observer import ObserverTuning
from ...simulation.scenario import Scenario, vehicle_config
from ...vehicle.config import AZIMUTH, Vehicle
from ..inputs.particulars import Particulars
from ..standard.weather import WeatherCondition
from .case_losses import case_losses

NOISE = MeasurementNoise(position_sigma=0.1, heading_sigma=math.radians(0.05))
"""White measurement noise of a case when the base scenario gives none: 0.1 m north and east
(a DGNSS position reference), 0.05 deg heading (a gyro compass); this package's choice."""


def dp_system(base: Scenario, period: float) -> ControlSystem:
    """The control system of a case whose sea has the peak period ``period`` [s]."""
    control = base.control
    observer = (replace(control.observer, wave_period=period) if control.observer is not None
                else ObserverTuning(wave_period=period))
    noise = control.noise if control.noise.position_sigma > 0.0 or control.noise.heading_sigma > 0.0 else NOISE
    return ControlSystem(observer, noise, wind_feedforward=True, wind_filter=control.wind_filter)


def lost_members(vehicle: Vehicle, group: str, actuators: tuple[str, ...]) -> tuple[str, ...]:
    """What the loss of ``group`` takes away: the vehicle file's named group's actuators and
    sources, else the given ``actuators``."""
    named = next((g for g in vehicle.redundancy_groups if g.name == group), None)
    return (*named.actuators, *named.sources) if named is not None else actuators


def with_dp_system(scenario: Scenario, particulars: Particulars | None, condition: WeatherCondition,
                   heading_deg: float, group: str, actuators: tuple[str, ...]) -> Scenario:
    """``scenario`` (a case's) with the DP system, the trip and the losses of the condition, the
    environment's heading [deg] and the loss of ``group`` (``actuators``; none intact)."""
    vehicle = vehicle_config(scenario.vehicle, scenario.parameters)
    parameters = dict(scenario.parameters)
    if all(a.diameter > 0.0 for a in vehicle.actuators if a.type == AZIMUTH):
        parameters["flushing_zones"] = "dnv"
    losses = None
    if particulars is not None:
        lost = lost_members(vehicle, group, actuators) if actuators else ()
        losses = case_losses(vehicle, particulars, condition, math.radians(heading_deg), lost)
    return replace(scenario, control=dp_system(scenario, scenario.environment.wave_period), fault_trip=True,
                   thrust_losses=losses, parameters=parameters)


def describe_dp_system(scenario: Scenario, period: float) -> str:
    """The Level 3 DP system in a few sentences, for the report: the observer's tuning (at the
    peak period ``period`` [s] of one condition; each case tunes it to its own), the noise, the
    feed-forward, the trip, the losses and the zones."""
    control = dp_system(scenario, period)
    return (f"DP system: {control.describe()}. The controller's gains those of the base scenario (kp "
            f"{', '.join(f'{k:g}' for k in scenario.gains.kp)}; kd {', '.join(f'{k:g}' for k in scenario.gains.kd)}; "
            f"ki {', '.join(f'{k:g}' for k in scenario.gains.ki)}); the observer's wave period each case's peak "
            f"period (here {period:g} s). A failure is a trip: the group's thrust is gone in one step. The simulated "
            f"thrusters lag ({scenario.thruster_time_constant:g} s) and follow their rate limits and suffer the "
            "static analysis' thrust losses (ventilation and misc. [3.9.3]-[3.9.4] or the Level 2 tables, the power "
            "share after a loss, flushing a dead thruster [3.11.4] or a skeg [3.11.5]); the allocator keeps the "
            "[3.11.3] zones and its loss onto a dead thruster (flushing_zones dnv) where the vehicle file gives "
            "every azimuth a diameter.")
