"""The Allocator facade: public API, faults, commands, state and warnings."""

import math

import numpy as np
import pytest
from conftest import DATA, ROOT, vehicle_from

from allocator_pkg import Allocator, FaultMode, load_vehicle, vehicle_from_parameters
from allocator_pkg.actuators import command_map

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
    otter_like = vehicle_from(DATA / "eight_thrusters.yaml", dofs=["surge", "heave", "yaw"],
                              **{f"actuators__t{i}__direction": [1.0, 0.0, 0.0] for i in range(1, 9)})
    alloc = Allocator(otter_like)
    assert any("no actuator can produce heave" in w for w in alloc.warnings)
    assert alloc.uncontrolled == ("sway", "roll", "pitch")


def test_a_controlled_dof_out_of_reach_is_a_warning_not_an_under_actuation_note():
    along_x = {f"actuators__t{i}__direction": [1.0, 0.0, 0.0] for i in range(1, 9)}
    controls_sway = Allocator(vehicle_from(DATA / "eight_thrusters.yaml", dofs=["surge", "sway", "yaw"], **along_x))
    assert any("no actuator can produce sway" in w for w in controls_sway.warnings) and controls_sway.notes == []
    leaves_sway = Allocator(vehicle_from(DATA / "eight_thrusters.yaml", dofs=["surge", "yaw"], **along_x))
    assert leaves_sway.warnings == []
    assert leaves_sway.notes == ["under-actuated: the actuators give 2 independent directions in surge, sway, yaw; "
                                 "sway is left to the vehicle's dynamics"]


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


NARROW_TWIN = {"dofs": ["surge", "yaw"], "actuators.names": ["port", "stbd"],
               "actuators.port.type": "fixed", "actuators.port.position": [0.0, -0.1, 0.0],
               "actuators.port.direction": [1.0, 0.0, 0.0], "actuators.stbd.direction": [1.0, 0.0, 0.0],
               "actuators.port.thrust_min": -1e5, "actuators.port.thrust_max": 1e5,
               "actuators.stbd.type": "fixed", "actuators.stbd.position": [0.0, 0.1, 0.0],
               "actuators.stbd.thrust_min": -1e5, "actuators.stbd.thrust_max": 1e5}


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
