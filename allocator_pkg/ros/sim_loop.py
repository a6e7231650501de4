"""The node in the loop of ``allocator-sim``: the real ``allocator_node`` as a child process,
unchanged, with ``use_sim_time`` and ``trigger: input``, behind the ROS link of ``sim_link``,
for the closed loop of :mod:`allocator_pkg.simulation.closed_loop`."""

from __future__ import annotations

import contextlib
import json
from collections.abc import Iterator
from pathlib import Path

from ..simulation.scenario import Scenario
from .process import child_process, node_command
from .sim_link import NodeLink


def scenario_command(scenario: Scenario, log_level: str = "warn") -> list[str]:
    """``allocator_node`` on the scenario's vehicle, on sim time, allocating each wrench on
    arrival with the scenario's method and parameters."""
    parameters = ["use_sim_time:=true", "trigger:=input", f"method:={scenario.method}"]
    parameters += [f"{name}:={json.dumps(value) if not isinstance(value, str) else value}"
                   for name, value in scenario.parameters.items()]
    return node_command(scenario.vehicle, "--log-level", log_level, parameters=parameters)


@contextlib.contextmanager
def node_link(scenario: Scenario, out: Path) -> Iterator[NodeLink]:
    """The node of ``scenario`` started (its output into ``out/node.log``, its recording into
    ``out/run.mcap``) and subscribed; stopped when the context ends."""
    node_log = out / "node.log"
    with child_process(scenario_command(scenario), output=node_log, dies_with_parent=True) as process, \
            contextlib.closing(NodeLink(out, node_log)) as link:
        link.wait_for_node(lambda: process.poll() is None)
        yield link
