"""Reading a scenario file's control system (``observer``, ``measurement`` and the wind
feed-forward keys of ``controller``), each value refused with its key (``ScenarioError``)."""

from __future__ import annotations

import math

from .control_system import ControlSystem
from .environment import EnvironmentSpec
from .measurement import MeasurementNoise
from .observer import ObserverTuning
from .scenario_values import ScenarioError, flag, number, section, vector


def control_system(data: dict, model: str, environment: EnvironmentSpec) -> ControlSystem:
    """The control system of a scenario file's mapping ``data``; the observer's wave period by
    default the waves' peak period."""
    controller, tuning, noise = section(data, "controller"), section(data, "observer"), section(data, "measurement")
    observer = None
    if flag(tuning, "enabled", "observer."):
        if model != "dp_vessel":
            raise ScenarioError(f"observer.enabled: for the dp_vessel model only, not {model}")
        period = number(tuning, "wave_period", "observer.", default=environment.wave_period or None)
        try:
            observer = ObserverTuning(
                wave_period=period,
                **{key: number(tuning, key, "observer.") for key in ("wave_damping", "notch_damping", "cutoff_ratio",
                                                                       "bias_time_constant", "k3_ratio")},
                k4_bis=vector(tuning, "k4_bis", "observer.", 3))
        except ValueError as error:
            raise ScenarioError(str(error)) from error
    feedforward = flag(controller, "wind_feedforward", "controller.")
    if feedforward and model != "dp_vessel":
        raise ScenarioError(f"controller.wind_feedforward: for the dp_vessel model only, not {model}")
    return ControlSystem(observer=observer,
                         noise=MeasurementNoise(number(noise, "position_sigma", "measurement."),
                                                math.radians(number(noise, "heading_sigma", "measurement."))),
                         wind_feedforward=feedforward, wind_filter=number(controller, "wind_filter", "controller."))
