"""ROS parameters to configuration: params files, flat parameter names, validation.

:func:`read_parameters` reads one node section of a ROS 2 params file into flat, dotted
names; :func:`parse_parameters` checks every name and value against
:mod:`allocator_pkg.configuration.schema` and builds the :class:`~allocator_pkg.vehicle.config.Vehicle` and the
node's :class:`~allocator_pkg.vehicle.node_settings.NodeSettings`. Every problem is reported in one
:class:`~allocator_pkg.vehicle.config.ConfigError` naming each offending key and the reason;
nothing is half-built.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from itertools import pairwise
from pathlib import Path
from typing import Any

import yaml

from ..effectiveness.actuators import command_map
from ..effectiveness.reach import unreachable_dofs
from ..effectiveness.sectors import allowed_arcs, in_feasible_sector, in_forbidden_sector
from ..vehicle.angles import ANGLE_TOLERANCE, TWO_PI
from ..vehicle.config import (
    AZIMUTH,
    AZIMUTH_VERTICAL,
    DOF_NAMES,
    FIN,
    FIXED,
    RUDDER,
    ActuatorConfig,
    CommandMapConfig,
    ConfigError,
    RotationConfig,
    SolverSettings,
    SurfaceConfig,
    Vehicle,
    Weights,
)
from ..vehicle.node_settings import NodeSettings
from . import schema
from .schema import (
    ACTUATOR_KEY_BY_NAME,
    ACTUATOR_PREFIX,
    BOOL,
    FLOAT,
    FLOAT_LIST,
    INT,
    INT_LIST,
    NODE_KEY_BY_NAME,
    STR,
    VEHICLE_KEY_BY_NAME,
    Key,
)


def parse_parameters(parameters: Mapping[str, Any]) -> tuple[Vehicle, NodeSettings]:
    """The vehicle and node settings of flat ROS parameter names and values; raise ConfigError."""
    return _Parser(parameters).parse()


def vehicle_from_parameters(parameters: Mapping[str, Any]) -> Vehicle:
    """The vehicle of flat ROS parameter names and values (node keys are checked, then left)."""
    return parse_parameters(parameters)[0]


def load_vehicle(path: str | Path, node_name: str | None = None) -> Vehicle:
    """Read a ROS 2 params file and build the vehicle of one node section.

    The first ``<node>: ros__parameters:`` section is used unless ``node_name`` picks one
    (see :func:`read_parameters`).
    """
    return vehicle_from_parameters(read_parameters(path, node_name))


class _ParamsLoader(yaml.SafeLoader):
    """YAML as ROS reads params files: also ``1e6`` and ``1.0e6`` are floats (YAML 1.1
    alone reads them as strings; rcl converts them with strtod)."""


_ParamsLoader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(?:[0-9][0-9_]*(?:\.[0-9_]*)?|\.[0-9_]+)[eE][-+]?[0-9]+$"),
    list("-+0123456789."),
)


def section_matches(section: str, node_name: str) -> bool:
    """Whether a params file's section key applies to a node, as rcl matches them: ``/**``
    stands for any namespace and name, ``*`` for one token, and a key without a leading
    ``/`` is in the root namespace. A ``node_name`` without a namespace (no leading ``/``)
    also matches a section of that name in any namespace."""
    pattern = section if section.startswith("/") else f"/{section}"
    expression = "".join("(?:/[^/]+)*" if token == "**" else "/" + re.escape(token).replace(r"\*", "[^/]*")
                         for token in pattern.split("/")[1:])
    if re.fullmatch(expression, node_name if node_name.startswith("/") else f"/{node_name}"):
        return True
    return not node_name.startswith("/") and pattern.rsplit("/", 1)[-1] == node_name


def read_parameters(path: str | Path, node_name: str | None = None) -> dict[str, Any]:
    """Flat parameters of one node section of a ROS 2 params file: the first section, or the
    first that applies to ``node_name`` (a full name such as ``/rov1/thrust_allocator``, or
    a name alone; :func:`section_matches`)."""
    path = Path(path)
    try:
        document = yaml.load(path.read_text(), Loader=_ParamsLoader)
    except OSError as error:
        raise ConfigError([(str(path), f"cannot read the file ({error.strerror})")]) from error
    except yaml.YAMLError as error:
        raise ConfigError([(str(path), f"not valid YAML: {error}")]) from error
    if not isinstance(document, dict) or not document:
        raise ConfigError([(str(path), "expected '<node_name>: ros__parameters: {...}' sections")])
    sections = {
        str(name): body["ros__parameters"]
        for name, body in document.items()
        if isinstance(body, dict) and isinstance(body.get("ros__parameters"), dict)
    }
    if not sections:
        raise ConfigError([(str(path), "no '<node_name>: ros__parameters:' section found")])
    if node_name is None:
        section = next(iter(sections.values()))
    else:
        matches = [body for name, body in sections.items() if section_matches(name, node_name)]
        if not matches:
            raise ConfigError([(str(path), f"no section for node '{node_name}'; sections: {', '.join(sections)}")])
        section = matches[0]
    flat: dict[str, Any] = {}
    problems: list[tuple[str, str]] = []
    _flatten(section, "", flat, problems)
    if problems:
        raise ConfigError(problems)
    return flat


def _flatten(node: Mapping[str, Any], prefix: str, out: dict[str, Any], problems: list[tuple[str, str]]) -> None:
    for key, value in node.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            _flatten(value, name + ".", out, problems)
        elif isinstance(value, list):
            if not value:
                continue  # rcl reads an empty list as "not set"
            kinds = {_ros_type(item) for item in value}
            if len(kinds) > 1:
                problems.append((name, f"a ROS parameter list holds one type, got {sorted(kinds)}; "
                                       "write floats as 1.0, not 1"))
            else:
                out[name] = value
        else:
            out[name] = value


def _ros_type(value: Any) -> str:
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "double"
    if isinstance(value, str):
        return "string"
    return type(value).__name__


_MISSING = object()

MIN_ALLOWED_ARC = math.radians(1.0)
"""[rad] The least total angle a rotatable thruster's feasible sector, less its forbidden
sectors, must leave to thrust in. One degree is about the pointing accuracy of an azimuth
drive: a thruster confined to a narrower arc is a fixed thruster whose direction cannot be
held, and sectors that leave so little are a slip (a start and end swapped, degrees for
radians) far more often than a design."""


class _Parser:
    """Checks every key against the schema and collects all problems."""

    def __init__(self, parameters: Mapping[str, Any]):
        self.parameters = {name: value for name, value in parameters.items() if value is not None}
        self.problems: list[tuple[str, str]] = []
        self._by_type: dict[str, Callable[[str, dict[str, Any], dict[str, Any]], ActuatorConfig | None]] = {
            FIXED: self._thruster, AZIMUTH: self._thruster, AZIMUTH_VERTICAL: self._thruster,
            RUDDER: self._surface, FIN: self._surface,
        }

    def fail(self, name: str, reason: str) -> None:
        self.problems.append((name, reason))

    def value(self, key: Key, name: str | None = None) -> Any:
        """The coerced value of a key, its default, or _MISSING (after recording why)."""
        name = name or key.name
        raw = self.parameters.get(name, _MISSING)
        if raw is _MISSING:
            if key.required:
                self.fail(name, "required key is missing")
                return _MISSING
            return key.default
        value = _coerce(key, raw)
        if isinstance(value, _Invalid):
            self.fail(name, value.reason)
            return _MISSING
        reason = _check_limits(key, value)
        if reason:
            self.fail(name, reason)
            return _MISSING
        return value

    def parse(self) -> tuple[Vehicle, NodeSettings]:
        names_key = VEHICLE_KEY_BY_NAME["actuators.names"]
        names = self.value(names_key)
        known = set(VEHICLE_KEY_BY_NAME) | set(NODE_KEY_BY_NAME)
        actuators: list[ActuatorConfig] = []
        links: dict[str, str] = {}
        if names is not _MISSING:
            names = self._check_names(names)
            for name in names:
                actuator = self._actuator(name)
                if actuator is not None:
                    actuators.append(actuator)
                link = self.parameters.get(schema.actuator_parameter(name, "link"), name)
                links[name] = link if isinstance(link, str) else name
                if not link:
                    self.fail(schema.actuator_parameter(name, "link"), "must not be empty")
                known.update(schema.actuator_parameter(name, key) for key in ACTUATOR_KEY_BY_NAME)
        for name in self.parameters:
            if name not in known:
                self._unknown(name, names if names is not _MISSING else [])

        values = {key.name: self.value(key) for key in schema.VEHICLE_KEYS if key.name != "actuators.names"}
        node = {key.name: self.value(key) for key in schema.NODE_KEYS}
        if node["base_frame"] == "":
            self.fail("base_frame", "must not be empty")
        dofs = self._dofs(values["dofs"])
        if dofs and actuators and len(actuators) == len(names):
            for dof in unreachable_dofs(tuple(actuators), dofs):
                self.fail("dofs", f"no actuator can produce {dof} at any angle (a zero row of T(alpha)); "
                                  f"leave {dof} out of dofs to let the vehicle's dynamics hold it")
        slack = self._slack(values["weights.slack"], values["dofs"], dofs)
        priorities = self._priorities(values, dofs)
        nominal_voltage = self._nominal_voltage(values["nominal_voltage"], actuators)
        if self.problems:
            raise ConfigError(self.problems)
        vehicle = Vehicle(
            actuators=tuple(actuators),
            dofs=dofs,
            method=values["method"],
            saturation=values["saturation"],
            rate_hz=values["rate_hz"],
            weights=Weights(slack=slack, minimax=values["weights.minimax"],
                            azimuth_change=values["weights.azimuth_change"]),
            singularity_rho=values["singularity.rho"],
            singularity_epsilon=values["singularity.epsilon"],
            azimuth_polygon_sides=values["azimuth_polygon_sides"],
            nonlinear_max_iterations=values["nonlinear.max_iterations"],
            solver=SolverSettings(eps_abs=values["solver.eps_abs"], eps_rel=values["solver.eps_rel"],
                                  max_iter=values["solver.max_iter"], time_limit=values["solver.time_limit"]),
            water_density=values["water_density"],
            dynamic_gain=values["dynamic.gain"],
            svd_filter_time_constant=values["svd_filter.time_constant"],
            svd_filter_damping_threshold=values["svd_filter.damping_threshold"],
            priorities=priorities,
            nominal_voltage=nominal_voltage,
            explicit_regions=values["explicit.regions"],
        )
        self._ros2_control(node, vehicle)
        if self.problems:
            raise ConfigError(self.problems)
        settings = NodeSettings(**{key.name.replace(".", "_"): node[key.name] for key in schema.NODE_KEYS},
                                links=links)
        return vehicle, settings

    def _ros2_control(self, node: dict[str, Any], vehicle: Vehicle) -> None:
        """The ros2_control actuators: known, each once, a rotatable one if angles are published;
        ``node['ros2_control.actuators']`` becomes a tuple (the configuration order if unset)."""
        key = "ros2_control.actuators"
        listed = node[key] or [actuator.name for actuator in vehicle.actuators]
        by_name = {actuator.name: actuator for actuator in vehicle.actuators}
        for name in sorted(set(listed) - set(by_name)):
            self.fail(key, f"'{name}' is not in actuators.names ({', '.join(by_name)})")
        for name in sorted({name for name in listed if listed.count(name) > 1}):
            self.fail(key, f"'{name}' is listed {listed.count(name)} times; each actuator at most once")
        if node["ros2_control.angle_topic"] and not any(by_name[name].rotatable for name in listed
                                                        if name in by_name):
            self.fail("ros2_control.angle_topic", f"none of {', '.join(listed)} is a rotatable thruster: no "
                                                  "azimuth angle to publish")
        node[key] = tuple(listed)

    def _check_names(self, names: list[str]) -> list[str]:
        valid = []
        seen = set()
        if not names:
            self.fail("actuators.names", "at least one actuator is needed")
        for name in names:
            if not schema.ACTUATOR_NAME.match(name):
                self.fail("actuators.names", f"'{name}' is not a valid name (letters, digits, '_', "
                                             "starting with a letter)")
            elif name in seen:
                self.fail("actuators.names", f"duplicate name '{name}'")
            else:
                seen.add(name)
                valid.append(name)
        return valid

    def _unknown(self, name: str, names: list[str]) -> None:
        if name.startswith(ACTUATOR_PREFIX):
            actuator, _, key = name[len(ACTUATOR_PREFIX):].partition(".")
            if actuator not in names:
                self.fail(name, f"'{actuator}' is not in actuators.names ({', '.join(names) or 'empty'})")
                return
            actuator_type = self.parameters.get(schema.actuator_parameter(actuator, "type"))
            self.fail(name, f"unknown key '{key}' for a {actuator_type} actuator")
            return
        self.fail(name, schema.REPLACED_KEYS.get(name, "unknown key"))

    def _actuator(self, name: str) -> ActuatorConfig | None:
        """One actuator: the keys common to every type here, the rest by its type's parser."""
        def param(key: str) -> str:
            return schema.actuator_parameter(name, key)

        actuator_type = self.value(ACTUATOR_KEY_BY_NAME["type"], param("type"))
        if actuator_type is _MISSING:
            return None
        applicable = schema.keys_for_type(actuator_type)
        applicable_names = {key.name for key in applicable}
        for key in schema.ACTUATOR_KEYS:
            if key.name not in applicable_names and param(key.name) in self.parameters:
                self.fail(param(key.name), f"does not apply to a {actuator_type} actuator; its keys are "
                                           f"{', '.join(sorted(applicable_names))}")
        v = {key.name: self.value(key, param(key.name)) for key in applicable}
        if any(value is _MISSING for value in v.values()):
            return None
        surface = actuator_type in (RUDDER, FIN)
        weight = v["weight"] if v["weight"] is not None else (0.1 if surface else 1.0)
        power = v["power_coefficient"]
        if power is None:
            power = 0.0 if surface else 1.0
        common = dict(name=name, type=actuator_type, position=tuple(v["position"]),
                      direction=self._direction(actuator_type, v.get("direction"), param("direction")),
                      weight=weight, power_coefficient=power)
        return self._by_type[actuator_type](name, v, common)

    def _surface(self, name: str, v: dict[str, Any], common: dict[str, Any]) -> ActuatorConfig:
        surface = SurfaceConfig(
            area=v["area"], lift_coefficient=v["lift_coefficient"], drag_coefficient=v["drag_coefficient"],
            deflection_max=v["deflection_max"], deflection_rate_max=v["deflection_rate_max"], flow=v["flow"],
            wake_speed_factor=v["wake_speed_factor"], min_control_speed=v["min_control_speed"])
        return ActuatorConfig(**common, surface=surface)

    def _thruster(self, name: str, v: dict[str, Any], common: dict[str, Any]) -> ActuatorConfig | None:
        """A fixed or rotatable thruster: thrust range, command map and, if it turns, rotation."""
        rotatable = common["type"] in (AZIMUTH, AZIMUTH_VERTICAL)
        rotation = self._rotation(name, v) if rotatable else None
        reversible = rotation.reversible if rotation else True
        thrust_max = v["thrust_max"]
        thrust_min = v["thrust_min"]
        if thrust_min is None:
            thrust_min = -thrust_max if reversible else 0.0
        elif thrust_min < 0.0 and not reversible:
            self.fail(schema.actuator_parameter(name, "thrust_min"), "negative thrust needs 'reversible: true'")
        command = self._command_map(name, v, thrust_min, thrust_max)
        if command is None or (rotatable and rotation is None):
            return None
        return ActuatorConfig(**common, thrust_min=thrust_min, thrust_max=thrust_max,
                              thrust_rate_max=v["thrust_rate_max"], command=command, rotation=rotation)

    def _direction(self, actuator_type: str, direction: list[float] | None, name: str) -> tuple[float, float, float]:
        if direction is None:
            if actuator_type == FIXED:
                self.fail(name, "required for a fixed actuator")
                return (1.0, 0.0, 0.0)
            if actuator_type == RUDDER:
                return (0.0, 1.0, 0.0)
            if actuator_type == FIN:
                return (0.0, 0.0, 1.0)
            return (0.0, 0.0, 0.0)
        norm = math.sqrt(sum(c * c for c in direction))
        if norm < 1e-9:
            self.fail(name, "must not be the zero vector")
            return (1.0, 0.0, 0.0)
        return tuple(c / norm for c in direction)

    def _command_map(self, name: str, v: dict[str, Any], thrust_min: float,
                     thrust_max: float) -> CommandMapConfig | None:
        def param(key: str) -> str:
            return schema.actuator_parameter(name, key)

        kind = v["command_map"]
        command_min = v["command_min"] if v["command_min"] is not None else -math.inf
        command_max = v["command_max"] if v["command_max"] is not None else math.inf
        if command_min >= command_max:
            self.fail(param("command_min"), f"must be below command_max ({command_min:g} >= {command_max:g})")
            return None
        table_command: tuple[float, ...] = ()
        table_thrust: tuple[float, ...] = ()
        table_voltage: tuple[float, ...] = ()
        deadband = v["command_deadband"]
        if kind == "table":
            if v["table_command"] is None or v["table_thrust"] is None:
                self.fail(param("table_command" if v["table_command"] is None else "table_thrust"),
                          "required with command_map: table")
                return None
            table_command, table_thrust = tuple(v["table_command"]), tuple(v["table_thrust"])
            table_voltage = tuple(v["table_voltage"] or ())
            if deadband > 0.0:
                self.fail(param("command_deadband"), "applies to linear and quadratic maps; a table's flat "
                                                     "stretch of zero force is its dead band")
                return None
            if any(b <= a for a, b in pairwise(table_voltage)) or any(volts <= 0.0 for volts in table_voltage):
                self.fail(param("table_voltage"), f"must be positive and strictly increasing, got "
                                                  f"{list(table_voltage)}")
                return None
            rows = max(len(table_voltage), 1)
            if len(table_command) < 2 or len(table_thrust) != rows * len(table_command):
                per = f" (one row of {len(table_command)} per voltage of table_voltage, {rows})" if table_voltage \
                    else ""
                self.fail(param("table_thrust"), f"needs {rows * len(table_command)} entries{per}, as many per row "
                                                 f"as table_command (>= 2); got {len(table_thrust)}")
                return None
            if any(b <= a for a, b in pairwise(table_command)):
                self.fail(param("table_command"), "must be strictly increasing")
                return None
            width = len(table_command)
            for row_index in range(rows):
                row = table_thrust[row_index * width:(row_index + 1) * width]
                at = f" (the row at {table_voltage[row_index]:g} V)" if table_voltage else ""
                if any(b < a for a, b in pairwise(row)):
                    self.fail(param("table_thrust"), f"must not decrease as the command increases{at}")
                    return None
                if not row[0] <= 0.0 <= row[-1]:
                    self.fail(param("table_thrust"), f"must span zero force{at}; spans [{row[0]:g}, {row[-1]:g}]")
                    return None
        else:
            for key in ("table_command", "table_thrust", "table_voltage"):
                if v[key] is not None:
                    self.fail(param(key), f"only used with command_map: table (this one is {kind})")
                    return None
            if deadband > 0.0 and not (deadband < command_max and -deadband > command_min):
                self.fail(param("command_deadband"), f"{deadband:g} leaves no command beyond it in "
                                                     f"[{command_min:g}, {command_max:g}]")
                return None
        gain = v["gain"]
        config = CommandMapConfig(kind=kind, gain=gain,
                                  gain_reverse=v["gain_reverse"] if v["gain_reverse"] is not None else gain,
                                  command_min=command_min, command_max=command_max,
                                  table_command=table_command, table_thrust=table_thrust,
                                  table_voltage=table_voltage, deadband=deadband, reversed=v["reversed"])
        low, high = command_map(config, table_voltage[0] if table_voltage else None).force_range()
        if not low <= 0.0 <= high:
            self.fail(param("command_min"), f"the command range [{command_min:g}, {command_max:g}] must include "
                                            "the set-point of zero force")
            return None
        if thrust_min > thrust_max:
            self.fail(param("thrust_min"), f"must not exceed thrust_max ({thrust_min:g} > {thrust_max:g})")
            return None
        return config

    def _rotation(self, name: str, v: dict[str, Any]) -> RotationConfig | None:
        def param(key: str) -> str:
            return schema.actuator_parameter(name, key)

        low, high = v["azimuth_min"], v["azimuth_max"]
        if low >= high:
            self.fail(param("azimuth_min"), f"must be below azimuth_max ({low:g} >= {high:g})")
            return None
        if high - low > TWO_PI + ANGLE_TOLERANCE:
            self.fail(param("azimuth_max"), f"the feasible sector may span at most 2 pi; spans {high - low:g} rad")
            return None
        flat = v["forbidden_sectors"] or []
        if len(flat) % 2:
            self.fail(param("forbidden_sectors"), f"needs [start, end] pairs; got {len(flat)} numbers")
            return None
        sectors = tuple((flat[i], flat[i + 1]) for i in range(0, len(flat), 2))
        for start, end in sectors:
            width = (end - start) % TWO_PI
            if width < ANGLE_TOLERANCE:
                self.fail(param("forbidden_sectors"), f"sector [{start:g}, {end:g}] is empty or the whole circle")
                return None
        rotation = RotationConfig(azimuth_min=low, azimuth_max=high, rate_max=v["azimuth_rate_max"],
                                  forbidden_sectors=sectors, reversible=v["reversible"],
                                  initial=v["azimuth_initial"])
        allowed = sum(end - start for start, end in allowed_arcs(rotation))
        if allowed < MIN_ALLOWED_ARC:
            key = "forbidden_sectors" if sectors else "azimuth_max"
            self.fail(param(key), f"leaves {math.degrees(allowed):.3g} deg of the circle to thrust in; at least "
                                  f"{math.degrees(MIN_ALLOWED_ARC):g} deg is needed")
            return None
        if not in_feasible_sector(rotation, rotation.initial):
            self.fail(param("azimuth_initial"), f"{rotation.initial:g} rad is outside the feasible sector "
                                                f"[{low:g}, {high:g}]")
            return None
        if in_forbidden_sector(rotation, rotation.initial):
            self.fail(param("azimuth_initial"), f"{rotation.initial:g} rad is inside a forbidden sector")
            return None
        return rotation

    def _dofs(self, dofs: Any) -> tuple[str, ...]:
        if dofs is _MISSING:
            return ()
        problems = [d for d in dofs if d not in DOF_NAMES]
        if problems:
            self.fail("dofs", f"unknown DOF {', '.join(map(repr, problems))}; choose from {', '.join(DOF_NAMES)}")
            return ()
        if len(set(dofs)) != len(dofs):
            self.fail("dofs", "lists a DOF twice")
            return ()
        if not dofs:
            self.fail("dofs", "at least one DOF is needed")
        return tuple(d for d in DOF_NAMES if d in dofs)

    def _priorities(self, values: dict[str, Any], dofs: tuple[str, ...]) -> tuple[int, ...]:
        """One level per controlled DOF in the order of ``dofs`` as given, returned in DOF order."""
        priorities, given_order = values["priorities"], values["dofs"]
        if priorities is None or priorities is _MISSING or given_order is _MISSING or not dofs:
            return ()
        if len(priorities) != len(given_order):
            self.fail("priorities", f"needs one level per controlled DOF in `dofs` order ({len(given_order)}: "
                                    f"{', '.join(given_order)}); got {len(priorities)}")
            return ()
        if len(set(priorities)) > 1 and values["saturation"] in ("preserve_direction", "direct"):
            self.fail("priorities", f"orders DOFs of an unattainable request; saturation {values['saturation']} "
                                    "scales them all alike instead: use one or the other")
            return ()
        by_dof = dict(zip(given_order, priorities))
        return tuple(by_dof[d] for d in dofs)

    def _nominal_voltage(self, nominal: Any, actuators: list[ActuatorConfig]) -> float | None:
        """The nominal supply voltage, required by and within every table measured at several voltages."""
        if nominal is _MISSING:
            return None
        tables = [(a.name, a.command.table_voltage) for a in actuators
                  if a.command is not None and a.command.table_voltage]
        if not tables:
            return nominal
        if nominal is None:
            self.fail("nominal_voltage", f"required with table_voltage (set for {', '.join(n for n, _ in tables)})")
            return None
        for name, voltages in tables:
            if not voltages[0] <= nominal <= voltages[-1]:
                self.fail("nominal_voltage", f"{nominal:g} V is outside the table of '{name}' "
                                             f"({voltages[0]:g} to {voltages[-1]:g} V)")
                return None
        return nominal

    def _slack(self, slack: Any, given_order: Any, dofs: tuple[str, ...]) -> tuple[float, ...]:
        if slack is _MISSING or given_order is _MISSING:
            return ()
        if slack is None:
            return ()
        if len(slack) != len(given_order):
            self.fail("weights.slack", f"needs one weight per controlled DOF ({len(given_order)}); got {len(slack)}")
            return ()
        by_dof = dict(zip(given_order, slack))
        return tuple(by_dof[d] for d in dofs)


@dataclass(frozen=True)
class _Invalid:
    reason: str


def _describe(raw: Any) -> str:
    if isinstance(raw, str):
        return f"the string '{raw}'"
    if isinstance(raw, bool):
        return f"the boolean {str(raw).lower()}"
    if isinstance(raw, (list, tuple)):
        return f"a list {list(raw)!r}"
    return f"{type(raw).__name__} {raw!r}"


def _number(raw: Any) -> float | None:
    if isinstance(raw, bool) or not isinstance(raw, (int, float)):
        return None
    return float(raw)


def _coerce(key: Key, raw: Any) -> Any:
    """Convert a parameter value to the key's type, or explain why it cannot be."""
    if key.kind == FLOAT:
        value = _number(raw)
        if value is None:
            return _Invalid(f"expected a number, got {_describe(raw)}")
        if not math.isfinite(value):
            return _Invalid(f"must be finite, got {value}")
        return value
    if key.kind == INT:
        value = _number(raw)
        if value is None or not math.isfinite(value) or value != int(value):
            return _Invalid(f"expected an integer, got {_describe(raw)}")
        return int(value)
    if key.kind == BOOL:
        if not isinstance(raw, bool):
            return _Invalid(f"expected true or false, got {_describe(raw)}")
        return raw
    if key.kind == STR:
        if not isinstance(raw, str):
            return _Invalid(f"expected a string, got {_describe(raw)}")
        return raw
    if not isinstance(raw, (list, tuple)):
        return _Invalid(f"expected a list ({key.kind}), got {_describe(raw)}")
    if key.kind == INT_LIST:
        values = [_number(item) for item in raw]
        if any(item is None or not math.isfinite(item) or item != int(item) for item in values):
            return _Invalid(f"expected a list of integers, got {_describe(raw)}")
        return [int(item) for item in values]
    if key.kind == FLOAT_LIST:
        values = [_number(item) for item in raw]
        if any(item is None for item in values):
            return _Invalid(f"expected a list of numbers, got {_describe(raw)}")
        if not all(math.isfinite(item) for item in values):
            return _Invalid(f"every element must be finite, got {list(raw)!r}")
        return values
    if not all(isinstance(item, str) for item in raw):
        return _Invalid(f"expected a list of strings, got {_describe(raw)}")
    return list(raw)


def _check_limits(key: Key, value: Any) -> str:
    """The reason a typed value breaks the key's limits, or ''."""
    if key.choices and value not in key.choices:
        return f"'{value}' is not one of {', '.join(key.choices)}"
    if key.length is not None and len(value) != key.length:
        return f"needs {key.length} elements, got {len(value)}"
    items = value if isinstance(value, list) else [value]
    if key.kind in (FLOAT, INT, FLOAT_LIST, INT_LIST):
        for item in items:
            if key.minimum is not None:
                if key.exclusive_minimum and item <= key.minimum:
                    return f"must be > {key.minimum:g}, got {item:g}"
                if item < key.minimum:
                    return f"must be >= {key.minimum:g}, got {item:g}"
            if key.maximum is not None and item > key.maximum:
                return f"must be <= {key.maximum:g}, got {item:g}"
    return ""
