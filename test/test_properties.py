"""Properties over generated vehicles, requests and faults, for every method.

Vehicles of 1-12 actuators of every type, with random positions, directions, limits, rates,
feasible and forbidden sectors; requests from zero to 1e9; random fault sets. Whatever the
input: outputs are finite and inside every (fault-adjusted) limit, rate limits hold, achieved
is what the commanded thrusts and angles give, an unsaturated result meets the request, and
the same inputs give the same outputs. A vehicle a method refuses (a saturation mode it does
not implement, no rotatable thruster for svd_filter) is not drawn for it.
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from allocator_pkg import METHODS, Allocator, FaultMode, Vehicle, vehicle_from_parameters
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix
from allocator_pkg.effectiveness.model import Model
from allocator_pkg.effectiveness.sectors import in_feasible_sector, in_forbidden_sector
from allocator_pkg.vehicle.angles import wrap
from allocator_pkg.vehicle.config import DOF_NAMES, SATURATION_MODES

TYPES = ("fixed", "azimuth", "azimuth_vertical", "rudder", "fin")
FIXED_DIRECTIONS = ("fixed", "rudder", "fin")
finite = st.floats(min_value=-3.0, max_value=3.0, allow_nan=False)
unit_vector = st.tuples(finite, finite, finite).filter(lambda v: math.hypot(*v) > 0.1)


@st.composite
def actuator(draw, name: str, types: tuple[str, ...] = TYPES) -> dict:
    kind = draw(st.sampled_from(types))
    keys = {"type": kind, "position": list(draw(st.tuples(finite, finite, finite)))}
    if kind in ("fixed", "azimuth", "azimuth_vertical"):
        keys["thrust_max"] = draw(st.floats(min_value=1.0, max_value=1e4))
        if draw(st.booleans()):
            keys["thrust_rate_max"] = draw(st.floats(min_value=0.5, max_value=1e5))
        keys["command_map"] = draw(st.sampled_from(("linear", "quadratic")))
    if kind in ("fixed", "rudder", "fin"):
        keys["direction"] = list(draw(unit_vector))
    if kind == "fixed":
        keys["thrust_min"] = -draw(st.floats(min_value=0.0, max_value=1.0)) * keys["thrust_max"]
    if kind in ("azimuth", "azimuth_vertical"):
        if draw(st.booleans()):
            keys["azimuth_rate_max"] = draw(st.floats(min_value=0.05, max_value=10.0))
        if draw(st.booleans()):
            low = draw(st.floats(min_value=-3.0, max_value=0.0))
            keys["azimuth_min"], keys["azimuth_max"] = low, low + draw(st.floats(min_value=0.5, max_value=3.0))
            keys["azimuth_initial"] = keys["azimuth_min"]
        elif draw(st.booleans()):
            start = draw(st.floats(min_value=0.5, max_value=2.5))
            keys["forbidden_sectors"] = [start, start + draw(st.floats(min_value=0.1, max_value=1.0))]
        if draw(st.booleans()):
            keys["reversible"] = True
            keys["thrust_min"] = -draw(st.floats(min_value=0.0, max_value=1.0)) * keys["thrust_max"]
    if kind in ("rudder", "fin"):
        keys.update(area=draw(st.floats(min_value=0.01, max_value=1.0)),
                    lift_coefficient=draw(st.floats(min_value=0.5, max_value=5.0)),
                    drag_coefficient=draw(st.floats(min_value=0.0, max_value=2.0)),
                    deflection_max=draw(st.floats(min_value=0.1, max_value=0.6)))
        if draw(st.booleans()):
            keys["deflection_rate_max"] = draw(st.floats(min_value=0.1, max_value=5.0))
    return {f"actuators.{name}.{key}": value for key, value in keys.items()}


@st.composite
def vehicles(draw, types: tuple[str, ...] = TYPES, saturation: tuple[str, ...] = SATURATION_MODES) -> Vehicle:
    count = draw(st.integers(min_value=1, max_value=12))
    names = [f"a{i}" for i in range(count)]
    parameters = {"actuators.names": names, "rate_hz": draw(st.sampled_from([10.0, 50.0, 200.0])),
                  "dofs": draw(st.lists(st.sampled_from(DOF_NAMES), min_size=1, max_size=6, unique=True)),
                  "saturation": draw(st.sampled_from(saturation)),
                  "weights.minimax": draw(st.sampled_from([0.0, 0.0, 10.0]))}
    for name in names:
        parameters.update(draw(actuator(name, types)))
    return vehicle_from_parameters(parameters)


@st.composite
def faults(draw, vehicle: Vehicle) -> dict:
    result = {}
    for a in vehicle.actuators:
        mode = draw(st.sampled_from([None, None, FaultMode.FAILED, FaultMode.DEGRADED, FaultMode.STUCK]))
        if mode == FaultMode.DEGRADED:
            result[a.name] = (mode, draw(st.floats(min_value=0.05, max_value=1.0)), 0.0)
        elif mode == FaultMode.STUCK and (a.rotatable or a.is_surface):
            if a.rotatable:
                low, high = (-math.pi, math.pi) if a.rotation.continuous else (a.rotation.azimuth_min,
                                                                               a.rotation.azimuth_max)
                angle = draw(st.floats(min_value=low, max_value=high))
            else:
                angle = draw(st.floats(min_value=-1.0, max_value=1.0)) * a.surface.deflection_max
            result[a.name] = (mode, 1.0, angle)
        elif mode == FaultMode.FAILED:
            result[a.name] = (mode, 0.0, 0.0)
    return result


requests = st.lists(st.tuples(*[st.one_of(st.just(0.0), st.floats(min_value=-1e3, max_value=1e3),
                                          st.floats(min_value=-1e9, max_value=1e9))] * 6),
                    min_size=1, max_size=4)


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


@pytest.mark.parametrize("method", list(METHODS))
@settings(deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                                HealthCheck.filter_too_much])
@given(data=st.data())
def test_outputs_respect_every_limit_and_are_deterministic(method, data):
    vehicle = data.draw(vehicles())
    if METHODS[method].problems(vehicle):      # a vehicle of the actuators and saturation the method takes
        vehicle = data.draw(vehicles(FIXED_DIRECTIONS if method == "explicit" else TYPES,
                                     METHODS[method].saturation_modes))
    assume(not METHODS[method].problems(vehicle))           # refused when parsed, with its reason
    fault_set = data.draw(faults(vehicle))
    sequence = data.draw(requests)
    speed = data.draw(st.floats(min_value=0.0, max_value=5.0))
    first = run(vehicle, method, fault_set, sequence, speed)
    again = run(vehicle, method, fault_set, sequence, speed)
    for a, b in zip(first, again):
        assert np.array_equal(a.thrust, b.thrust) and np.array_equal(a.azimuth, b.azimuth)
        assert np.array_equal(a.command, b.command) and a.saturated == b.saturated
