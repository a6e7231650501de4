"""Thrust allocation for marine and underwater vehicles.

The core is plain Python (numpy, OSQP, PyYAML); ROS lives only in ``allocator_pkg.node``
and the command-line tools::

    from allocator_pkg import load_vehicle, Allocator, FaultMode
    alloc = Allocator(load_vehicle("config/example1_rov.yaml"))
    result = alloc.allocate([X, Y, Z, K, M, N])
"""

from .allocator import AllocationResult, Allocator, AllocatorStats
from .faults import Fault, FaultMode
from .vehicle import ConfigError, Vehicle, load_vehicle

__all__ = [
    "AllocationResult",
    "Allocator",
    "AllocatorStats",
    "ConfigError",
    "Fault",
    "FaultMode",
    "Vehicle",
    "load_vehicle",
]
