"""Loading and validating vehicle configurations (ROS 2 params files)."""

import math
import subprocess
import sys

import pytest

from allocator_pkg import ConfigError, vehicle_from_parameters

VALID = {
    "dofs": ["surge", "yaw"],
    "actuators.names": ["port", "stbd", "azi", "rudder"],
    "actuators.port.type": "fixed",
    "actuators.port.position": [-1.0, -0.3, 0.0],
    "actuators.port.direction": [2.0, 0.0, 0.0],
    "actuators.port.thrust_max": 50.0,
    "actuators.stbd.type": "fixed",
    "actuators.stbd.position": [-1.0, 0.3, 0.0],
    "actuators.stbd.direction": [1.0, 0.0, 0.0],
    "actuators.stbd.thrust_max": 50,
    "actuators.azi.type": "azimuth",
    "actuators.azi.position": [1.0, 0.0, 0.0],
    "actuators.azi.thrust_max": 20.0,
    "actuators.azi.forbidden_sectors": [3.0, 3.3],
    "actuators.rudder.type": "rudder",
    "actuators.rudder.position": [-1.2, 0.0, 0.0],
    "actuators.rudder.area": 0.1,
    "actuators.rudder.lift_coefficient": 3.0,
    "actuators.rudder.deflection_max": 0.5,
}


def with_changes(**changes):
    parameters = dict(VALID)
    for key, value in changes.items():
        key = key.replace("__", ".")
        if value is None:
            parameters.pop(key, None)
        else:
            parameters[key] = value
    return parameters


def problem_for(**changes) -> str:
    with pytest.raises(ConfigError) as error:
        vehicle_from_parameters(with_changes(**changes))
    return str(error.value)


def test_valid_parameters_and_defaults():
    vehicle = vehicle_from_parameters(VALID)
    port = vehicle.actuator("port")
    assert port.direction == pytest.approx((1.0, 0.0, 0.0))     # normalised
    assert port.thrust_min == -50.0                              # fixed: reversible by default
    assert vehicle.actuator("stbd").thrust_max == 50.0           # an integer is a float
    azi = vehicle.actuator("azi")
    assert azi.thrust_min == 0.0                                 # not reversible by default
    assert azi.rotation.continuous
    assert azi.rotation.forbidden_sectors == ((3.0, 3.3),)
    rudder = vehicle.actuator("rudder")
    assert rudder.direction == (0.0, 1.0, 0.0)                   # rudder lift along +y by default
    assert rudder.weight == pytest.approx(0.1) and port.weight == 1.0
    assert rudder.power_coefficient == 0.0 and port.power_coefficient == 1.0 == azi.power_coefficient
    fin = vehicle_from_parameters(with_changes(actuators__rudder__type="fin")).actuator("rudder")
    assert fin.direction == (0.0, 0.0, 1.0)                      # fin lift along +z by default
    assert vehicle.method == "qp" and vehicle.rate_hz == 50.0
    assert vehicle.dofs == ("surge", "yaw")
    assert vehicle.weights.slack == ()                           # derived per DOF by the allocator


def test_dofs_are_kept_in_canonical_order_with_their_slack_weights():
    vehicle = vehicle_from_parameters(with_changes(dofs=["yaw", "surge"], weights__slack=[5.0, 7.0]))
    assert vehicle.dofs == ("surge", "yaw")
    assert vehicle.weights.slack == (7.0, 5.0)


@pytest.mark.parametrize(
    ("changes", "key", "reason"),
    [
        ({"actuators__names": None}, "actuators.names", "required"),
        ({"actuators__names": ["port", "port"]}, "actuators.names", "duplicate"),
        ({"actuators__names": ["1bad"]}, "actuators.names", "not a valid name"),
        ({"actuators__port__type": "jet"}, "actuators.port.type", "not one of"),
        ({"actuators__port__direction": [0.0, 0.0, 0.0]}, "actuators.port.direction", "zero"),
        ({"actuators__port__direction": None}, "actuators.port.direction", "required"),
        ({"actuators__port__position": [1.0, 2.0]}, "actuators.port.position", "3 elements"),
        ({"actuators__port__thrust_max": float("nan")}, "actuators.port.thrust_max", "finite"),
        ({"actuators__port__thrust_max": "big"}, "actuators.port.thrust_max", "expected a number"),
        ({"actuators__port__thrust_max": -5.0}, "actuators.port.thrust_max", "must be >"),
        ({"actuators__port__thrust_min": 5.0}, "actuators.port.thrust_min", "must be <= 0"),
        ({"actuators__azi__thrust_min": -5.0}, "actuators.azi.thrust_min", "reversible"),
        ({"actuators__port__command_min": 10.0, "actuators__port__command_max": 5.0},
         "actuators.port.command_min", "below command_max"),
        ({"actuators__port__command_map": "table"}, "actuators.port.table_command", "required"),
        ({"actuators__port__table_thrust": [1.0, 2.0]}, "actuators.port.table_thrust", "only used with"),
        ({"actuators__azi__azimuth_min": 1.0, "actuators__azi__azimuth_max": 0.5},
         "actuators.azi.azimuth_min", "below"),
        ({"actuators__azi__forbidden_sectors": [1.0, 2.0, 3.0]}, "actuators.azi.forbidden_sectors", "pairs"),
        ({"actuators__azi__azimuth_initial": 3.1}, "actuators.azi.azimuth_initial", "forbidden"),
        ({"actuators__azi__direction": [1.0, 0.0, 0.0]}, "actuators.azi.direction", "does not apply"),
        ({"actuators__rudder__thrust_max": 5.0}, "actuators.rudder.thrust_max", "does not apply"),
        ({"actuators__rudder__area": None}, "actuators.rudder.area", "required"),
        ({"actuators__ghost__thrust_max": 5.0}, "actuators.ghost.thrust_max", "not in actuators.names"),
        ({"actuators__port__thrust_maximum": 5.0}, "actuators.port.thrust_maximum", "unknown key"),
        ({"rate": 5.0}, "rate", "unknown key"),
        ({"rate_hz": 0.0}, "rate_hz", "must be >"),
        ({"method": "magic"}, "method", "not one of"),
        ({"dofs": ["surge", "surge"]}, "dofs", "twice"),
        ({"dofs": ["surge", "heading"]}, "dofs", "unknown DOF"),
        ({"weights__slack": [1.0]}, "weights.slack", "one weight per controlled DOF"),
        ({"azimuth_polygon_sides": 2}, "azimuth_polygon_sides", "must be >="),
        ({"azimuth_polygon_sides": 8.5}, "azimuth_polygon_sides", "integer"),
        ({"per_actuator_topics": 1}, "per_actuator_topics", "true or false"),
        ({"consequence__rate": 0.5}, "consequence.rate", "0 (off) or at least 1 Hz"),
        ({"consequence__rate": 20.0}, "consequence.rate", "must be <= 10"),
        ({"consequence__filter_time": -1.0}, "consequence.filter_time", "must be >= 0"),
    ],
)
def test_each_invalid_key_is_named_with_its_reason(changes, key, reason):
    message = problem_for(**changes)
    assert f"{key}:" in message
    assert reason in message


def test_all_problems_are_reported_together():
    with pytest.raises(ConfigError) as error:
        vehicle_from_parameters(with_changes(rate_hz=-1.0, method="x"))
    assert {name for name, _ in error.value.problems} == {"rate_hz", "method"}


def test_table_map_validation():
    base = {"actuators__port__command_map": "table"}
    assert "strictly increasing" in problem_for(**base, actuators__port__table_command=[0.0, 0.0, 1.0],
                                                actuators__port__table_thrust=[-1.0, 0.0, 1.0])
    assert "must not decrease" in problem_for(**base, actuators__port__table_command=[0.0, 1.0, 2.0],
                                              actuators__port__table_thrust=[-1.0, 1.0, 0.0])
    assert "span zero" in problem_for(**base, actuators__port__table_command=[0.0, 1.0],
                                      actuators__port__table_thrust=[1.0, 2.0])


def test_rotation_limits_and_initial_angle():
    vehicle = vehicle_from_parameters(with_changes(actuators__azi__azimuth_min=-1.0, actuators__azi__azimuth_max=1.0,
                                                   actuators__azi__forbidden_sectors=None,
                                                   actuators__azi__azimuth_initial=0.5))
    rotation = vehicle.actuator("azi").rotation
    assert not rotation.continuous
    assert rotation.initial == 0.5
    message = problem_for(actuators__azi__azimuth_min=-1.0, actuators__azi__azimuth_max=1.0,
                          actuators__azi__azimuth_initial=1.5)
    assert "outside the feasible sector" in message
    assert "2 pi" in problem_for(actuators__azi__azimuth_min=-4.0, actuators__azi__azimuth_max=4.0)
    assert math.isclose(vehicle_from_parameters(VALID).actuator("azi").rotation.azimuth_max, math.pi)


VOLTAGE_TABLE = {"actuators__port__command_map": "table", "actuators__port__table_command": [1100.0, 1500.0, 1900.0],
                 "actuators__port__table_voltage": [12.0, 16.0],
                 "actuators__port__table_thrust": [-30.0, 0.0, 40.0, -40.0, 0.0, 50.0], "nominal_voltage": 14.0}


def test_a_voltage_table_and_the_nominal_voltage():
    vehicle = vehicle_from_parameters(with_changes(**VOLTAGE_TABLE))
    command = vehicle.actuator("port").command
    assert command.table_voltage == (12.0, 16.0)
    assert command.thrust_rows == ((-30.0, 0.0, 40.0), (-40.0, 0.0, 50.0))
    assert vehicle.nominal_voltage == 14.0 and vehicle.voltage_range == (12.0, 16.0)


@pytest.mark.parametrize(
    ("changes", "key", "reason"),
    [
        ({"actuators__port__table_voltage": [16.0, 12.0]}, "actuators.port.table_voltage", "strictly increasing"),
        ({"actuators__port__table_voltage": [12.0, 12.0]}, "actuators.port.table_voltage", "strictly increasing"),
        ({"actuators__port__table_voltage": [-1.0, 12.0]}, "actuators.port.table_voltage", "positive"),
        ({"actuators__port__table_thrust": [-30.0, 0.0, 40.0, -40.0, 0.0]}, "actuators.port.table_thrust",
         "needs 6 entries (one row of 3 per voltage of table_voltage, 2)"),
        ({"actuators__port__table_thrust": [-30.0, 0.0, 40.0, -40.0, 10.0, 5.0]}, "actuators.port.table_thrust",
         "must not decrease as the command increases (the row at 16 V)"),
        ({"actuators__port__table_thrust": [-30.0, 0.0, 40.0, 1.0, 2.0, 5.0]}, "actuators.port.table_thrust",
         "must span zero force (the row at 16 V)"),
        ({"nominal_voltage": None}, "nominal_voltage", "required with table_voltage (set for port)"),
        ({"nominal_voltage": 17.0}, "nominal_voltage", "17 V is outside the table of 'port' (12 to 16 V)"),
        ({"nominal_voltage": float("nan")}, "nominal_voltage", "finite"),
        ({"actuators__port__command_deadband": 1.0}, "actuators.port.command_deadband", "flat stretch"),
        ({"actuators__port__command_map": "linear", "actuators__port__table_command": None,
          "actuators__port__table_thrust": None}, "actuators.port.table_voltage", "only used with command_map: table"),
    ],
)
def test_each_invalid_voltage_key_is_named_with_its_reason(changes, key, reason):
    message = problem_for(**{**VOLTAGE_TABLE, **changes})
    assert f"{key}:" in message and reason in message


@pytest.mark.parametrize(
    ("changes", "key", "reason"),
    [
        ({"priorities": [0]}, "priorities",
         "needs one level per controlled DOF in `dofs` order (2: surge, yaw); got 1"),
        ({"priorities": [0, 1, 2]}, "priorities", "got 3"),
        ({"priorities": [0, -1]}, "priorities", "must be >= 0, got -1"),
        ({"priorities": [0.5, 1.0]}, "priorities", "expected a list of integers"),
        ({"priorities": ["yaw", "surge"]}, "priorities", "expected a list of integers"),
        ({"priorities": [1, 0], "saturation": "preserve_direction"}, "priorities", "use one or the other"),
        ({"actuators__port__command_deadband": -1.0}, "actuators.port.command_deadband", "must be >= 0"),
        ({"actuators__port__command_max": 2.0, "actuators__port__command_deadband": 2.0},
         "actuators.port.command_deadband", "leaves no command beyond it"),
        ({"actuators__port__reversed": "yes"}, "actuators.port.reversed", "true or false"),
    ],
)
def test_each_invalid_priority_or_command_key_is_named_with_its_reason(changes, key, reason):
    message = problem_for(**changes)
    assert f"{key}:" in message and reason in message


def test_priorities_are_given_in_dofs_order_and_kept_in_dof_order():
    vehicle = vehicle_from_parameters(with_changes(dofs=["yaw", "surge"], priorities=[0, 1]))
    assert vehicle.dofs == ("surge", "yaw") and vehicle.priorities == (1, 0)
    assert vehicle.priority_levels == ((1,), (0,))
    same = vehicle_from_parameters(with_changes(priorities=[3, 3]))
    assert same.priority_levels == ()                       # one level: nothing to order


def test_reading_a_configuration_loads_no_solver():
    """The configuration sits below the solvers and the methods: importing it (with the package)
    loads none of OSQP, DAQP and HiGHS; the allocator does."""
    code = ("import sys\n"
            "import allocator_pkg.configuration.parameters\n"
            "solvers = ('osqp', 'daqp', 'highspy')\n"
            "print([name for name in solvers if name in sys.modules])\n"
            "from allocator_pkg import Allocator\n"
            "print([name for name in solvers if name in sys.modules])\n")
    lines = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.splitlines()
    assert lines == ["[]", "['osqp', 'daqp', 'highspy']"]
