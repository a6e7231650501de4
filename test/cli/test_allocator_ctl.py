"""allocator-ctl: its words for the node's answers and the values it sends (the command-line round
trips are in test_process)."""

def test_a_capability_answer_in_words():
    from allocator_msgs.srv import GetCapability
    from allocator_pkg.cli.allocator_ctl import format_capability
    from allocator_pkg.ros.conversions import array_to_wrench
    response = GetCapability.Response(success=True, message="steady state", scale=2.5,
                                      achieved=array_to_wrench([250.0, 0, 0, 0, 0, 0]))
    assert format_capability([100.0, 0, 0, 0, 0, 0], response) == (
        "scale 2.5 along [100 0 0 0 0 0]; achieved there [250.00 0.00 0.00 0.00 0.00 0.00] (steady state)")
    refused = GetCapability.Response(success=False, message="not configured")
    assert format_capability([1.0, 0, 0, 0, 0, 0], refused) == "no capability: not configured"


def test_unknown_parameters_are_named_with_the_nearest_declared_one():
    from allocator_pkg.cli.allocator_ctl import unknown_parameters
    declared = ["rate_hz", "weights.minimax", "weights.slack", "wrench_timeout"]
    assert unknown_parameters(["rate_hz", "weights.minimax"], declared, "/thrust_allocator") == []
    assert unknown_parameters(["weights.minmax", "nosuch.param"], declared, "/rov1/thrust_allocator") == [
        "'weights.minmax' is not a parameter of /rov1/thrust_allocator; did you mean weights.minimax?",
        "'nosuch.param' is not a parameter of /rov1/thrust_allocator"]


def test_command_line_values_are_typed_as_a_params_file_types_them():
    from allocator_pkg.cli.allocator_ctl import parse_value
    assert parse_value("1.0e6") == 1.0e6 and isinstance(parse_value("1.0e6"), float)
    assert parse_value("[1.0e6, 1.0e6]") == [1.0e6, 1.0e6]
    assert parse_value("[surge, yaw]") == ["surge", "yaw"]
    assert parse_value("[1, 2.5]") == [1.0, 2.5] and parse_value("3") == 3 and parse_value("true") is True


def test_allocator_ctl_and_the_nodes_keep_dds_on_this_machine_unless_told_otherwise():
    """Every entry point takes ROS_DOMAIN_ID and ROS_AUTOMATIC_DISCOVERY_RANGE from the
    environment, LOCALHOST and 42 where they are not set, before rclpy starts (rclpy.init is
    stopped there, so nothing reaches DDS)."""
    import os
    import subprocess
    import sys

    probe = ("import os, sys, rclpy\n"
             "def init(*args, **kwargs):\n"
             "    print(os.environ.get('ROS_DOMAIN_ID'), os.environ.get('ROS_AUTOMATIC_DISCOVERY_RANGE'))\n"
             "    sys.exit(0)\n"
             "rclpy.init = init\n"
             "from allocator_pkg.cli import allocator_ctl as ctl\n"
             "from allocator_pkg.ros import main_loop\n"
             "ctl.main(['clear']) if sys.argv[1] == 'ctl' else main_loop.spin(None)\n")
    plain = {k: v for k, v in os.environ.items() if k not in ("ROS_DOMAIN_ID", "ROS_AUTOMATIC_DISCOVERY_RANGE")}
    for entry in ("ctl", "node"):
        default = subprocess.run([sys.executable, "-c", probe, entry], env=plain, capture_output=True, text=True)
        assert default.stdout.split() == ["42", "LOCALHOST"], default.stderr
        chosen = subprocess.run([sys.executable, "-c", probe, entry], capture_output=True, text=True,
                                env={**plain, "ROS_DOMAIN_ID": "7", "ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET"})
        assert chosen.stdout.split() == ["7", "SUBNET"], chosen.stderr
