"""The method registry and interface: every name the rest of the package offers comes from
``METHODS`` (the schema's from ``METHOD_NAMES``, the same names), every registered method
implements the interface, and a new method registered there is taken everywhere."""

from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT, vehicle_from

from allocator_pkg import (
    METHODS,
    Allocator,
    ConfigError,
    load_vehicle,
    read_parameters,
    vehicle_from_parameters,
)
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.configuration import schema
from allocator_pkg.methods.base import AllocationMethod, MethodOutput
from allocator_pkg.methods.pseudoinverse import PseudoInverseAllocation

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


def test_the_schema_offers_exactly_the_registered_methods():
    assert schema.VEHICLE_KEY_BY_NAME["method"].choices == tuple(METHODS)
    assert set(METHODS) == {"qp", "pseudoinverse", "nonlinear", "lp", "dynamic", "svd_filter", "explicit"}


@pytest.mark.parametrize("name", list(METHODS))
def test_every_registered_method_implements_the_interface(name):
    method = METHODS[name]
    assert issubclass(method, AllocationMethod) and method.name == name
    vehicle = load_vehicle(EXAMPLE)
    if method.problems(vehicle):                      # explicit: actuators of fixed direction only
        vehicle = load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml")
    allocator = Allocator(vehicle, method=name)
    assert allocator.method == name
    assert METHODS[name].problems(vehicle) == []
    sides = method.thrust_region_sides(vehicle)
    assert sides is None or sides >= vehicle.azimuth_polygon_sides


class HalfPseudoInverse(PseudoInverseAllocation):
    """A method that gives half of the pseudo-inverse's forces: enough to see it taken."""

    name = "half"

    def solve(self, tau, limits) -> MethodOutput:
        output = super().solve(tau, limits)
        output.force = 0.5 * output.force
        return output

    @classmethod
    def problems(cls, vehicle):
        return [] if len(vehicle.actuators) == 4 else ["works on four actuators only"]


@pytest.fixture
def registered(monkeypatch):
    """HalfPseudoInverse added to the registry, as its one line in methods/__init__.py and its
    name in METHOD_NAMES would (the schema reads the names when it is imported, so its key is
    rebuilt here)."""
    monkeypatch.setitem(METHODS, HalfPseudoInverse.name, HalfPseudoInverse)
    key = replace(schema.VEHICLE_KEY_BY_NAME["method"], choices=tuple(METHODS))
    monkeypatch.setitem(schema.VEHICLE_KEY_BY_NAME, "method", key)
    monkeypatch.setattr(schema, "VEHICLE_KEYS", tuple(key if k.name == "method" else k for k in schema.VEHICLE_KEYS))


def test_a_registered_method_is_taken_by_the_allocator_the_parser_and_the_capability(registered):
    parameters = read_parameters(EXAMPLE)
    parameters["method"] = "half"
    vehicle = vehicle_from_parameters(parameters)
    half = Allocator(vehicle)
    full = Allocator(vehicle, method="pseudoinverse")
    tau = [20.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    for _ in range(20):
        a, b = half.allocate(tau), full.allocate(tau)
    assert half.method == "half"
    assert np.sum(a.thrust) == pytest.approx(0.5 * np.sum(b.thrust), rel=1e-6)
    assert Capability(vehicle).sides is None


def test_a_method_that_cannot_serve_a_vehicle_is_refused_with_its_reason(registered):
    parameters = read_parameters(ROOT / "config" / "otter_usv.yaml")
    parameters["method"] = "half"
    with pytest.raises(ConfigError, match="method: 'half' cannot serve this vehicle: works on four actuators only"):
        Allocator(vehicle_from_parameters(parameters))


def test_an_unknown_method_is_refused_everywhere():
    with pytest.raises(ValueError, match=f"unknown method 'magic'; choose from {', '.join(METHODS)}"):
        Allocator(load_vehicle(EXAMPLE), method="magic")
    with pytest.raises(ValueError, match="unknown method 'magic'"):
        Capability(load_vehicle(EXAMPLE), method="magic")
    with pytest.raises(ConfigError, match=f"'magic' is not one of {', '.join(METHODS)}"):
        vehicle_from(EXAMPLE, method="magic")


def test_svd_filter_is_refused_for_a_vehicle_without_rotatable_thrusters():
    parameters = read_parameters(ROOT / "config" / "bluerov2_heavy.yaml")
    parameters["method"] = "svd_filter"
    with pytest.raises(ConfigError, match="method: 'svd_filter' cannot serve this vehicle: it steers rotatable "
                                          "thrusters and this vehicle has none"):
        Allocator(vehicle_from_parameters(parameters))
    with pytest.raises(ValueError, match="'svd_filter' cannot serve this vehicle"):
        Allocator(load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml"), method="svd_filter")


@pytest.mark.parametrize("name", [name for name in METHODS if "direct" not in METHODS[name].saturation_modes])
def test_a_saturation_mode_a_method_does_not_implement_is_refused_with_its_reason(name):
    parameters = read_parameters(EXAMPLE)
    parameters.update(method=name, saturation="direct")
    with pytest.raises(ConfigError, match=f"'{name}' cannot serve this vehicle: it does not implement saturation "
                                          "'direct'"):
        Allocator(vehicle_from_parameters(parameters))


@pytest.mark.parametrize("name", [name for name in METHODS if "direct" in METHODS[name].saturation_modes])
def test_saturation_direct_is_taken_by_the_methods_that_implement_it(name):
    vehicle = vehicle_from(EXAMPLE, method=name, saturation="direct")
    assert Allocator(vehicle).method == name
    assert set(METHODS) - {n for n in METHODS if "direct" in METHODS[n].saturation_modes} == \
        {"nonlinear", "dynamic", "svd_filter", "explicit"}


@pytest.mark.parametrize("name", list(METHODS))
def test_a_method_implements_priorities_or_is_refused_with_them(name):
    """Safe by default: a method that does not declare priorities never runs with them."""
    # the Otter (surge, yaw), or for a method that steers rotatable thrusters the DP vessel (surge, sway, yaw)
    path, levels = ((ROOT / "config" / "otter_usv.yaml", [1, 0]) if not METHODS[name].problems(
        replace(load_vehicle(ROOT / "config" / "otter_usv.yaml"), method=name))
        else (ROOT / "config" / "dp_vessel.yaml", [1, 1, 0]))
    parameters = read_parameters(path)
    parameters.update(method=name, priorities=levels)
    if METHODS[name].implements_priorities:
        vehicle = vehicle_from_parameters(parameters)
        assert len(vehicle.priority_levels) == 2
        Allocator(vehicle).allocate([500.0, 0.0, 0.0, 0.0, 0.0, 300.0])
        return
    with pytest.raises(ConfigError, match=f"priorities: method '{name}' does not implement DOF priorities"):
        Allocator(vehicle_from_parameters(parameters))
    prioritised = vehicle_from(path, priorities=levels)
    with pytest.raises(ValueError, match=f"method '{name}' does not implement DOF priorities"):
        Allocator(prioritised, method=name)
    overridden = Allocator(load_vehicle(path), method=name)
    with pytest.raises(ValueError, match="does not implement DOF priorities"):
        overridden.reconfigure(prioritised)


def test_a_new_method_does_not_implement_priorities_unless_it_says_so():
    assert HalfPseudoInverse.implements_priorities is False
    assert {name for name, kind in METHODS.items() if kind.implements_priorities} == {"qp", "pseudoinverse"}
