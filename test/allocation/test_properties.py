"""Properties over generated vehicles, requests and faults, for every method.

Vehicles of 1-12 actuators of every type, with random positions, directions, limits, rates,
feasible and forbidden sectors; requests from zero to 1e9; random fault sets. Whatever the
input: outputs are finite and inside every (fault-adjusted) limit, rate limits hold, achieved
is what the commanded thrusts and angles give, an unsaturated result meets the request, and
the same inputs give the same outputs. A vehicle a method refuses (a saturation mode it does
not implement, no rotatable thruster for svd_filter) is not drawn for it; nor one the loader
refuses. The strategies are in generators.py.
"""

import numpy as np
import pytest
from generators import FIXED_DIRECTIONS, TYPES, faults, requests, vehicles
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from allocator_pkg import METHODS, Allocator, FaultMode
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix
from allocator_pkg.effectiveness.model import Model
from allocator_pkg.effectiveness.sectors import in_feasible_sector, in_forbidden_sector
from allocator_pkg.vehicle.angles import wrap


def run(vehicle, method, fault_set, sequence, speed):
    alloc = Allocator(vehicle, method=method)
    alloc.set_speed(speed)
    for name, (mode, efficiency, angle) in fault_set.items():
        alloc.set_fault(name, mode, efficiency=efficiency, angle=angle)
    previous = alloc.stop()
    results = []
    for tau in sequence:
        result = alloc.allocate(tau)
        check(vehicle, alloc, fault_set, previous, result, np.array(tau))
        previous = result
        results.append(result)
    return results


def check(vehicle, alloc, fault_set, previous, result, tau):
    dt = alloc.dt
    assert np.all(np.isfinite(result.thrust)) and np.all(np.isfinite(result.azimuth))
    assert np.all(np.isfinite(result.command)) and np.all(np.isfinite(result.achieved))
    for i, a in enumerate(vehicle.actuators):
        mode, efficiency, angle = fault_set.get(a.name, (FaultMode.NOMINAL, 1.0, 0.0))
        thrust = result.thrust[i]
        if a.is_surface:
            assert abs(result.command[i]) <= a.surface.deflection_max * (1 + 1e-9)
            continue
        scale = 0.0 if mode == FaultMode.FAILED else (efficiency if mode == FaultMode.DEGRADED else 1.0)
        slack = 1e-9 * max(1.0, a.thrust_max)
        assert a.thrust_min * scale - slack <= thrust <= a.thrust_max * scale + slack
        if a.thrust_rate_max > 0:
            assert abs(thrust - previous.thrust[i]) <= a.thrust_rate_max * dt * (1 + 1e-9) + slack
        if a.rotatable:
            rotation = a.rotation
            assert in_feasible_sector(rotation, result.azimuth[i])
            if abs(thrust) > slack:
                assert not in_forbidden_sector(rotation, result.azimuth[i])
            if mode == FaultMode.STUCK:
                assert abs(wrap(result.azimuth[i] - angle)) < 1e-9
            elif rotation.rate_max > 0:
                assert abs(wrap(result.azimuth[i] - previous.azimuth[i])) <= rotation.rate_max * dt + 1e-9
    achieved = configuration_matrix(vehicle.actuators, result.azimuth) @ result.thrust
    achieved[0] -= result.drag
    assert result.achieved == pytest.approx(achieved, rel=1e-9, abs=1e-9 * max(1.0, np.max(np.abs(achieved))))
    if not result.saturated:
        rows = list(vehicle.dof_indices)
        tolerance = Model.build(vehicle, dt).dof_tolerance
        assert np.all(np.abs(result.achieved[rows] - tau[rows]) <= tolerance * (1 + 1e-9))


@pytest.mark.slow
@pytest.mark.parametrize("method", list(METHODS))
@settings(deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                                HealthCheck.filter_too_much])
@given(data=st.data())
def test_outputs_respect_every_limit_and_are_deterministic(method, data):
    vehicle = data.draw(vehicles())
    if METHODS[method].problems(vehicle):      # a vehicle of the actuators and saturation the method takes
        vehicle = data.draw(vehicles(FIXED_DIRECTIONS if method == "explicit" else TYPES,
                                     METHODS[method].saturation_modes))
    assume(not METHODS[method].problems(vehicle))           # the allocator refuses it, with its reason
    fault_set = data.draw(faults(vehicle))
    sequence = data.draw(requests)
    speed = data.draw(st.floats(min_value=0.0, max_value=5.0))
    first = run(vehicle, method, fault_set, sequence, speed)
    again = run(vehicle, method, fault_set, sequence, speed)
    for a, b in zip(first, again):
        assert np.array_equal(a.thrust, b.thrust) and np.array_equal(a.azimuth, b.azimuth)
        assert np.array_equal(a.command, b.command) and a.saturated == b.saturated
