"""Thrust allocation for marine and underwater vehicles.

The core is plain Python (numpy, OSQP, HiGHS, PyYAML); ROS lives only in ``allocator_pkg.node``
and the command-line tools::

    from allocator_pkg import load_vehicle, Allocator, FaultMode
    alloc = Allocator(load_vehicle("config/example1_rov.yaml"))
    result = alloc.allocate([X, Y, Z, K, M, N])
"""

from .allocator import AllocationResult, Allocator, AllocatorStats
from .faults import Fault, FaultMode, FaultSet
from .methods import METHODS
from .parameters import load_vehicle, parse_parameters, read_parameters, vehicle_from_parameters
from .vehicle import ConfigError, Vehicle

__all__ = [
    "METHODS",
    "AllocationResult",
    "Allocator",
    "AllocatorStats",
    "ConfigError",
    "Fault",
    "FaultMode",
    "FaultSet",
    "Vehicle",
    "load_vehicle",
    "parse_parameters",
    "read_parameters",
    "vehicle_from_parameters",
]
