"""The configuration types are filled from the schema by name: every field is one key's and
every key fills one field, but for the few the builder reads or derives by hand."""

from dataclasses import fields

import pytest

from allocator_pkg import parse_parameters
from allocator_pkg.configuration import schema
from allocator_pkg.configuration.fields import (
    Field,
    actuator_field,
    filled,
    group_field,
    node_field,
    source_field,
    tie_field,
    vehicle_field,
)
from allocator_pkg.vehicle.config import (
    ActuatorConfig,
    BiasSettings,
    BusTie,
    CommandMapConfig,
    PowerSource,
    RedundancyGroup,
    RotationConfig,
    SolverSettings,
    SurfaceConfig,
    Vehicle,
    Weights,
)
from allocator_pkg.vehicle.node_settings import NodeSettings

TABLES = ((schema.VEHICLE_KEYS, vehicle_field), (schema.NODE_KEYS, node_field), (schema.ACTUATOR_KEYS, actuator_field),
          (schema.SOURCE_KEYS, source_field), (schema.GROUP_KEYS, group_field), (schema.TIE_KEYS, tie_field))
STRUCTS = (Vehicle, Weights, SolverSettings, BiasSettings, NodeSettings, ActuatorConfig, CommandMapConfig,
           RotationConfig, SurfaceConfig, PowerSource, RedundancyGroup, BusTie)

NO_FIELD = {"actuators.names", "redundancy_groups.names", "power.bus_ties", "link"}
"""Keys read by hand: the names make Vehicle.actuators, Vehicle.redundancy_groups and
Vehicle.bus_ties, a link is configuration.urdf's."""

NO_KEY = {Vehicle: {"actuators", "weights", "solver", "bias", "redundancy_groups", "bus_ties"},
          ActuatorConfig: {"name", "command", "rotation", "surface"}, PowerSource: {"name"},
          RedundancyGroup: {"name"}, BusTie: {"name"}}
"""Fields of no key: built from other keys (a source's or group's name is its place in the list)."""

DERIVED = {"dofs", "weights.slack", "priorities", "nominal_voltage", "ros2_control.actuators", "position", "direction",
           "thrust_min", "gain_reverse", "command_min", "command_max", "table_command", "table_thrust", "table_voltage",
           "forbidden_sectors", "protects", "power.sources", "feeds", "feed_shares", "sources", "actuators",
           "bias.pairs"}
"""Keys whose field the builder derives by hand (an order, a default that depends on other keys,
a normalised vector, sector pairs, structs or tuples of names); every other key's value is its
field's as it stands."""


def test_every_key_fills_one_field_and_every_field_is_one_key():
    keys_of: dict[Field, list[str]] = {}
    for keys, field_of in TABLES:
        for key in keys:
            field = field_of(key.name)
            assert (field is None) == (key.name in NO_FIELD), key.name
            if field is not None:
                keys_of.setdefault(field, []).append(key.name)
    assert all(len(names) == 1 for names in keys_of.values()), keys_of
    for struct in STRUCTS:
        for field in fields(struct):
            has_key = Field(struct, field.name) in keys_of
            assert has_key != (field.name in NO_KEY.get(struct, ())), f"{struct.__name__}.{field.name}"


VEHICLE_VALUES = {
    "rate_hz": 20.0, "method": "pseudoinverse", "saturation": "preserve_direction", "weights.minimax": 0.5,
    "weights.azimuth_change": 3.0, "singularity.rho": 0.1, "singularity.epsilon": 2e-3, "azimuth_polygon_sides": 12,
    "nonlinear.max_iterations": 3, "dynamic.gain": 0.25, "svd_filter.time_constant": 0.7,
    "svd_filter.damping_threshold": 0.1, "explicit.regions": "regions.npz", "solver.eps_abs": 1e-4,
    "solver.eps_rel": 2e-4, "solver.max_iter": 500, "solver.time_limit": 0.01, "water_density": 1000.0,
    "flushing_zones": "dnv", "power.phase_back": False, "power.restore_ramp": 20.0,
    "bias.enabled": True, "bias.thrust": 5.0, "bias.fade_start": 0.3, "bias.fade_end": 0.6,
    "bias.fade_time_constant": 10.0,
}
NODE_VALUES = {
    "wrench_timeout": 1.5, "per_actuator_topics": True, "frame": "flu", "base_frame": "hull",
    "wrench_type": "wrench_stamped", "trigger": "input", "executor": "single_threaded", "status_rate_hz": 5.0,
    "markers_rate_hz": 2.0, "geometry_source": "robot_description", "battery_timeout": 2.0, "power_timeout": 3.0,
    "power_stale_fallback": 0.5,
    "robot_description_file": "r.urdf", "ros2_control.thrust_topic": "/thrust", "ros2_control.angle_topic": "/angle",
    "step_test.enabled": True, "step_test.thrust_share": 0.3, "step_test.duration_max": 10.0,
    "consequence.rate": 2.0, "consequence.filter_time": 30.0,
}
THRUSTER_VALUES = {
    "type": "azimuth", "weight": 2.0, "power_coefficient": 0.5, "thrust_max": 20.0, "thrust_rate_max": 5.0,
    "command_map": "quadratic", "gain": 2.0, "command_deadband": 0.1, "reversed": True, "azimuth_min": -1.0,
    "azimuth_max": 2.0, "azimuth_rate_max": 0.5, "reversible": True, "azimuth_initial": 0.3, "diameter": 0.4,
    "ducted": True, "reverse_power_coefficient": 0.7, "drive_limit": 12.0,
}
TUNNEL_VALUES = {"type": "fixed", "direction": [0.0, 1.0, 0.0], "thrust_max": 10.0, "tunnel": True}
SOURCE_VALUES = {"capacity": 1500.0}
TIE_VALUES = {"closed": False}
SURFACE_VALUES = {
    "type": "fin", "weight": 0.3, "power_coefficient": 0.2, "area": 0.2, "lift_coefficient": 2.5,
    "drag_coefficient": 0.3, "deflection_max": 0.6, "deflection_rate_max": 0.4, "flow": "propeller_wake",
    "wake_speed_factor": 1.3, "min_control_speed": 0.8,
}


def test_every_other_key_is_the_value_of_its_field():
    """Every key but the derived and the hand-read ones, each at a value unlike its default."""
    parameters = {**VEHICLE_VALUES, **NODE_VALUES, "dofs": ["surge", "heave", "yaw"],
                  "actuators.names": ["azi", "fin", "tun"], "actuators.azi.position": [1.0, 0.0, 0.0],
                  "actuators.fin.position": [-1.0, 0.0, 0.0], "actuators.tun.position": [2.0, 0.0, 0.0],
                  "actuators.tun.feeds": ["bus"]}
    parameters.update({f"actuators.azi.{key}": value for key, value in THRUSTER_VALUES.items()})
    parameters.update({f"actuators.fin.{key}": value for key, value in SURFACE_VALUES.items()})
    parameters.update({f"actuators.tun.{key}": value for key, value in TUNNEL_VALUES.items()})
    parameters.update({"power.sources": ["bus", "aux"], "actuators.azi.feeds": ["bus"], "power.aux.capacity": 1.0,
                       **{f"power.bus.{key}": value for key, value in SOURCE_VALUES.items()},
                       "power.bus_ties": ["tie"], "power.bus_tie.tie.sources": ["bus", "aux"],
                       **{f"power.bus_tie.tie.{key}": value for key, value in TIE_VALUES.items()}})
    parameters.update({"actuators.names": ["azi", "fin", "tun", "partner"], "actuators.partner.type": "azimuth",
                       "actuators.partner.position": [-1.0, 2.0, 0.0], "actuators.partner.thrust_max": 20.0,
                       "actuators.partner.diameter": 0.5,
                       "actuators.partner.feeds": ["bus"], "bias.pairs": ["azi", "partner"]})
    vehicle, settings = parse_parameters(parameters)
    azi, fin, tun, _ = vehicle.actuators
    owners = {Vehicle: vehicle, Weights: vehicle.weights, SolverSettings: vehicle.solver, BiasSettings: vehicle.bias,
              NodeSettings: settings}
    per_actuator = schema.ACTUATOR_KEY_BY_NAME.get
    given = [(VEHICLE_VALUES, vehicle_field, schema.key_for, owners), (NODE_VALUES, node_field, schema.key_for, owners),
             (THRUSTER_VALUES, actuator_field, per_actuator, {ActuatorConfig: azi, CommandMapConfig: azi.command,
                                                              RotationConfig: azi.rotation}),
             (SURFACE_VALUES, actuator_field, per_actuator, {ActuatorConfig: fin, SurfaceConfig: fin.surface}),
             ({"tunnel": True}, actuator_field, per_actuator, {ActuatorConfig: tun}),
             (SOURCE_VALUES, source_field, schema.SOURCE_KEY_BY_NAME.get, {PowerSource: vehicle.power_sources[0]}),
             (TIE_VALUES, tie_field, schema.TIE_KEY_BY_NAME.get, {BusTie: vehicle.bus_ties[0]})]
    checked = set()
    for values, field_of, key_of, objects in given:
        for name, value in values.items():
            assert value != key_of(name).default, name
            field = field_of(name)
            assert getattr(objects[field.struct], field.name) == value, name
            checked.add(name)
    for keys, _ in TABLES:
        for key in keys:
            assert (key.name in checked) != (key.name in DERIVED | NO_FIELD), key.name


def test_filled_takes_the_fields_of_its_struct_and_the_derived_ones_given():
    values = {"weights.minimax": 1.0, "weights.azimuth_change": 2.0, "weights.slack": [9.0], "solver.eps_abs": 3.0}
    assert filled(Weights, values, vehicle_field, slack=(1.0,)) == Weights(slack=(1.0,), minimax=1.0,
                                                                          azimuth_change=2.0)
    with pytest.raises(TypeError, match="slack"):
        filled(Weights, {"weights.minimax": 1.0, "weights.azimuth_change": 2.0}, vehicle_field)
