"""Scenario files (``config/scenarios/*.yaml``): the vehicle, the method and node parameters,
the duration and seed, the hull model, the environment, the set-point, the controller's
gains, timed events (set-point steps and ramps among them), named windows, the bounds the
run must stay within (over the run, or over a window) and, under ``methods``, the bounds a
method is held to in place of those. Paths are relative to the scenario file; every angle is
in degrees. Bad input raises ``ScenarioError`` naming the key, before anything runs: an
unknown key at any depth (with the nearest known one), a vehicle file or particulars that do
not fit the hull model or whose parameters the allocator refuses, a method that cannot serve
it, an event the vehicle cannot take or that comes after the end, a supply voltage outside the
thrust tables, an environment no sea gives or the hull does not take, a depth off the hull's
(:mod:`.scenario_check`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from ..configuration.parameters import vehicle_from_parameters
from ..configuration.params_file import read_parameters
from ..configuration.yaml_file import read_mapping
from ..effectiveness.faults import FaultMode, FaultSet
from ..hull.environment_loads import VesselParticulars
from ..hull.hull_file import read_hull
from ..vehicle.config import ConfigError, Vehicle
from .control_system import ControlSystem
from .control_values import control_system
from .controller import Gains
from .electric_plant import PlantSpec
from .environment import EnvironmentSpec
from .method_bounds import MethodBounds, method_bounds
from .power_plant_file import check_plant_bounds, check_plant_events, read_power_plant
from .scenario_check import (
    check_member,
    check_method_serves,
    check_parameter,
    check_particulars,
    check_run,
    check_vehicle,
    unknown_keys,
)
from .scenario_keys import EVENT_KEYS, FAULT_MODES, MODELS, scenario_default
from .scenario_values import (
    ScenarioError,
    environment,
    flag,
    number,
    read_bounds,
    read_windows,
    section,
    setpoint_target,
    vector,
)
from .setpoint import SetpointSchedule
from .thrust_losses import ThrustLosses
from .windows import Window, fault_windows

EVENT_KINDS = tuple(key.name for key in EVENT_KEYS[1:])


@dataclass(frozen=True)
class Event:
    """At ``time`` [s]: one of a fault (``fault``: actuator, mode, value: the share of force
    left when ``degraded``, the angle [rad] when ``stuck`` (the file gives it in degrees), None
    for the angle it has then),
    clearing every fault, a battery voltage ramp (``ramp``: to [V], duration [s]), a node
    parameter, a new set-point (``setpoint``: value a SetpointTarget), a redundancy group's
    loss (``group_fault``: name the group), the available power of a source changing
    (``power``: name the source, value [kW]), a bus tie opening or closing (``bus_tie``: name
    the tie, value True for closed) or the weather growing (``weather_ramp``: value
    the scale of the environment's speeds and wave height it reaches, duration [s])."""

    time: float
    kind: str
    actuator: str = ""
    mode: str = ""
    value: Any = 0.0
    duration: float = 0.0
    name: str = ""


@dataclass(frozen=True)
class Scenario:
    name: str
    path: Path
    vehicle: Path
    model: str
    method: str
    duration: float
    seed: int
    thruster_time_constant: float
    setpoint_position: tuple[float, float, float]
    """NED [m] at t = 0; the set-point events move it (:meth:`schedule`)"""
    setpoint_heading: float
    """[rad] at t = 0"""
    initial_position: tuple[float, float, float]
    initial_heading: float
    gains: Gains
    environment: EnvironmentSpec
    particulars: VesselParticulars | None = None
    parameters: dict[str, Any] = field(default_factory=dict)
    voltage: float | None = None
    events: tuple[Event, ...] = ()
    bounds: dict[str, float] = field(default_factory=dict)
    """Upper bounds of the run's metrics (metric name: largest value)."""
    windows: tuple[Window, ...] = ()
    """The named windows of the file (the automatic ones: :meth:`all_windows`)."""
    description: str = ""
    position_limit: float = scenario_default("position_limit")
    """[m] The vessel has lost its position once its position error exceeds this."""
    method_bounds: dict[str, MethodBounds] = field(default_factory=dict)
    """Per method, what the scenario expects of it in place of ``bounds`` (``methods`` of the file)."""
    control: ControlSystem = field(default_factory=ControlSystem)
    """What the controller acts on: the true state, or an observer's estimate from measurements."""
    fault_trip: bool = False
    """A failed actuator's thrust drops to zero at once, not at its rate limit."""
    thrust_losses: ThrustLosses | None = None
    """The thrust losses the simulated thrusters suffer (a Level 3 case's; none from a file)."""
    power_plant: PlantSpec | None = None
    """The simulated electric power plant (``power_plant`` of the file), or None."""

    @property
    def horizontal(self) -> bool:
        """Position error in the horizontal plane only (a surface vessel)."""
        return self.model == "dp_vessel"

    def scaled(self, factor: float) -> Scenario:
        """The same scenario with its duration, event times and ramps times ``factor``."""
        if not (math.isfinite(factor) and factor > 0.0):
            raise ScenarioError(f"duration scale: a finite number > 0, not {factor!r}")
        events = tuple(replace(e, time=e.time * factor, duration=e.duration * factor,
                               value=e.value.scaled(factor) if e.kind == "setpoint" else e.value)
                       for e in self.events)
        return replace(self, duration=self.duration * factor, events=events,
                       windows=tuple(w.scaled(factor) for w in self.windows))

    def schedule(self) -> SetpointSchedule:
        """The set-point at any time of the run."""
        return SetpointSchedule(self.setpoint_position, self.setpoint_heading,
                                [(e.time, e.value) for e in self.events if e.kind == "setpoint"])

    def all_windows(self) -> tuple[Window, ...]:
        """The file's windows, then the automatic ones of the faults (``windows.fault_windows``)."""
        return self.windows + tuple(fault_windows(self.events, self.duration))

    def run_bounds(self) -> dict[str, float]:
        """The bounds over the run that ``method`` is held to: ``bounds``, each replaced by the
        method's own where the scenario gives one."""
        own = self.method_bounds.get(self.method)
        return {**self.bounds, **own.bounds} if own else dict(self.bounds)

    def window_bounds(self) -> dict[str, dict[str, float]]:
        """Per named window with bounds, those ``method`` is held to (the window's, each
        replaced by the method's own where the scenario gives one)."""
        own = self.method_bounds.get(self.method, MethodBounds())
        found = {w.name: {**w.bounds, **own.windows.get(w.name, {})} for w in self.windows}
        return {name: limits for name, limits in found.items() if limits}

    def with_method(self, method: str) -> Scenario:
        """The same scenario under another method; ScenarioError when it cannot serve the vehicle."""
        try:
            check_method_serves(method, vehicle_config(self.vehicle, self.parameters))
        except ValueError as error:
            raise ScenarioError(str(error)) from error
        return replace(self, method=method)


def vehicle_config(path: Path, parameters: dict[str, Any]) -> Vehicle:
    """The vehicle the node runs: the vehicle file with the scenario's node parameters over it;
    ScenarioError (naming each key the allocator refuses) otherwise."""
    try:
        return vehicle_from_parameters({**read_parameters(path), **parameters})
    except ConfigError as error:
        raise ScenarioError("; ".join(f"{'vehicle' if key == str(path) else 'parameters.' + key}: {reason}"
                                      for key, reason in error.problems)) from error


def _event(data: Any, index: int) -> Event:
    where = f"events[{index}]."
    if not isinstance(data, dict):
        raise ScenarioError(f"events[{index}]: a mapping, not {data!r}")
    time = number(data, "time", where)
    kinds = [k for k in EVENT_KINDS if k in data]
    if len(kinds) != 1:
        raise ScenarioError(f"{where[:-1]}: exactly one of {', '.join(EVENT_KINDS)}")
    kind, body = kinds[0], data[kinds[0]]
    if kind == "clear_faults":
        return Event(time, kind)
    if kind == "setpoint":
        return Event(time, kind, value=setpoint_target(body, where + "setpoint"))
    if not isinstance(body, dict):
        raise ScenarioError(f"{where}{kind}: a mapping, not {body!r}")
    if kind == "fault":
        mode = body.get("mode")
        if mode not in FAULT_MODES:
            raise ScenarioError(f"{where}fault.mode: one of {', '.join(FAULT_MODES)}, not {mode!r}")
        if not isinstance(body.get("actuator"), str):
            raise ScenarioError(f"{where}fault.actuator: an actuator name, not {body.get('actuator')!r}")
        if mode == "degraded" and "value" not in body:
            raise ScenarioError(f"{where}fault.value: required for degraded, the share of force left in (0, 1]")
        if mode == "failed" and "value" in body:
            raise ScenarioError(f"{where}fault.value: a failed actuator gives nothing; failed takes no value")
        if mode == "stuck":
            return Event(time, kind, actuator=body["actuator"], mode=mode, value=_stuck_angle(body, where))
        return Event(time, kind, actuator=body["actuator"], mode=mode,
                     value=number(body, "value", where + "fault."))
    if kind in ("battery_ramp", "weather_ramp"):
        return Event(time, kind, value=number(body, "to", f"{where}{kind}."),
                     duration=number(body, "duration", f"{where}{kind}."))
    if kind == "group_fault":
        if not isinstance(body.get("group"), str):
            raise ScenarioError(f"{where}group_fault.group: a redundancy group's name, not {body.get('group')!r}")
        return Event(time, kind, name=body["group"])
    if kind == "generator_trip":
        if not isinstance(body.get("generator_set"), str):
            raise ScenarioError(f"{where}generator_trip.generator_set: a generator set's name, not "
                                f"{body.get('generator_set')!r}")
        return Event(time, kind, name=body["generator_set"])
    if kind == "power":
        if not isinstance(body.get("source"), str):
            raise ScenarioError(f"{where}power.source: a power source's name, not {body.get('source')!r}")
        return Event(time, kind, name=body["source"], value=number(body, "available", where + "power."))
    if kind == "bus_tie":
        if not isinstance(body.get("name"), str) or not isinstance(body.get("closed"), bool):
            raise ScenarioError(f"{where}bus_tie: name (a bus tie's) and closed (true or false), not {body!r}")
        return Event(time, kind, name=body["name"], value=body["closed"])
    if not isinstance(body.get("name"), str) or "value" not in body:
        raise ScenarioError(f"{where}parameter: name and value")
    return Event(time, kind, name=body["name"], value=body["value"])


def _stuck_angle(body: dict, where: str) -> float | None:
    """A stuck fault's ``value``: the angle [deg in the file, like every angle of it] the
    azimuth is stuck at, in radians; None (absent) for the angle it has then."""
    if "value" not in body:
        return None
    degrees = number(body, "value", where + "fault.")
    if not -180.0 <= degrees <= 180.0:
        raise ScenarioError(f"{where}fault.value: the stuck angle in degrees, -180 to 180, not {degrees!r}")
    return math.radians(degrees)


def _check_event(event: Event, index: int, vehicle: Vehicle) -> None:
    """Raise ScenarioError when the vehicle cannot take the event: an actuator it does not have,
    a fault that actuator cannot have, a parameter the allocator does not know or a value it
    refuses."""
    where = f"events[{index}]"
    try:
        if event.kind == "fault":
            if event.actuator not in vehicle.names:
                raise ValueError(f"{where}.fault.actuator: '{event.actuator}' is not an actuator of the vehicle "
                                 f"({', '.join(vehicle.names)})")
            actuator = vehicle.actuator(event.actuator)
            angle = event.value if event.value is not None else (
                actuator.rotation.initial if actuator.rotation is not None else 0.0)
            mode = FaultMode[event.mode.upper()]
            try:
                FaultSet(vehicle).with_fault(event.actuator, mode, efficiency=event.value, angle=angle)
            except ValueError as error:
                raise ValueError(f"{where}.fault.value: {error}") from error
        elif event.kind == "parameter":
            check_parameter(event.name, f"{where}.parameter.name")
        elif event.kind == "group_fault":
            check_member(event.name, [g.name for g in vehicle.redundancy_groups], f"{where}.group_fault.group",
                         "redundancy group")
        elif event.kind == "power":
            check_member(event.name, [s.name for s in vehicle.power_sources], f"{where}.power.source", "power source")
        elif event.kind == "bus_tie":
            check_member(event.name, [t.name for t in vehicle.bus_ties], f"{where}.bus_tie.name", "bus tie")
    except ValueError as error:
        raise ScenarioError(str(error)) from error


def _replay_events(events: list[Event], vehicle: Path, parameters: dict[str, Any], config: Vehicle) -> Vehicle:
    """The vehicle at the end of the run: the ``events`` in time order, each checked against the
    vehicle at its time (:func:`_check_event`), each parameter event's value over the node
    ``parameters`` of the ``vehicle`` file; ScenarioError naming the first the vehicle refuses."""
    changed = dict(parameters)
    for index, event in sorted(enumerate(events), key=lambda item: item[1].time):
        _check_event(event, index, config)
        if event.kind == "parameter":
            changed[event.name] = event.value
            try:
                config = vehicle_config(vehicle, changed)
            except ScenarioError as error:
                raise ScenarioError(f"events[{index}].parameter: the allocator refuses it: {error}") from error
    return config


def _particulars(data: dict, path: Path, config: Vehicle) -> VesselParticulars:
    """The dp_vessel's particulars file (``particulars``, relative to the scenario), checked
    against the vehicle."""
    if not isinstance(data.get("particulars"), str):
        raise ScenarioError("particulars: required for dp_vessel, a particulars file")
    try:
        read = read_hull(path.parent / data["particulars"])
    except ValueError as error:
        raise ScenarioError(f"particulars: {error}") from error
    try:
        check_particulars("dp_vessel", config, read, data["particulars"])
    except ValueError as error:
        raise ScenarioError(str(error)) from error
    return read.vessel


def load_scenario(path: str | Path) -> Scenario:
    """Read and check a scenario file."""
    path = Path(path)
    try:
        data = read_mapping(path, "a scenario file")
    except ValueError as error:
        raise ScenarioError(str(error)) from error
    unknown = unknown_keys(data)
    if unknown:
        raise ScenarioError("; ".join(unknown))
    model = data.get("model")
    if model not in MODELS:
        raise ScenarioError(f"model: one of {', '.join(MODELS)}, not {model!r}")
    for key in ("vehicle", "method"):
        if not isinstance(data.get(key), str):
            raise ScenarioError(f"{key}: required, a string")
    vehicle = (path.parent / data["vehicle"]).resolve()
    if not vehicle.is_file():
        raise ScenarioError(f"vehicle: no file {vehicle}")
    parameters = data.get("parameters", {}) or {}
    if not isinstance(parameters, dict):
        raise ScenarioError("parameters: a mapping of node parameters")
    config = vehicle_config(vehicle, parameters)
    try:
        check_vehicle(model, config, data["vehicle"])
        check_method_serves(data["method"], config)
    except ValueError as error:
        raise ScenarioError(str(error)) from error
    particulars = _particulars(data, path, config) if model == "dp_vessel" else None
    setpoint, initial = section(data, "setpoint"), section(data, "initial")
    position = vector(setpoint, "position", "setpoint.", 3)
    heading = number(setpoint, "heading", "setpoint.")
    controller = section(data, "controller")
    try:
        gains = Gains(**{k: tuple(controller.get(k, ())) for k in ("kp", "kd", "ki", "unallocated_threshold")})
    except (TypeError, ValueError) as error:
        raise ScenarioError(str(error)) from error
    if len(gains.kp) != (3 if model == "dp_vessel" else 6):
        raise ScenarioError(f"controller.kp: {3 if model == 'dp_vessel' else 6} values for {model}")
    duration = number(data, "duration", "")
    named = read_windows(data.get("windows", []) or [], duration)
    battery = section(data, "battery")
    events = data.get("events", []) or []
    if not isinstance(events, list):
        raise ScenarioError("events: a list")
    checked = [_event(e, i) for i, e in enumerate(events)]
    voltage = number(battery, "voltage", "battery.", minimum=0.0) if battery else None
    initial_position = vector(initial, "position", "initial.", 3, list(position))
    environment_data = section(data, "environment")
    spec = environment(environment_data)
    try:
        check_run(model, config, duration, voltage, checked, environment_data,
                   {"setpoint.position": position, "initial.position": initial_position})
    except ValueError as error:
        raise ScenarioError(str(error)) from error
    plant = read_power_plant(data["power_plant"], config) if "power_plant" in data else None
    check_plant_events(checked, plant)
    check_plant_bounds(data.get("bounds", {}) or {}, plant)
    config = _replay_events(checked, vehicle, parameters, config)
    return Scenario(
        name=str(data.get("name", path.stem)), path=path, vehicle=vehicle, model=model, method=data["method"],
        duration=duration, seed=int(number(data, "seed", "")),
        thruster_time_constant=number(data, "thruster_time_constant", ""),
        setpoint_position=position, setpoint_heading=math.radians(heading),
        initial_position=initial_position,
        initial_heading=math.radians(number(initial, "heading", "initial.", heading)),
        gains=gains, environment=spec, particulars=particulars,
        parameters=dict(parameters), voltage=voltage,
        events=tuple(sorted(checked, key=lambda e: e.time)),
        bounds=read_bounds(data.get("bounds", {}) or {}, "bounds"), windows=tuple(named),
        description=str(data.get("description", "")),
        position_limit=number(data, "position_limit", ""),
        method_bounds=method_bounds(data.get("methods", {}) or {}, named, config),
        control=control_system(data, model, spec), fault_trip=flag(data, "fault_trip", ""), power_plant=plant)

