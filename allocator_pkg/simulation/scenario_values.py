"""Reading the values of a scenario file: numbers, vectors and mappings, each refused with
its key (``ScenarioError``), their defaults and lower bounds those of :data:`SCENARIO_KEYS`; the
environment, a set-point event's target, the bounds and the named windows."""

from __future__ import annotations

import math
import re
from typing import Any

from ..configuration.file_keys import FileKey
from .environment import EnvironmentSpec, SlowVariation
from .metrics import BOUNDED_METRICS, PLANT_METRICS
from .scenario_keys import scenario_key
from .setpoint import SetpointTarget
from .windows import Window

DECLARED: Any = object()
"""A default or lower bound as :data:`SCENARIO_KEYS` declares it for the key."""


class ScenarioError(ValueError):
    pass


def number(data: dict, key: str, where: str, default: Any = DECLARED, minimum: Any = DECLARED) -> float:
    """``data[key]`` (or ``default``) as a finite float of at least ``minimum``; both as
    :data:`SCENARIO_KEYS` declares them unless given (None: required, no bound)."""
    declared = scenario_key(where + key) or FileKey(key, "", "")
    default = declared.default if default is DECLARED else default
    exclusive = declared.exclusive_minimum and minimum is DECLARED
    minimum = declared.minimum if minimum is DECLARED else minimum
    value = data.get(key, default)
    if value is None:
        raise ScenarioError(f"{where}{key}: required")
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ScenarioError(f"{where}{key}: a finite number, not {value!r}")
    if minimum is not None and exclusive and value <= minimum:
        raise ScenarioError(f"{where}{key}: a number > {minimum:g}, not {value!r}")
    if minimum is not None and value < minimum:
        raise ScenarioError(f"{where}{key}: at least {minimum:g}, not {value!r}")
    return float(value)


def vector(data: dict, key: str, where: str, size: int, default: Any = DECLARED) -> tuple[float, ...]:
    """``data[key]`` (or ``default``, else :data:`SCENARIO_KEYS`' default) as ``size`` finite floats."""
    if default is DECLARED:
        declared = scenario_key(where + key)
        default = list(declared.default) if declared is not None and declared.default is not None else None
    value = data.get(key, default)
    if not isinstance(value, list) or len(value) != size or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in value):
        raise ScenarioError(f"{where}{key}: a list of {size} finite numbers, not {value!r}")
    return tuple(float(v) for v in value)


def section(data: dict, key: str) -> dict:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise ScenarioError(f"{key}: a mapping, not {value!r}")
    return value


def _variation(data: dict, sigma: str, time: str, where: str) -> SlowVariation:
    return SlowVariation(number(data, sigma, where), number(data, time, where))


def environment(data: dict) -> EnvironmentSpec:
    current, wind, waves = (section(data, k) for k in ("current", "wind", "waves"))
    return EnvironmentSpec(
        current_speed=number(current, "speed", "environment.current."),
        current_direction=number(current, "direction", "environment.current."),
        current_speed_variation=_variation(current, "speed_sigma", "time_constant", "environment.current."),
        current_direction_variation=_variation(current, "direction_sigma", "time_constant", "environment.current."),
        current_down=number(current, "down", "environment.current."),
        wind_speed=number(wind, "speed", "environment.wind."),
        wind_direction=number(wind, "direction", "environment.wind."),
        gusts=_variation(wind, "gust_sigma", "gust_time_constant", "environment.wind."),
        wave_height=number(waves, "hs", "environment.waves."),
        wave_period=number(waves, "peak_period", "environment.waves."),
        wave_direction=number(waves, "direction", "environment.waves."),
        drift_variation=_variation(waves, "drift_sigma", "drift_time_constant", "environment.waves."),
        wind_spectrum=choice(wind, "spectrum", "environment.wind."),
        wind_direction_variation=_variation(wind, "direction_sigma", "direction_time_constant", "environment.wind."),
        wave_spectrum=choice(waves, "spectrum", "environment.waves."),
        peak_factor=number(waves, "peak_factor", "environment.waves."),
        wave_spreading=number(waves, "spreading", "environment.waves."))


def choice(data: dict, key: str, where: str) -> str:
    """``data[key]`` (or its default), one of the key's choices in :data:`SCENARIO_KEYS`."""
    declared = scenario_key(where + key)
    value = data.get(key, declared.default)
    if value not in declared.choices:
        raise ScenarioError(f"{where}{key}: one of {', '.join(declared.choices)}, not {value!r}")
    return value



def setpoint_target(body: Any, where: str) -> SetpointTarget:
    """A set-point event's ``setpoint``: a position NED [m] and/or a heading [deg], a ramp's
    ``speed`` [m/s] (with a position) and ``heading_rate`` [deg/s] (with a heading), each > 0."""
    if not isinstance(body, dict) or not ("position" in body or "heading" in body):
        raise ScenarioError(f"{where}: a mapping with a position, a heading or both, not {body!r}")
    for rate, of in (("speed", "position"), ("heading_rate", "heading")):
        if rate in body and of not in body:
            raise ScenarioError(f"{where}.{rate}: a ramp of the {of}, which the event does not change")
        if rate in body:
            number(body, rate, where + ".")
    return SetpointTarget(
        position=vector(body, "position", where + ".", 3) if "position" in body else None,
        heading=math.radians(number(body, "heading", where + ".")) if "heading" in body else None,
        speed=float(body["speed"]) if "speed" in body else None,
        heading_rate=math.radians(float(body["heading_rate"])) if "heading_rate" in body else None)


def read_bounds(data: Any, where: str) -> dict[str, float]:
    """Upper bounds (metric name: largest value, >= 0) of BOUNDED_METRICS."""
    if not isinstance(data, dict):
        raise ScenarioError(f"{where}: a mapping of metric names to their largest values, not {data!r}")
    for key in data:
        if key not in BOUNDED_METRICS:
            raise ScenarioError(f"{where}.{key}: not one of {', '.join(BOUNDED_METRICS)}")
        number(data, key, where + ".")
    return {key: float(value) for key, value in data.items()}


def read_windows(data: Any, duration: float) -> list[Window]:
    """The named windows: each a name, ``start`` [s] and ``end`` [s] (default: the end of the
    run) with 0 <= start < end <= duration, and bounds of its own; names distinct and not
    those of the automatic windows."""
    if not isinstance(data, list):
        raise ScenarioError(f"windows: a list, not {data!r}")
    found = []
    for index, item in enumerate(data):
        where = f"windows[{index}]"
        if not isinstance(item, dict) or not isinstance(item.get("name"), str) or not item["name"]:
            raise ScenarioError(f"{where}: a mapping with a name")
        start = number(item, "start", where + ".")
        end = number(item, "end", where + ".", duration)
        if not start < end <= duration:
            raise ScenarioError(f"{where}: start < end <= duration ({duration:g} s), not {start:g} to {end:g}")
        if re.fullmatch(r"(after_)?fault(_\d+)?", item["name"]):
            raise ScenarioError(f"{where}.name: '{item['name']}' is the name of an automatic window (fault, "
                                "after_fault, fault_N, after_fault_N)")
        if item["name"] in [w.name for w in found]:
            raise ScenarioError(f"{where}.name: '{item['name']}' names another window too")
        bounds = read_bounds(item.get("bounds", {}), where + ".bounds")
        over_run = [name for name in bounds if name in PLANT_METRICS]
        if over_run:
            raise ScenarioError(f"{where}.bounds.{over_run[0]}: a power plant's metric, bounded over the run only")
        found.append(Window(item["name"], start, end, bounds))
    return found


def flag(data: dict, key: str, where: str) -> bool:
    """``data[key]`` (or :data:`SCENARIO_KEYS`' default) as true or false."""
    value = data.get(key, scenario_key(where + key).default)
    if not isinstance(value, bool):
        raise ScenarioError(f"{where}{key}: true or false, not {value!r}")
    return value
