"""Every shipped vehicle loads, allocates a representative wrench within its limits and,
that wrench being attainable, exactly; the vehicle table lists them all."""

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg import Allocator, load_vehicle
from allocator_pkg.effectiveness.model import Model
from allocator_pkg.effectiveness.sectors import in_forbidden_sector
from allocator_pkg.vehicle.config import DOF_NAMES

CONFIGS = sorted((ROOT / "config").glob("*.yaml"))


def test_the_shipped_set():
    names = {path.stem for path in CONFIGS}
    assert {"default", "example1_rov", "bluerov2_heavy", "dp_vessel", "infante_auv", "otter_usv"} <= names


def test_default_is_a_copy_of_a_shipped_vehicle():
    default = load_vehicle(ROOT / "config" / "default.yaml")
    assert any(load_vehicle(path) == default for path in CONFIGS if path.stem != "default")


@pytest.mark.parametrize("path", CONFIGS, ids=[p.stem for p in CONFIGS])
def test_vehicle_allocates_a_representative_wrench(path):
    vehicle = load_vehicle(path)
    alloc = Allocator(vehicle)
    alloc.set_speed(2.0)
    model = Model.build(vehicle, alloc.dt)
    tau = np.zeros(6)
    for k, (dof, authority) in enumerate(zip(vehicle.dofs, model.authority)):
        tau[DOF_NAMES.index(dof)] = (0.1 if k % 2 == 0 else -0.1) * authority
    for _ in range(300):
        result = alloc.allocate(tau)
        assert np.all(np.isfinite(result.thrust)) and np.all(np.isfinite(result.command))
        for actuator, thrust, angle, command in zip(vehicle.actuators, result.thrust, result.azimuth,
                                                     result.command):
            if actuator.is_surface:
                assert abs(command) <= actuator.surface.deflection_max + 1e-12     # the deflection [rad]
            else:
                assert actuator.thrust_min - 1e-9 <= thrust <= actuator.thrust_max + 1e-9
            if actuator.rotatable and abs(thrust) > 0.0:
                assert not in_forbidden_sector(actuator.rotation, angle)
    assert not result.saturated, f"{path.stem}: {result.achieved} for {tau}"
    rows = list(vehicle.dof_indices)
    assert result.achieved[rows] == pytest.approx(tau[rows], rel=1e-3, abs=1e-3 * np.max(np.abs(tau)))


@pytest.mark.parametrize("path", CONFIGS, ids=[p.stem for p in CONFIGS])
def test_an_under_actuated_vehicle_says_so(path):
    """The Otter's two propellers, both along x, give surge and yaw but never sway; every
    other shipped vehicle can push independently in surge, sway and yaw."""
    notes = Allocator(load_vehicle(path)).notes
    if path.stem == "otter_usv":
        assert notes == ["under-actuated: the actuators give 2 independent directions in surge, sway, yaw; "
                         "sway is left to the vehicle's dynamics"]
    else:
        assert notes == []


def test_vehicle_table_lists_every_vehicle():
    table = (ROOT / "docs" / "vehicles.md").read_text()
    for path in CONFIGS:
        if path.stem != "default":
            assert f"`config/{path.name}`" in table
