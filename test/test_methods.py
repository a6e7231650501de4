"""The method registry and interface: every name the rest of the package offers comes from
``METHODS``, every registered method implements the interface, and a new method registered
there is taken everywhere with no other change."""

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
    schema,
    vehicle_from_parameters,
)
from allocator_pkg.capability import Capability
from allocator_pkg.methods.base import AllocationMethod
from allocator_pkg.methods.pseudoinverse import PseudoInverseAllocation
from allocator_pkg.model import MethodOutput

EXAMPLE = ROOT / "config" / "example1_rov.yaml"


def test_the_schema_offers_exactly_the_registered_methods():
    assert schema.VEHICLE_KEY_BY_NAME["method"].choices == tuple(METHODS)
    assert set(METHODS) == {"qp", "pseudoinverse", "nonlinear", "explicit"}


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
    """HalfPseudoInverse added to the registry, as its one line in methods/__init__.py would
    (the schema reads the registry when it is imported, so its key is rebuilt here)."""
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
        vehicle_from_parameters(parameters)


def test_an_unknown_method_is_refused_everywhere():
    with pytest.raises(ValueError, match="unknown method 'magic'; choose from qp, pseudoinverse, nonlinear, explicit"):
        Allocator(load_vehicle(EXAMPLE), method="magic")
    with pytest.raises(ValueError, match="unknown method 'magic'"):
        Capability(load_vehicle(EXAMPLE), method="magic")
    with pytest.raises(ConfigError, match="'magic' is not one of qp, pseudoinverse, nonlinear, explicit"):
        vehicle_from(EXAMPLE, method="magic")
