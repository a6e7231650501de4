"""The Allocator facade: public API, faults, commands, state and warnings."""

import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import DATA, ROOT, vehicle_from

from allocator_pkg import Allocator, ConfigError, FaultMode, load_vehicle, vehicle_from_parameters
from allocator_pkg.effectiveness.actuators import command_map

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


@pytest.fixture
def alloc():
    return Allocator(load_vehicle(EXAMPLE))


def test_public_api(alloc):
    assert alloc.names == ("azimuth_fwd", "azimuth_aft", "main_port", "main_stbd")
    assert alloc.dofs == ("surge", "sway", "yaw")
    assert alloc.method == "qp"
    assert alloc.dt == pytest.approx(1 / 50)
    result = alloc.allocate([50.0, 10.0, 99.0, 99.0, 99.0, 5.0])     # heave, roll, pitch ignored
    assert result.thrust.shape == result.azimuth.shape == result.command.shape == (4,)
    assert result.achieved.shape == (6,)
    assert result.method == "qp" and result.status == "solved"
    assert result.iterations > 0 and result.solve_time > 0.0
    assert result.power == pytest.approx(np.sum(np.abs(result.thrust) ** 1.5))
    assert result.achieved == pytest.approx(alloc.configuration_matrix() @ result.thrust)
    assert alloc.configuration_matrix([0.5, 0, 0, 0])[1, 0] == pytest.approx(math.sin(0.5))


@pytest.mark.parametrize("tau", [[1, 2, 3], [0, 0, math.nan, 0, 0, 0], [math.inf, 0, 0, 0, 0, 0]])
def test_bad_requests_raise_and_change_nothing(alloc, tau):
    before = alloc.thrust
    with pytest.raises(ValueError, match="tau"):
        alloc.allocate(tau)
    assert np.array_equal(alloc.thrust, before)
    assert alloc.stats.samples == 0


def test_fault_errors_name_the_valid_choices(alloc):
    with pytest.raises(ValueError, match="unknown actuator 'ghost'; actuators: azimuth_fwd, azimuth_aft"):
        alloc.set_fault("ghost", FaultMode.FAILED)
    for efficiency in (0.0, -1.0, 2.0, math.nan, None):
        with pytest.raises(ValueError, match=r"efficiency in \(0, 1\]"):
            alloc.set_fault("main_port", FaultMode.DEGRADED, efficiency=efficiency)
    with pytest.raises(ValueError, match="these can be stuck: azimuth_fwd, azimuth_aft"):
        alloc.set_fault("main_port", FaultMode.STUCK, angle=0.3)
    with pytest.raises(ValueError, match="unknown fault mode"):
        alloc.set_fault("main_port", 7)
    assert alloc.faults == {}


def test_stuck_outside_the_feasible_sector_is_refused():
    vehicle = vehicle_from(EXAMPLE, actuators__azimuth_fwd__azimuth_min=-1.0, actuators__azimuth_fwd__azimuth_max=1.0)
    alloc = Allocator(vehicle)
    with pytest.raises(ValueError, match="outside the feasible sector"):
        alloc.set_fault("azimuth_fwd", FaultMode.STUCK, angle=2.0)


def test_commands_map_back_to_the_allocated_force():
    vehicle = vehicle_from(EXAMPLE)
    alloc = Allocator(vehicle)
    alloc.set_fault("main_stbd", FaultMode.DEGRADED, efficiency=0.5)
    for _ in range(50):
        result = alloc.allocate([200.0, 30.0, 0.0, 0.0, 0.0, -20.0])
    for actuator, force, command, mode in zip(vehicle.actuators, result.thrust, result.command, result.mode):
        efficiency = 0.5 if mode == FaultMode.DEGRADED else 1.0
        assert efficiency * command_map(actuator.command).force(command) == pytest.approx(force, abs=1e-6)


def test_stop_zeroes_thrust_and_holds_angles(alloc):
    for _ in range(30):
        alloc.allocate([0.0, 80.0, 0.0, 0.0, 0.0, 0.0])
    angles = alloc.azimuth
    stopped = alloc.stop()
    assert np.all(stopped.thrust == 0.0)
    assert np.array_equal(stopped.azimuth, angles)
    assert stopped.status == "stopped"


def test_reset_returns_to_initial_angles(alloc):
    alloc.allocate([0.0, 80.0, 0.0, 0.0, 0.0, 0.0])
    alloc.reset()
    assert np.all(alloc.azimuth == 0.0) and np.all(alloc.thrust == 0.0)


def test_uncontrollable_dofs_are_reported():
    """The loader refuses a controlled DOF out of reach; a Vehicle built in code still gets
    the warning."""
    along_x = {f"actuators__t{i}__direction": [1.0, 0.0, 0.0] for i in range(1, 9)}
    with pytest.raises(ConfigError, match="dofs: no actuator can produce heave"):
        vehicle_from(DATA / "eight_thrusters.yaml", dofs=["surge", "heave", "yaw"], **along_x)
    otter_like = replace(vehicle_from(DATA / "eight_thrusters.yaml", dofs=["surge", "yaw"], **along_x),
                         dofs=("surge", "heave", "yaw"))
    alloc = Allocator(otter_like)
    assert any("no actuator can produce heave" in w for w in alloc.warnings)
    assert alloc.uncontrolled == ("sway", "roll", "pitch")


def test_a_controlled_dof_out_of_reach_is_a_warning_not_an_under_actuation_note():
    along_x = {f"actuators__t{i}__direction": [1.0, 0.0, 0.0] for i in range(1, 9)}
    leaves = vehicle_from(DATA / "eight_thrusters.yaml", dofs=["surge", "yaw"], **along_x)
    controls_sway = Allocator(replace(leaves, dofs=("surge", "sway", "yaw")))
    assert any("no actuator can produce sway" in w for w in controls_sway.warnings) and controls_sway.notes == []
    leaves_sway = Allocator(vehicle_from(DATA / "eight_thrusters.yaml", dofs=["surge", "yaw"], **along_x))
    assert leaves_sway.warnings == []
    assert leaves_sway.notes == ["under-actuated: the actuators give 2 independent directions in surge, sway, yaw; "
                                 "sway is left to the vehicle's dynamics"]


def test_the_reach_the_faults_take_is_named_when_they_change():
    """dp_vessel: azimuths at (-41.5, +-7) m, tunnels along y at x 37 and 35 m; a force (fx, fy)
    at (x, y) gives yaw x fy - y fx, an azimuth at angle a thrusts along (cos a, sin a)."""
    alloc = Allocator(load_vehicle(ROOT / "config" / "dp_vessel.yaml"))
    assert alloc.lost_reach == []
    alloc.set_fault("tunnel_fwd", FaultMode.FAILED)
    alloc.set_fault("tunnel_aft", FaultMode.FAILED)
    assert alloc.lost_reach == []                      # (1, 0, -7), (0, 1, -41.5), (1, 0, 7): rank 3
    alloc.set_fault("azimuth_stbd", FaultMode.STUCK, angle=0.0)
    alloc.set_fault("azimuth_port", FaultMode.STUCK, angle=0.0)
    assert alloc.lost_reach == [                       # (1, 0, -7), (1, 0, 7): no sway, surge and yaw alone
        "after the faults no working actuator produces sway; requests in it will always be saturated"]
    alloc.set_fault("azimuth_port", FaultMode.FAILED)
    alloc.set_fault("azimuth_stbd", FaultMode.NOMINAL)
    assert alloc.lost_reach == [                       # (1, 0, -7), (0, 1, -41.5): no unit wrench in their span
        "after the faults the working actuators reach 2 independent directions of the 3 controlled DOFs "
        "(surge, sway, yaw), 3 with every actuator; surge, sway, yaw only together with other DOFs; some "
        "combinations will be saturated"]
    alloc.set_fault("azimuth_stbd", FaultMode.STUCK, angle=math.pi / 2)
    assert alloc.lost_reach == [                       # (0, 1, -41.5) alone
        "after the faults no working actuator produces surge; requests in it will always be saturated",
        "after the faults the working actuators reach 1 independent direction of the 3 controlled DOFs "
        "(surge, sway, yaw), 3 with every actuator; sway, yaw only together with other DOFs; some combinations "
        "will be saturated"]
    alloc.clear_faults()
    assert alloc.lost_reach == []
    alloc.set_group_fault("switchboard_b")             # azimuth_port, tunnel_aft: (1, 0, -7), (0, 1, -41.5), (0, 1, 37)
    assert alloc.lost_reach == []
    alloc.set_fault("tunnel_fwd", FaultMode.DEGRADED, efficiency=0.2)
    assert alloc.lost_reach == []                      # weaker, not gone
    alloc.set_fault("tunnel_fwd", FaultMode.FAILED)
    assert len(alloc.lost_reach) == 1 and "surge, sway, yaw only together" in alloc.lost_reach[0]
    assert alloc.warnings == []                        # the configuration's own warnings stay as they were


def test_unknown_method_and_bad_dt():
    vehicle = load_vehicle(EXAMPLE)
    with pytest.raises(ValueError, match="unknown method 'fast'"):
        Allocator(vehicle, method="fast")
    with pytest.raises(ValueError, match="dt"):
        Allocator(vehicle, dt=0.0)


def test_reconfigure_keeps_faults_and_refuses_other_actuators(alloc):
    alloc.set_fault("main_port", FaultMode.FAILED)
    alloc.reconfigure(vehicle_from(EXAMPLE, rate_hz=20.0))
    assert alloc.dt == pytest.approx(0.05)
    assert alloc.faults["main_port"].mode == FaultMode.FAILED
    with pytest.raises(ValueError, match="keeps the actuators"):
        alloc.reconfigure(load_vehicle(DATA / "eight_thrusters.yaml"))


def test_a_cached_method_takes_the_changes_made_while_another_ran_when_chosen_again(monkeypatch):
    """A configuration change updates the method in use only, not every cached one (a change
    costs one method's update); a cached method chosen again takes the latest values then,
    with no new solver, and answers as a fresh allocator of that configuration does."""
    from allocator_pkg.methods import METHODS
    updated = []
    for name in ("qp", "lp"):
        original = METHODS[name].update_model
        monkeypatch.setattr(METHODS[name], "update_model",
                            lambda self, model, name=name, original=original: (updated.append(name),
                                                                               original(self, model)))
    tau = np.array([120.0, 40.0, 0.0, 0.0, 0.0, 30.0])
    alloc = Allocator(load_vehicle(EXAMPLE))
    alloc.allocate(tau)
    alloc.reconfigure(vehicle_from(EXAMPLE, method="lp"))
    alloc.allocate(tau)
    setups = alloc.stats.solver_setups
    for thrust_max in (250.0, 200.0, 100.0):
        alloc.reconfigure(vehicle_from(EXAMPLE, method="lp", actuators__main_port__thrust_max=thrust_max))
        alloc.allocate(tau)
    assert updated == ["lp"] * 3
    final = vehicle_from(EXAMPLE, actuators__main_port__thrust_max=100.0)
    alloc.reconfigure(final)
    assert updated == ["lp"] * 3 + ["qp"]
    assert alloc.stats.solver_setups == setups
    alloc.reset()
    fresh = Allocator(final)
    for _ in range(100):
        mine, theirs = alloc.allocate(tau), fresh.allocate(tau)
    assert alloc.ranges[1][2] == 100.0 and mine.thrust[2] <= 100.0
    assert mine.thrust == pytest.approx(theirs.thrust, abs=1e-3 * 300.0)
    assert mine.azimuth == pytest.approx(theirs.azimuth, abs=1e-4)


NARROW_TWIN = {"dofs": ["surge", "yaw"], "actuators.names": ["port", "stbd"],
               "actuators.port.type": "fixed", "actuators.port.position": [0.0, -0.1, 0.0],
               "actuators.port.direction": [1.0, 0.0, 0.0], "actuators.stbd.direction": [1.0, 0.0, 0.0],
               "actuators.port.thrust_min": -1e5, "actuators.port.thrust_max": 1e5,
               "actuators.stbd.type": "fixed", "actuators.stbd.position": [0.0, 0.1, 0.0],
               "actuators.stbd.thrust_min": -1e5, "actuators.stbd.thrust_max": 1e5}


def test_a_change_of_method_only_switches_methods(monkeypatch):
    """A configuration that differs only in ``method`` builds no new model: the method chosen
    takes the current values (a clean start), the state carries over."""
    import allocator_pkg.allocation.allocator as allocator_module
    alloc = Allocator(load_vehicle(EXAMPLE))
    tau = np.array([120.0, 40.0, 0.0, 0.0, 0.0, 30.0])
    alloc.allocate(tau)
    built = []
    original = allocator_module.Model.build
    monkeypatch.setattr(allocator_module.Model, "build", lambda *args: built.append(args) or original(*args))
    for method in ("lp", "pseudoinverse", "qp"):
        thrust = alloc.thrust
        alloc.reconfigure(vehicle_from(EXAMPLE, method=method))
        assert alloc.method == method and alloc.vehicle == vehicle_from(EXAMPLE, method=method)
        assert np.array_equal(alloc.thrust, thrust)
        for _ in range(100):
            result = alloc.allocate(tau)
        assert result.method == method and result.achieved[[0, 1, 5]] == pytest.approx(tau[[0, 1, 5]], abs=0.3)
    assert built == []
    alloc.reconfigure(vehicle_from(EXAMPLE, rate_hz=20.0))
    assert len(built) == 1 and alloc.dt == pytest.approx(0.05)


def test_warnings_follow_a_reconfigured_geometry():
    """The reach warnings are kept across changes that leave the geometry alone and made again
    when positions or directions change."""
    alloc = Allocator(vehicle_from_parameters(NARROW_TWIN))
    assert alloc.warnings == []
    in_line = {**NARROW_TWIN, "actuators.port.position": [0.0, 0.0, 0.0], "actuators.stbd.position": [0.0, 0.0, 0.0]}
    def without_yaw(parameters):                    # the loader refuses yaw out of reach; code may build it
        return replace(vehicle_from_parameters({**parameters, "dofs": ["surge"]}), dofs=("surge", "yaw"))

    alloc.reconfigure(without_yaw({**in_line, "actuators.port.thrust_max": 5e4}))
    assert alloc.warnings == ["no actuator can produce yaw; requests in it will always be saturated"]
    alloc.reconfigure(without_yaw({**in_line, "actuators.port.thrust_max": 4e4}))
    assert len(alloc.warnings) == 1
    alloc.reconfigure(vehicle_from_parameters(NARROW_TWIN))
    assert alloc.warnings == []


@pytest.mark.parametrize(("yaw_factor", "saturated"), [(0.999, False), (1.003, True)])
def test_saturation_is_judged_in_each_dof_against_its_own_authority(yaw_factor, saturated):
    """Two 1e5 N thrusters 0.2 m apart: surge authority 2e5 N, yaw authority 0.1 (2e5) = 2e4 N m.
    A yaw moment 0.3 % beyond it misses by 60 N m: 3e-3 of the yaw authority, so saturated,
    although that is less than 1e-3 of the thrusters' force."""
    alloc = Allocator(vehicle_from_parameters(NARROW_TWIN))
    tau = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 2e4 * yaw_factor])
    result = alloc.allocate(tau)
    assert result.saturated is saturated
    if saturated:
        assert result.achieved[5] == pytest.approx(2e4, rel=1e-4)
        assert abs(result.achieved[5] - tau[5]) < 1e-3 * 1e5       # below the force-based tolerance
    else:
        assert result.achieved[[0, 5]] == pytest.approx(tau[[0, 5]], abs=1e-3 * 2e4)


BLUEROV = ROOT / "config" / "bluerov2_heavy.yaml"
T200_VOLTS = [10.0, 12.0, 14.0, 16.0, 18.0, 20.0]
T200_AT_1900 = [28.7, 36.4, 44.3, 51.5, 59.0, 65.9]       # Blue Robotics' data, the curves' forward ends [N]


@pytest.mark.parametrize("method", ["qp", "pseudoinverse"])
def test_thrust_limits_follow_the_supply_voltage_without_a_new_solver(method):
    alloc = Allocator(load_vehicle(BLUEROV), method=method)
    assert alloc.voltage == 16.0
    heave = alloc.allocate([0.0, 0.0, 400.0, 0.0, 0.0, 0.0])
    assert heave.achieved[2] == pytest.approx(4 * 51.5, rel=1e-5)
    setups = alloc.stats.solver_setups
    for volts in np.arange(10.0, 20.01, 0.5):
        alloc.set_voltage(volts)
        result = alloc.allocate([0.0, 0.0, 400.0, 0.0, 0.0, 0.0])
        expected = np.interp(volts, T200_VOLTS, T200_AT_1900)
        assert result.achieved[2] == pytest.approx(4 * expected, rel=1e-4)
        assert result.saturated and result.at_thrust_limit[4:].all() and not result.at_thrust_limit[:4].any()
        assert result.command[4:] == pytest.approx(1900.0, abs=0.1)      # the end of the curve in use
        assert alloc.ranges[1][4] == pytest.approx(expected)
    assert alloc.stats.solver_setups == setups


@pytest.mark.parametrize("volts", [math.nan, math.inf, -12.0, 0.0, 9.9, 20.1])
def test_a_voltage_that_is_not_finite_or_outside_the_tables_is_refused_and_changes_nothing(volts):
    alloc = Allocator(load_vehicle(BLUEROV))
    alloc.set_voltage(12.0)
    before = alloc.ranges
    with pytest.raises(ValueError, match="finite and positive" if not 0.0 < volts < math.inf else "10 to 20 V"):
        alloc.set_voltage(volts)
    assert alloc.voltage == 12.0
    assert np.array_equal(alloc.ranges[0], before[0]) and np.array_equal(alloc.ranges[1], before[1])


def test_a_vehicle_without_voltage_tables_takes_a_voltage_and_keeps_its_limits():
    alloc = Allocator(vehicle_from(DATA / "eight_thrusters.yaml"))
    assert alloc.voltage is None
    alloc.set_voltage(12.0)
    assert alloc.voltage == 12.0 and alloc.ranges[1].tolist() == [40.0] * 8


def test_reconfiguration_keeps_the_voltage():
    alloc = Allocator(load_vehicle(BLUEROV))
    alloc.set_voltage(13.0)
    alloc.reconfigure(vehicle_from(BLUEROV, weights__minimax=1.0))
    assert alloc.voltage == 13.0
    assert alloc.ranges[1][0] == pytest.approx(np.interp(13.0, T200_VOLTS, T200_AT_1900))


def test_unallocated_is_requested_minus_achieved_in_the_controlled_dofs():
    alloc = Allocator(load_vehicle(EXAMPLE))              # surge, sway, yaw
    for _ in range(200):
        result = alloc.allocate([900.0, 300.0, 50.0, 5.0, 5.0, 400.0])
    assert result.saturated
    controlled = [0, 1, 5]
    assert result.unallocated[controlled] == pytest.approx(result.requested[controlled] - result.achieved[controlled])
    assert result.unallocated[[2, 3, 4]].tolist() == [0.0, 0.0, 0.0]
    assert np.abs(result.unallocated[controlled]).max() > 1.0
    for _ in range(300):                                                   # rate limits: thrust ramps down
        calm = alloc.allocate([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert not calm.saturated and np.abs(calm.unallocated).max() < 1e-3 * 10.0
    assert alloc.stop().unallocated.tolist() == [0.0] * 6


def test_limit_flags_name_the_actuators_at_their_thrust_and_rate_limits():
    eight = DATA / "eight_thrusters.yaml"
    alloc = Allocator(vehicle_from(eight, **{f"actuators__t{i}__thrust_rate_max": 50.0 for i in range(5, 9)}),
                      dt=0.1)                                                 # verticals: 5 N per sample
    first = alloc.allocate([0.0, 0.0, 400.0, 0.0, 0.0, 0.0])
    assert first.at_rate_limit.tolist() == [False] * 4 + [True] * 4 and not first.at_thrust_limit.any()
    for _ in range(8):
        result = alloc.allocate([0.0, 0.0, 400.0, 0.0, 0.0, 0.0])
    assert result.thrust[4:] == pytest.approx(40.0)
    assert result.at_thrust_limit.tolist() == [False] * 4 + [True] * 4 and not result.at_rate_limit.any()
    alloc.set_fault("t5", FaultMode.DEGRADED, efficiency=0.5)      # 20 N now: the limit in force
    result = alloc.allocate([0.0, 0.0, 400.0, 0.0, 0.0, 0.0])
    assert result.thrust[4] == pytest.approx(20.0) and result.at_thrust_limit[4]
    reverse = Allocator(vehicle_from(eight)).allocate([0.0, 0.0, -400.0, 0.0, 0.0, 0.0])
    assert reverse.thrust[4:] == pytest.approx(-30.0) and reverse.at_thrust_limit[4:].all()


def test_a_turning_azimuth_is_flagged_at_its_rate_limit():
    alloc = Allocator(load_vehicle(EXAMPLE))
    turning = alloc.allocate([0.0, 200.0, 0.0, 0.0, 0.0, 0.0])     # the azimuths turn from 0 toward sway
    step = [a.rotation.rate_max * alloc.dt for a in alloc.vehicle.actuators[:2]]
    assert np.abs(turning.azimuth[:2]) == pytest.approx(step)
    assert turning.at_rate_limit[:2].all()


@pytest.mark.parametrize("kind", ["linear", "quadratic"])
def test_a_dead_band_force_is_zero_or_the_edge_whichever_is_nearer(kind):
    """Eight thrusters, the four verticals sharing heave: each gets a quarter of it."""
    gain = {"linear": 1.0, "quadratic": 0.5}[kind]
    band = {"linear": 2.0, "quadratic": 2.0}[kind]
    edge = gain * band if kind == "linear" else gain * band * band               # 2 N either way
    overrides = {f"actuators__t{i}__{key}": value for i in range(1, 9)
                 for key, value in (("command_map", kind), ("gain", gain), ("command_deadband", band))}
    alloc = Allocator(vehicle_from(DATA / "eight_thrusters.yaml", **overrides))
    for heave, each in ((3.2, 0.0), (4.4, edge), (6.0, edge), (8.0, edge), (12.0, 3.0)):
        result = alloc.allocate([0.0, 0.0, heave, 0.0, 0.0, 0.0])
        assert result.thrust[4:] == pytest.approx(each, abs=1e-4)      # the solver's tolerance
        assert result.achieved[2] == pytest.approx(4 * result.thrust[4:].mean(), abs=1e-9)   # what is commanded
        assert result.saturated == (abs(4 * each - heave) > 1e-3 * 160.0)
        command = result.command[4:]
        assert np.all((command == 0.0) | (np.abs(command) >= band - 1e-9))
    small = alloc.allocate([0.0, 0.0, -3.2, 0.0, 0.0, 0.0])
    assert small.thrust[4:] == pytest.approx(0.0) and small.command[4:] == pytest.approx(0.0)


def test_a_reversed_thruster_gets_the_same_force_with_its_command_flipped():
    eight = DATA / "eight_thrusters.yaml"
    plain = Allocator(vehicle_from(eight)).allocate([20.0, 5.0, 30.0, 1.0, 0.0, 2.0])
    flipped = Allocator(vehicle_from(eight, actuators__t1__reversed=True,
                                     actuators__t6__reversed=True)).allocate([20.0, 5.0, 30.0, 1.0, 0.0, 2.0])
    assert flipped.thrust == pytest.approx(plain.thrust)
    assert flipped.command[[0, 5]] == pytest.approx(-plain.command[[0, 5]])
    assert flipped.command[[1, 2, 3, 4, 6, 7]] == pytest.approx(plain.command[[1, 2, 3, 4, 6, 7]])
    table = Allocator(vehicle_from(BLUEROV, actuators__thruster_1__reversed=True))
    forward = table.allocate([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    reference = Allocator(load_vehicle(BLUEROV)).allocate([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert forward.command[0] == pytest.approx(3000.0 - reference.command[0])     # mirrored about 1500 us
