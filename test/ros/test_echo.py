"""allocator-ctl echo: its live table line, and its CSV, each row a sample's commands with the
status of the same sample, from a node on simulated time."""

import csv
import io
import math

import pytest
from conftest import ROOT

from allocator_msgs.msg import AllocationStatus, ThrusterCommands
from allocator_pkg.ros.echo import format_sample

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


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
    assert line.split("\n")[1:] == ["|| sat YES       0 us     0 it solved | unallocated 12.5 0.0 0.0 0.0 0.0 -3.0 | "
                                     "at limit (! thrust, ~ rate): a! c!~", "  | 14.80 V"]
    status.voltage = math.nan
    assert not format_sample(commands, status).endswith(" V")


def test_a_sample_line_shows_the_power_per_source_when_the_vehicle_has_sources():
    commands = ThrusterCommands(name=["a", "b"], thrust=[10.0, 20.0], command=[1.0, 2.0], azimuth=[0.0, 0.0],
                                mode=[0, 0])
    status = AllocationStatus(solver_status="solved", power_source=["swbd_a", "swbd_b"],
                              source_power=[998.7, 12.25], source_available=[1000.0, 7800.0], power_limited=True)
    assert format_sample(commands, status).endswith("| power swbd_a 999/1000 kW, swbd_b 12/7800 kW LIMITED")
    status.power_limited = False
    assert format_sample(commands, status).endswith("swbd_b 12/7800 kW")
    status.power_source, status.source_power, status.source_available = [], [], []
    assert "power" not in format_sample(commands, status)


def csv_rows(harness, samples: int, **settings) -> list[dict[str, str]]:
    from allocator_pkg.ros.echo import Echo
    from allocator_pkg.ros.node_client import Controller

    table = io.StringIO()
    echo = Echo(Controller(harness.probe), io.StringIO(), csv_file=table, rate=0.0, **settings)
    harness.spin_until(lambda: echo._status.get_publisher_count() > 0 and echo._commands.get_publisher_count() > 0)
    harness.send_wrench([100.0, 20.0, 0.0, 0.0, 0.0, 10.0])
    first = len(harness.commands)
    harness.tick(samples)
    harness.spin_for(0.3)
    echo.close()
    rows = list(csv.DictReader(io.StringIO(table.getvalue())))
    stamps = [f"{c.header.stamp.sec + c.header.stamp.nanosec * 1e-9}" for c in harness.commands[first:]]
    assert [row["stamp"] for row in rows][-samples:] == stamps
    return rows[-samples:]


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
def test_every_csv_row_has_the_status_of_its_own_sample(harness):
    rows = csv_rows(harness, 5)
    statuses = {f"{s.header.stamp.sec + s.header.stamp.nanosec * 1e-9}": s for s in harness.status}
    for row in rows:
        status = statuses[row["stamp"]]
        assert row["solver_status"] == status.solver_status and row["iterations"] == str(status.iterations)
        assert float(row["unallocated.x"]) == status.unallocated.force.x


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0, status_rate_hz=10.0)
def test_a_sample_without_a_status_of_its_own_has_empty_status_columns(harness):
    rows = csv_rows(harness, 10)
    reported = {f"{s.header.stamp.sec + s.header.stamp.nanosec * 1e-9}" for s in harness.status}
    with_status = [row["stamp"] in reported for row in rows]
    assert 0 < sum(with_status) < len(rows)
    for row, has in zip(rows, with_status):
        assert (row["solver_status"] != "") == has


def test_the_live_table_of_a_dp_vessel_keeps_within_its_width():
    """Four actuators with long names at kN thrusts, saturated, every one at a limit, two sources:
    each line at most WIDTH characters, every figure still there."""
    from allocator_pkg.simulation.live_text import WIDTH
    names = ["azimuth_stbd", "azimuth_port", "tunnel_fwd", "tunnel_aft"]
    commands = ThrusterCommands(name=names, thrust=[419999.9, 655000.0, -300000.0, 299999.5],
                                command=[147.43, 160.0, -155.5, 155.5],
                                azimuth=[math.radians(47.4), math.radians(-133.0), 0.0, 0.0], mode=[0, 0, 0, 0])
    status = AllocationStatus(saturated=True, solve_time=1234e-6, iterations=112, solver_status="solved",
                              at_thrust_limit=[True] * 4, at_rate_limit=[True] * 4, power_source=["swbd_a", "swbd_b"],
                              source_power=[5599.6, 7800.0], source_available=[5600.0, 7800.0], power_limited=True)
    lines = format_sample(commands, status).split("\n")
    assert max(len(line) for line in lines) <= WIDTH
    text = "\n".join(lines)
    assert "azimuth_port  655000.0 N cmd   160.00 @-133.0" in text and "tunnel_aft  299999.5 N" in text
    assert lines[2].startswith("|| sat YES    1234 us   112 it solved | unallocated")
    assert text.endswith("power swbd_a 5600/5600 kW, swbd_b 7800/7800 kW LIMITED")
