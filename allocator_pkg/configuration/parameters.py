"""ROS parameters to configuration: flat parameter names checked against the schema and built
into the configuration types.

:func:`parse_parameters` checks every name and value against
:mod:`allocator_pkg.configuration.schema` and builds the :class:`~allocator_pkg.vehicle.config.Vehicle`
and the node's :class:`~allocator_pkg.vehicle.node_settings.NodeSettings`; :func:`load_vehicle`
does so for one section of a params file (:mod:`allocator_pkg.configuration.params_file`). Every
problem is reported in one :class:`~allocator_pkg.vehicle.config.ConfigError` naming each
offending key and the reason; nothing is half-built.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..effectiveness.reach import unreachable_dofs
from ..vehicle.config import (
    DOF_NAMES,
    ActuatorConfig,
    BiasSettings,
    ConfigError,
    SolverSettings,
    Vehicle,
    Weights,
)
from ..vehicle.node_settings import NodeSettings
from . import schema
from .actuator_parsers import parse_actuator
from .bias_pairs import parse_bias_pairs
from .bus_tie_keys import TIES_KEY, parse_bus_ties
from .fields import filled, node_field, vehicle_field
from .flushing_keys import check_flushing
from .params_file import read_parameters
from .power import parse_power
from .schema import ACTUATOR_KEY_BY_NAME, ACTUATOR_PREFIX, NODE_KEY_BY_NAME, VEHICLE_KEY_BY_NAME
from .values import MISSING, Reader

BY_HAND = ("actuators.names", "power.sources", "redundancy_groups.names", TIES_KEY)
"""Vehicle-wide keys read by their own parsers."""


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


class _Parser(Reader):
    """Checks every key against the schema and collects all problems."""

    def parse(self) -> tuple[Vehicle, NodeSettings]:
        names_key = VEHICLE_KEY_BY_NAME["actuators.names"]
        names = self.value(names_key)
        known = set(VEHICLE_KEY_BY_NAME) | set(NODE_KEY_BY_NAME)
        actuators: list[ActuatorConfig] = []
        if names is not MISSING:
            names = self._check_names(names)
            for name in names:
                actuator = parse_actuator(self, name)
                if actuator is not None:
                    actuators.append(actuator)
                if not self.parameters.get(schema.actuator_parameter(name, "link"), name):
                    self.fail(schema.actuator_parameter(name, "link"), "must not be empty")
                known.update(schema.actuator_parameter(name, key) for key in ACTUATOR_KEY_BY_NAME)
        sources, groups, power_keys = parse_power(self, names if names is not MISSING else [], actuators)
        known.update(power_keys)
        ties, tie_keys = parse_bus_ties(self, [source.name for source in sources])
        known.update(tie_keys)
        for name in self.parameters:
            if name not in known:
                self._unknown(name, names if names is not MISSING else [])

        values = {key.name: self.value(key) for key in schema.VEHICLE_KEYS if key.name not in BY_HAND}
        if values["flushing_zones"] is not MISSING:
            check_flushing(self, values["flushing_zones"], actuators)
        node = {key.name: self.value(key) for key in schema.NODE_KEYS}
        if node["base_frame"] == "":
            self.fail("base_frame", "must not be empty")
        rate = node["consequence.rate"]
        if rate is not MISSING and 0.0 < rate < 1.0:
            self.fail("consequence.rate", f"{rate:g} Hz: 0 (off) or at least 1 Hz")
        dofs = self._dofs(values["dofs"])
        if dofs and actuators and len(actuators) == len(names):
            for dof in unreachable_dofs(tuple(actuators), dofs):
                self.fail("dofs", f"no actuator can produce {dof} at any angle (a zero row of T(alpha)); "
                                  f"leave {dof} out of dofs to let the vehicle's dynamics hold it")
        slack = self._slack(values["weights.slack"], values["dofs"], dofs)
        priorities = self._priorities(values, dofs)
        nominal_voltage = self._nominal_voltage(values["nominal_voltage"], actuators)
        bias_pairs = parse_bias_pairs(self, values, actuators, dofs)
        if self.problems:
            raise ConfigError(self.problems)
        vehicle = filled(Vehicle, values, vehicle_field, actuators=tuple(actuators), dofs=dofs,
                         weights=filled(Weights, values, vehicle_field, slack=slack),
                         solver=filled(SolverSettings, values, vehicle_field),
                         priorities=priorities, nominal_voltage=nominal_voltage,
                         bias=filled(BiasSettings, values, vehicle_field, pairs=bias_pairs), power_sources=sources,
                         redundancy_groups=groups, bus_ties=ties)
        ros2_control_actuators = self._ros2_control(node, vehicle)
        if self.problems:
            raise ConfigError(self.problems)
        settings = filled(NodeSettings, node, node_field, ros2_control_actuators=ros2_control_actuators)
        return vehicle, settings

    def _ros2_control(self, node: dict[str, Any], vehicle: Vehicle) -> tuple[str, ...]:
        """The ros2_control actuators: known, each once, a rotatable one if angles are published
        (the configuration order if unset)."""
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
        return tuple(listed)

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
        for prefix, listing in ((schema.TIE_PREFIX, TIES_KEY), (schema.SOURCE_PREFIX, "power.sources"),
                                (schema.GROUP_PREFIX, "redundancy_groups.names")):
            if name.startswith(prefix):
                instance = name[len(prefix):].partition(".")[0]
                self.fail(name, f"'{instance}' is not in {listing}" if schema.key_for(name) else "unknown key")
                return
        self.fail(name, schema.REPLACED_KEYS.get(name, "unknown key"))

    def _dofs(self, dofs: Any) -> tuple[str, ...]:
        if dofs is MISSING:
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
        if priorities is None or priorities is MISSING or given_order is MISSING or not dofs:
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
        if nominal is MISSING:
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
        if slack is MISSING or given_order is MISSING:
            return ()
        if slack is None:
            return ()
        if len(slack) != len(given_order):
            self.fail("weights.slack", f"needs one weight per controlled DOF ({len(given_order)}); got {len(slack)}")
            return ()
        by_dof = dict(zip(given_order, slack))
        return tuple(by_dof[d] for d in dofs)
