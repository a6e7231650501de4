"""Thrust allocation for marine and underwater vehicles.

The core is plain Python (numpy, OSQP, DAQP, HiGHS, PyYAML); ROS lives in ``allocator_pkg.ros``
and the command-line tools in ``allocator_pkg.cli``::

    from allocator_pkg import load_vehicle, Allocator, FaultMode
    alloc = Allocator(load_vehicle("config/example1_rov.yaml"))
    result = alloc.allocate([X, Y, Z, K, M, N])
"""

from .allocation.allocator import Allocator
from .allocation.result import AllocationResult, AllocatorStats
from .configuration.parameters import load_vehicle, parse_parameters, read_parameters, vehicle_from_parameters
from .effectiveness.faults import Fault, FaultMode, FaultSet
from .methods import METHODS
from .solvers.outcome import Outcome
from .vehicle.config import ConfigError, Vehicle

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
