"""Every single and double failure on every shipped vehicle: inside the degraded attainable
set a request is met; outside it the result says saturated and stays within every limit."""

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg import Allocator, FaultMode, load_vehicle
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.capability.fault_matrix import failure_sets, markdown
from allocator_pkg.vehicle.config import DOF_NAMES

CONFIGS = sorted(p for p in (ROOT / "config").glob("*.yaml") if p.stem != "default")
SPEED = 2.0


def test_faults_doc_is_up_to_date():
    assert (ROOT / "docs" / "faults.md").read_text() == markdown(CONFIGS), "run `make docs`"


def settle(alloc, tau, samples):
    for _ in range(samples):
        result = alloc.allocate(tau)
    return result


def within_limits(vehicle, result, failed):
    for actuator, thrust in zip(vehicle.actuators, result.thrust):
        if actuator.name in failed:
            assert thrust == 0.0
        elif not actuator.is_surface:
            assert actuator.thrust_min - 1e-9 <= thrust <= actuator.thrust_max + 1e-9
    assert np.all(np.isfinite(result.command))


@pytest.mark.parametrize("path", CONFIGS, ids=[p.stem for p in CONFIGS])
def test_requests_inside_and_outside_the_degraded_set(path):
    vehicle = load_vehicle(path)
    capability = Capability(vehicle, speed=SPEED)
    rng = np.random.default_rng(len(vehicle.actuators))
    limited = any(a.rotatable or a.thrust_rate_max > 0 or a.is_surface for a in vehicle.actuators)
    samples = 300 if limited else 5
    rows = list(vehicle.dof_indices)
    for failed in failure_sets(vehicle):
        direction = np.zeros(6)
        direction[rows] = rng.normal(size=len(rows)) * capability.model.authority
        faults = dict.fromkeys(failed, FaultMode.FAILED)
        scale = capability.scale(direction, faults)
        alloc = Allocator(vehicle)
        alloc.set_speed(SPEED)
        for name in failed:
            alloc.set_fault(name, FaultMode.FAILED)
        if scale > 1e-6:
            inside = 0.8 * scale * direction
            result = settle(alloc, inside, samples)
            within_limits(vehicle, result, failed)
            assert not result.saturated, f"{path.stem} without {failed}: {result.achieved} for {inside}"
            error = np.abs(result.achieved[rows] - inside[rows]) / capability.model.authority
            assert np.max(error) < 1e-3
        outside = (1.5 * scale if scale > 1e-6 else 1.0) * direction
        result = settle(alloc, outside, samples)
        within_limits(vehicle, result, failed)
        assert result.saturated, f"{path.stem} without {failed}: {outside} should be out of reach"


def test_lost_directions_of_a_known_case():
    # BlueROV2 Heavy without both front horizontal thrusters: the rear pair can still push
    # ahead and astern, but a sideways push or a yaw moment always brings the other along.
    vehicle = load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml")
    from allocator_pkg.capability.fault_matrix import lost_directions
    lost = lost_directions(Capability(vehicle), ("thruster_1", "thruster_2"))
    assert set(lost) == {"+sway", "-sway", "+yaw", "-yaw"}
    assert DOF_NAMES.index("sway") == 1
