"""The pytest plugin of allocator_pkg: the fixture ``allocator_harness``.

``allocator_harness(params_file, parameters={...}, node="plain" | "lifecycle")`` returns a
:class:`~allocator_pkg.testing.harness.Harness` running the allocator node of that params file
and a probe in one in-process executor on simulated time; every harness a test made, its
executor and its rclpy context are torn down after the test. A relative ``params_file`` is
looked for next to the calling test file, then in the current directory.

Each harness runs in a namespace of its own (:func:`~allocator_pkg.ros.process.run_namespace`,
``/clock`` and ``/diagnostics`` inside it), so that any number of test runs (pytest-xdist's
workers, another developer's suite) share a machine and a domain.

DDS stays on this machine: unless the caller set them, ``ROS_AUTOMATIC_DISCOVERY_RANGE`` is
``LOCALHOST`` and ``ROS_DOMAIN_ID`` a domain of this pytest process's own (1 to 100, from its
process id), set when pytest starts, before any test creates a participant. rclpy is imported
only when the fixture is first used.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any, Protocol

import pytest

DOMAINS = 100
"""Domains 1 to 100: inside the range every DDS implementation maps to ports on Linux, and never 0,
the default of the ROS 2 processes a developer has running."""


def own_domain(pid: int) -> str:
    """A ROS_DOMAIN_ID for the process ``pid``."""
    return str(1 + pid % DOMAINS)


def pytest_configure(config: pytest.Config) -> None:
    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    os.environ.setdefault("ROS_DOMAIN_ID", own_domain(os.getpid()))


class HarnessFactory(Protocol):
    def __call__(self, params_file: str | Path, parameters: Mapping[str, Any] | None = None,
                 node: str = "plain", timeout: float = 10.0): ...


def params_path(params_file: str | Path, caller: Path) -> Path:
    """The params file a test names: as given when absolute, else next to the test file in
    ``caller`` (a directory), else in the current directory. FileNotFoundError naming every
    place looked at."""
    path = Path(params_file).expanduser()
    places = [path] if path.is_absolute() else list(dict.fromkeys([caller / path, Path.cwd() / path]))
    for place in places:
        if place.is_file():
            return place.resolve()
    raise FileNotFoundError(f"no such params file: {params_file} (looked for {' and '.join(map(str, places))})")


@pytest.fixture
def allocator_harness(request: pytest.FixtureRequest) -> Iterator[HarnessFactory]:
    """A factory of harnesses: ``allocator_harness(params_file, parameters={...},
    node="plain" | "lifecycle")``. Each harness has a context of its own, shut down with it
    after the test."""
    import rclpy

    from ..ros.process import namespace_arguments, run_namespace
    from .harness import Harness
    made: list[tuple[Harness | None, rclpy.Context]] = []

    def make(params_file: str | Path, parameters: Mapping[str, Any] | None = None, node: str = "plain",
             timeout: float = 10.0) -> Harness:
        path = params_path(params_file, request.path.parent)
        context = rclpy.Context()
        rclpy.init(context=context, args=["--ros-args", *namespace_arguments(run_namespace())])
        made.append((None, context))
        harness = Harness(context, path, parameters, node, timeout)
        made[-1] = (harness, context)
        return harness

    yield make
    for harness, context in reversed(made):
        try:
            if harness is not None:
                harness.close()
        finally:
            rclpy.try_shutdown(context=context)
