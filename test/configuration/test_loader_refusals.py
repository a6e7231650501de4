"""Configurations that cannot work are refused by the loader, naming the key, and a method that
cannot serve the vehicle by the allocator; the node refuses the same as a runtime parameter
change and keeps its configuration; a DOF produced only weakly is a warning (start-up log,
allocator-capability), not an error."""

import math

import pytest
from conftest import ROOT
from test_parameters import VALID, problem_for, with_changes

from allocator_pkg import Allocator, ConfigError, load_vehicle, read_parameters, vehicle_from_parameters
from allocator_pkg.cli import allocator_capability as capability_tool
from allocator_pkg.configuration.actuator_parsers import MIN_ALLOWED_ARC
from allocator_pkg.configuration.params_file import write_parameters
from allocator_pkg.effectiveness.reach import WEAK_SHARE

EXAMPLE = ROOT / "config" / "example1_rov.yaml"
DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"


def test_a_valid_vehicle_and_every_shipped_one_still_load():
    vehicle_from_parameters(VALID)
    for path in sorted((ROOT / "config").glob("*.yaml")) + sorted((ROOT / "test" / "data").glob("*.yaml")):
        assert Allocator(load_vehicle(path)).warnings == [], path


@pytest.mark.parametrize(("changes", "key", "reason"), [
    ({"method": "explicit"}, "method", "'explicit' cannot serve this vehicle: it needs actuators of fixed direction "
                                       "(survey 4.1), and azi rotate; use qp or nonlinear"),
    ({"method": "dynamic", "saturation": "direct"}, "method",
     "'dynamic' cannot serve this vehicle: it does not implement saturation 'direct' (it takes weighted)"),
    ({"method": "nonlinear", "priorities": [1, 0]}, "priorities",
     "method 'nonlinear' does not implement DOF priorities; methods that do: qp, pseudoinverse"),
])
def test_a_method_that_cannot_serve_the_vehicle_loads_and_the_allocator_refuses_it(changes, key, reason):
    """Whether a method can serve a vehicle is the allocator's one check, naming the key."""
    vehicle = vehicle_from_parameters(with_changes(**changes))
    with pytest.raises(ConfigError) as error:
        Allocator(vehicle)
    assert error.value.problems == [(key, reason)]


def test_heave_on_horizontal_azimuths_and_tunnels_is_refused_naming_dofs():
    parameters = read_parameters(DP_VESSEL)
    with pytest.raises(ConfigError) as error:
        vehicle_from_parameters({**parameters, "dofs": ["surge", "sway", "heave", "yaw"]})
    assert error.value.problems == [("dofs", "no actuator can produce heave at any angle (a zero row of T(alpha)); "
                                             "leave heave out of dofs to let the vehicle's dynamics hold it")]


@pytest.mark.parametrize(("dofs", "refused"), [
    (["surge", "sway", "roll", "yaw"], []),                  # with the rudder moved below the origin
    (["surge", "heave", "yaw"], ["heave"]),
    (["surge", "heave", "pitch", "yaw"], ["heave", "pitch"]),
])
def test_each_dof_out_of_reach_is_named(dofs, refused):
    """VALID is planar (every position at z = 0, every force horizontal): heave, roll and pitch
    are out of reach; the rudder's lift gives no roll at z = 0 either."""
    flat = {**VALID, "dofs": dofs}
    if not refused:
        flat["actuators.rudder.position"] = [-1.2, 0.0, 0.4]     # a rudder below the origin: roll
        vehicle_from_parameters(flat)
        return
    with pytest.raises(ConfigError) as error:
        vehicle_from_parameters(flat)
    assert [reason.split(" at ")[0] for key, reason in error.value.problems if key == "dofs"] == \
        [f"no actuator can produce {dof}" for dof in refused]


def test_a_rotatable_thruster_reaches_a_dof_through_either_column():
    """An azimuth at x = 1 gives yaw only through sin(alpha): at alpha = 0 its yaw entry is zero,
    yet it reaches yaw at any other angle; a vertical azimuth gives heave through cos(alpha)."""
    azimuth_alone = {"dofs": ["yaw"], "actuators.names": ["azi"], "actuators.azi.type": "azimuth",
                     "actuators.azi.position": [1.0, 0.0, 0.0], "actuators.azi.thrust_max": 10.0}
    vehicle_from_parameters(azimuth_alone)
    vertical = {"dofs": ["heave", "surge"], "actuators.names": ["v"], "actuators.v.type": "azimuth_vertical",
                "actuators.v.position": [0.0, 0.0, 0.0], "actuators.v.thrust_max": 10.0}
    vehicle_from_parameters(vertical)
    with pytest.raises(ConfigError, match="dofs: no actuator can produce sway"):
        vehicle_from_parameters({**vertical, "dofs": ["heave", "sway"]})


def test_a_fault_does_not_decide_reach():
    """Reach is judged with every actuator nominal: a vehicle loads whatever fails later."""
    vehicle = vehicle_from_parameters({**VALID, "dofs": ["surge", "sway", "yaw"]})
    allocator = Allocator(vehicle)
    allocator.set_fault("azi", 2)
    assert allocator.allocate([0.0, 1.0, 0.0, 0.0, 0.0, 0.0]).saturated


@pytest.mark.parametrize(("sectors", "refused"), [
    ([0.5e-8, -0.5e-8], True),                                   # all but 1e-8 rad
    ([0.25 * MIN_ALLOWED_ARC, -0.25 * MIN_ALLOWED_ARC], True),    # all but half the minimum
    ([0.6 * MIN_ALLOWED_ARC, -0.6 * MIN_ALLOWED_ARC], False),     # all but 1.2 times the minimum
    ([0.4 * MIN_ALLOWED_ARC, math.pi, math.pi, -0.4 * MIN_ALLOWED_ARC], True),   # two sectors together
    ([3.0, 3.3], False),
])
def test_forbidden_sectors_leaving_less_than_the_minimum_are_refused(sectors, refused):
    changes = {"actuators__azi__forbidden_sectors": sectors}
    if not refused:
        vehicle_from_parameters(with_changes(**changes))
        return
    message = problem_for(**changes)
    assert message.startswith("actuators.azi.forbidden_sectors: leaves ")
    assert f"at least {math.degrees(MIN_ALLOWED_ARC):g} deg is needed" in message


def test_a_feasible_sector_narrower_than_the_minimum_is_refused():
    message = problem_for(actuators__azi__forbidden_sectors=None, actuators__azi__azimuth_min=0.0,
                          actuators__azi__azimuth_max=0.5 * MIN_ALLOWED_ARC)
    assert message.startswith("actuators.azi.azimuth_max: leaves 0.5 deg")


@pytest.mark.parametrize("key", ["actuators__port__thrust_max", "actuators__azi__thrust_max", "rate_hz",
                                 "actuators__rudder__area", "weights__minimax"])
@pytest.mark.parametrize("value", ["550e3", True, False, "1.0"])
def test_a_string_or_bool_where_a_number_belongs_is_refused(key, value):
    message = problem_for(**{key: value})
    assert message.startswith(f"{key.replace('__', '.')}: expected a number, got the ")


@pytest.mark.parametrize(("key", "value"), [
    ("actuators__port__position", [1.0, "2.0", 0.0]),
    ("actuators__port__position", [1.0, True, 0.0]),
    ("actuators__port__direction", ["1", "0", "0"]),
    ("actuators__azi__forbidden_sectors", [3.0, "3.3"]),
    ("weights__slack", [1.0, False]),
])
def test_a_string_or_bool_in_a_list_of_numbers_is_refused(key, value):
    assert problem_for(**{key: value}).startswith(f"{key.replace('__', '.')}: expected a list of numbers")


def test_a_string_thrust_in_a_params_file_is_refused(tmp_path):
    text = EXAMPLE.read_text().replace("thrust_max: 300.0", 'thrust_max: "550e3"', 1)
    path = tmp_path / "quoted.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError) as error:
        load_vehicle(path)
    assert error.value.problems == [("actuators.main_port.thrust_max", "expected a number, got the string '550e3'")]


WEAK_HEAVE = {"dofs": ["surge", "heave", "yaw"], "actuators.names": ["port", "stbd", "lift"],
              "actuators.port.type": "fixed", "actuators.port.position": [-1.0, -0.5, 0.0],
              "actuators.port.direction": [1.0, 0.0, 0.0], "actuators.port.thrust_max": 100.0,
              "actuators.stbd.type": "fixed", "actuators.stbd.position": [-1.0, 0.5, 0.0],
              "actuators.stbd.direction": [1.0, 0.0, 0.0], "actuators.stbd.thrust_max": 100.0,
              "actuators.lift.type": "fixed", "actuators.lift.position": [0.0, 0.0, 0.0],
              "actuators.lift.direction": [0.0, 0.0, 1.0], "actuators.lift.thrust_max": 1.0}


def test_a_weak_dof_is_a_warning_not_an_error():
    """Heave from a 1 N thruster against 200 N of surge: 0.5 % of the strongest other DOF."""
    allocator = Allocator(vehicle_from_parameters(WEAK_HEAVE))
    assert allocator.warnings == ["heave is weak: its authority is 0.5 % of the strongest other DOF's (moments "
                                  "per metre of the largest lever); requests in it saturate early"]
    strong = Allocator(vehicle_from_parameters({**WEAK_HEAVE, "actuators.lift.thrust_max": 2.0 / WEAK_SHARE}))
    assert strong.warnings == []


def test_allocator_capability_prints_the_warnings(tmp_path, capsys):
    path = write_parameters(tmp_path / "weak.yaml", WEAK_HEAVE)
    assert capability_tool.main([str(path), "--out", str(tmp_path), "--step", "45",
                                 "--plane", "surge", "yaw"]) == 0
    assert "warning: heave is weak: its authority is 0.5 %" in capsys.readouterr().err


def parameter(name, value):
    from rclpy.parameter import Parameter
    return Parameter(name, value=value)


@pytest.mark.params(EXAMPLE, wrench_timeout=0.0)
@pytest.mark.parametrize(("name", "value", "reason"), [
    ("dofs", ["surge", "sway", "heave", "yaw"], "dofs: no actuator can produce heave at any angle"),
    ("actuators.azimuth_fwd.forbidden_sectors", [0.5e-8, -0.5e-8],
     "actuators.azimuth_fwd.forbidden_sectors: leaves 5.73e-07 deg of the circle"),
    ("method", "explicit", "'explicit' cannot serve this vehicle: it needs actuators of fixed direction"),
])
def test_the_node_refuses_the_same_at_a_runtime_change_and_keeps_its_configuration(harness, name, value, reason):
    node = harness.node
    before = node.allocator.vehicle
    result = node.set_parameters([parameter(name, value)])[0]
    assert not result.successful and reason in result.reason
    assert node.allocator.vehicle == before
    assert node.get_parameter("dofs").value == ["surge", "sway", "yaw"]
    harness.send_wrench([50.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    harness.tick(2)
    assert harness.status[-1].solver_status == "solved"


def test_the_node_refuses_at_start_a_method_that_cannot_serve_the_vehicle(tmp_path, ros_context):
    """The allocator's check, reported as every invalid configuration is: naming the key."""
    from allocator_pkg.ros.node import AllocatorNode
    from allocator_pkg.ros.node_base import NodeConfigError
    params = write_parameters(tmp_path / "explicit.yaml", {**read_parameters(EXAMPLE), "method": "explicit"})
    with pytest.raises(NodeConfigError) as error:
        AllocatorNode(context=ros_context, cli_args=["--ros-args", "--params-file", str(params)])
    assert [key for key, _ in error.value.problems] == ["method"]
    assert "method: 'explicit' cannot serve this vehicle" in error.value.report()
