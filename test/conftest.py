"""Shared fixtures. The node tests run on the package's own pytest plugin
(:mod:`allocator_pkg.testing.plugin`, installed with the package): its ``allocator_harness``
keeps DDS on this machine, on loopback and in a domain of its own unless the caller chose them.
Every test that starts a node puts it in a namespace of the test's own (``namespace``, which
``ros_context`` shares), so that any number of runs of the suite (pytest-xdist's workers, other
developers' runs) share a machine and a domain."""

import os

from allocator_pkg.ros.process import dds_environment, namespace_arguments, run_namespace

# DDS discovery stays on loopback (ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST), in the suite's own
# domain (ROS_DOMAIN_ID=42), unless the caller set them, as the Makefile does, before anything here
# or in the plugin loads rclpy.
os.environ.update(dds_environment())

import importlib
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from hypothesis import settings

from allocator_pkg import Vehicle, read_parameters, vehicle_from_parameters
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix

# Property tests: `make test` runs the same examples every time (a red CI means a change broke
# something); HYPOTHESIS_PROFILE=explore draws many fresh ones to look for new failures.
settings.register_profile("ci", derandomize=True, max_examples=60)
settings.register_profile("explore", max_examples=1000)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

ROOT = Path(__file__).resolve().parents[1]
SUITE = Path(__file__).resolve().parent
for _folder in sorted(path for path in SUITE.rglob("*") if path.is_dir() and path.name not in {"data", "__pycache__"}):
    if str(_folder) not in sys.path:
        sys.path.append(str(_folder))
"""The suite's folders mirror the package; pytest imports each test module by its name (no
``__init__.py``), so with every folder on the path a test module imports another's helpers by
name from any folder (their names are unique: ``test_imports``)."""
DATA = Path(__file__).resolve().parent / "data"
BENCH = ROOT / "bench"
ALARM_TOLERANCE = 2 * 1.0 + 3 * 0.1
"""[s] How far apart two closed-loop runs' consequence alarm times may be when the node is in
the loop: two analysis periods (consequence.rate 1 Hz, the DP vessel's: the node's timer has a
phase of its own on the sim clock, and an analysis that takes longer in wall time than the sim
clock gives it, at the run's real-time factor, answers at the next period) and three samples for
the node's thread to answer."""
ALARM_METRICS = ("consequence_alarm_time", "alarm_lead_time", "alarm_after_position_loss")
"""The metrics of the consequence alarm's time: the node analyses asynchronously, so these may
differ between the node and the in-process link by up to one analysis period."""


def bench_module(name: str) -> ModuleType:
    """The module ``bench/<name>.py``, for the tests of the benchmarks' own logic and those that
    share the settling sweep's optimum. The bench scripts import each other by name, as they
    find each other when one runs as a script, so ``bench/`` goes on the path; nothing in
    ``bench/`` imports from ``test/``."""
    if str(BENCH) not in sys.path:
        sys.path.insert(0, str(BENCH))
    return importlib.import_module(name)


def matrices(vehicle: Vehicle) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """T (controlled rows, every angle zero), the actuator weights and the configured thrust
    ranges of a vehicle of fixed directions, from the configuration alone."""
    t = configuration_matrix(vehicle.actuators, [0.0] * len(vehicle.actuators))[list(vehicle.dof_indices)]
    w = np.array([a.weight for a in vehicle.actuators])
    low = np.array([a.thrust_min for a in vehicle.actuators])
    high = np.array([a.thrust_max for a in vehicle.actuators])
    return t, w, low, high


def vehicle_from(path, **overrides) -> Vehicle:
    """A vehicle from a params file with some parameters replaced (dots in names as '__')."""
    parameters = read_parameters(path)
    parameters.update({key.replace("__", "."): value for key, value in overrides.items()})
    return vehicle_from_parameters(parameters)


@pytest.fixture
def eight_thrusters():
    return DATA / "eight_thrusters.yaml"


@pytest.fixture
def namespace() -> str:
    """A namespace of this test's own (``/run_<pid>_<hex>``): give it to the nodes the test starts
    as ``node_command(path, *namespace_arguments(namespace))`` and to allocator-ctl as
    ``--namespace``."""
    return run_namespace()


@pytest.fixture
def ros_context(namespace):
    """A fresh rclpy context per test, its nodes in the test's ``namespace`` (``/clock`` and
    ``/diagnostics`` too), shut down afterwards."""
    import rclpy
    context = rclpy.Context()
    rclpy.init(context=context, args=["--ros-args", *namespace_arguments(namespace)])
    yield context
    rclpy.try_shutdown(context=context)


@pytest.fixture
def harness(allocator_harness, request):
    """Harness on the params file a test names with @pytest.mark.params(path, **overrides)
    (dots in names as '__')."""
    marker = request.node.get_closest_marker("params")
    path = marker.args[0] if marker else ROOT / "config" / "example1_rov.yaml"
    values = marker.kwargs if marker else {}
    return allocator_harness(path, {name.replace("__", "."): value for name, value in values.items()})
