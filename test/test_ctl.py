"""allocator-ctl's live table line (the command-line round trips are in test_process)."""

import math

from allocator_msgs.msg import AllocationStatus, ThrusterCommands
from allocator_pkg.cli.ctl import format_sample


def test_a_sample_line_shows_thrust_command_azimuth_and_the_solver():
    commands = ThrusterCommands(name=["azimuth_fwd", "main_port"], thrust=[120.0, -35.25],
                                command=[219.09, -0.5], azimuth=[math.radians(30.0), 0.0], mode=[0, 0])
    status = AllocationStatus(saturated=True, solve_time=80e-6, iterations=25, solver_status="solved")
    line = format_sample(commands, status)
    assert "azimuth_fwd     120.0 N cmd   219.09 @  30.0" in line
    assert "main_port     -35.2 N cmd    -0.50" in line and "@" not in line.split("main_port")[1]
    assert "|| sat YES      80 us    25 it solved | unallocated 0.0 0.0 0.0 0.0 0.0 0.0" in line
    assert "at limit" not in line and " V" not in line           # no flags; voltage not set


def test_a_sample_line_shows_the_unallocated_wrench_the_actuators_at_a_limit_and_the_voltage():
    from allocator_pkg.ros.conversions import array_to_wrench
    commands = ThrusterCommands(name=["a", "b", "c"], thrust=[10.0, 20.0, 30.0], command=[1.0, 2.0, 3.0],
                                azimuth=[0.0, 0.0, 0.0], mode=[0, 0, 0])
    status = AllocationStatus(saturated=True, solver_status="solved",
                              unallocated=array_to_wrench([12.5, 0, 0, 0, 0, -3]),
                              at_thrust_limit=[True, False, True], at_rate_limit=[False, False, True], voltage=14.8)
    line = format_sample(commands, status)
    assert line.endswith("| unallocated 12.5 0.0 0.0 0.0 0.0 -3.0 | at limit (! thrust, ~ rate): a! c!~ | 14.80 V")
    status.voltage = math.nan
    assert not format_sample(commands, status).endswith(" V")


def test_a_capability_answer_in_words():
    from allocator_msgs.srv import GetCapability
    from allocator_pkg.cli.ctl import format_capability
    from allocator_pkg.ros.conversions import array_to_wrench
    response = GetCapability.Response(success=True, message="steady state", scale=2.5,
                                      achieved=array_to_wrench([250.0, 0, 0, 0, 0, 0]))
    assert format_capability([100.0, 0, 0, 0, 0, 0], response) == (
        "scale 2.5 along [100 0 0 0 0 0]; achieved there [250.00 0.00 0.00 0.00 0.00 0.00] (steady state)")
    refused = GetCapability.Response(success=False, message="not configured")
    assert format_capability([1.0, 0, 0, 0, 0, 0], refused) == "no capability: not configured"


def test_unknown_parameters_are_named_with_the_nearest_declared_one():
    from allocator_pkg.cli.ctl import unknown_parameters
    declared = ["rate_hz", "weights.minimax", "weights.slack", "wrench_timeout"]
    assert unknown_parameters(["rate_hz", "weights.minimax"], declared, "/thrust_allocator") == []
    assert unknown_parameters(["weights.minmax", "nosuch.param"], declared, "/rov1/thrust_allocator") == [
        "'weights.minmax' is not a parameter of /rov1/thrust_allocator; did you mean weights.minimax?",
        "'nosuch.param' is not a parameter of /rov1/thrust_allocator"]


def test_command_line_values_are_typed_as_a_params_file_types_them():
    from allocator_pkg.cli.ctl import parse_value
    assert parse_value("1.0e6") == 1.0e6 and isinstance(parse_value("1.0e6"), float)
    assert parse_value("[1.0e6, 1.0e6]") == [1.0e6, 1.0e6]
    assert parse_value("[surge, yaw]") == ["surge", "yaw"]
    assert parse_value("[1, 2.5]") == [1.0, 2.5] and parse_value("3") == 3 and parse_value("true") is True
