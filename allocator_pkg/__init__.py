"""Thrust allocation for marine and underwater vehicles.

The core is plain Python (numpy, OSQP, DAQP, HiGHS, PyYAML); ROS lives in ``allocator_pkg.ros``
and the command-line tools in ``allocator_pkg.cli``::

    from allocator_pkg import load_vehicle, Allocator, FaultMode
    alloc = Allocator(load_vehicle("config/example1_rov.yaml"))
    result = alloc.allocate([X, Y, Z, K, M, N])

The names that live above the configuration (the allocator, its results, the methods) are
imported when first used, so that reading a configuration loads no solver.
"""

from importlib import import_module
from typing import Any

from .configuration.parameters import load_vehicle, parse_parameters, vehicle_from_parameters
from .configuration.params_file import read_parameters
from .effectiveness.faults import Fault, FaultMode, FaultSet
from .vehicle.config import ConfigError, Vehicle

_ON_FIRST_USE = {
    "Allocator": "allocation.allocator",
    "AllocationResult": "allocation.result",
    "AllocatorStats": "allocation.result",
    "METHODS": "methods",
    "Outcome": "solvers.outcome",
}
"""The names imported when first used, each with its module."""

__all__ = [
    "METHODS",
    "AllocationResult",
    "Allocator",
    "AllocatorStats",
    "ConfigError",
    "Fault",
    "FaultMode",
    "FaultSet",
    "Outcome",
    "Vehicle",
    "load_vehicle",
    "parse_parameters",
    "read_parameters",
    "vehicle_from_parameters",
]


def __getattr__(name: str) -> Any:
    if name not in _ON_FIRST_USE:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(import_module(f".{_ON_FIRST_USE[name]}", __name__), name)
    globals()[name] = value
    return value
