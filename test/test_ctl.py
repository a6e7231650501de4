"""allocator-ctl's live table line (the command-line round trips are in test_process)."""

import math

from allocator_msgs.msg import AllocationStatus, ThrusterCommands
from allocator_pkg.ctl import format_sample


def test_a_sample_line_shows_thrust_command_azimuth_and_the_solver():
    commands = ThrusterCommands(name=["azimuth_fwd", "main_port"], thrust=[120.0, -35.25],
                                command=[219.09, -0.5], azimuth=[math.radians(30.0), 0.0], mode=[0, 0])
    status = AllocationStatus(saturated=True, solve_time=80e-6, iterations=25, solver_status="solved")
    line = format_sample(commands, status)
    assert "azimuth_fwd     120.0 N cmd   219.09 @  30.0" in line
    assert "main_port     -35.2 N cmd    -0.50" in line and "@" not in line.split("main_port")[1]
    assert line.endswith("|| sat YES      80 us    25 it solved")
