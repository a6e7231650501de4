"""allocator-ctl: its words for the node's answers and the values it sends (the command-line round
trips are in test_process)."""

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
