"""The node in the loop of ``allocator-sim``: the real ``allocator_node`` as a child process,
unchanged, with ``use_sim_time`` and ``trigger: input``, behind the ROS link of ``sim_link``,
for the closed loop of :mod:`allocator_pkg.simulation.closed_loop`. Each run's node and link are
in a namespace of the run's own (:func:`~allocator_pkg.ros.process.run_namespace`)."""

from __future__ import annotations

import contextlib
import json
from collections.abc import Iterator
from pathlib import Path

from ..configuration.parameters import load_vehicle
from ..simulation.scenario import Scenario
from .process import child_process, namespace_arguments, node_command, run_namespace
from .sim_link import NodeLink


def scenario_command(scenario: Scenario, namespace: str, log_level: str = "warn") -> list[str]:
    """``allocator_node`` on the scenario's vehicle in ``namespace``, on sim time, allocating each
    wrench on arrival with the scenario's method and parameters."""
    parameters = ["use_sim_time:=true", "trigger:=input", f"method:={scenario.method}"]
    parameters += [f"{name}:={json.dumps(value) if not isinstance(value, str) else value}"
                   for name, value in scenario.parameters.items()]
    return node_command(scenario.vehicle, *namespace_arguments(namespace), "--log-level", log_level,
                        parameters=parameters)


@contextlib.contextmanager
def node_link(scenario: Scenario, out: Path) -> Iterator[NodeLink]:
    """The node of ``scenario`` started in a namespace of this run's own (its output into
    ``out/node.log``, its recording into ``out/run.mcap``) and subscribed; stopped when the
    context ends."""
    node_log = out / "node.log"
    namespace = run_namespace()
    actuators = [actuator.name for actuator in load_vehicle(scenario.vehicle).actuators]
    with child_process(scenario_command(scenario, namespace), output=node_log, dies_with_parent=True) as process, \
            contextlib.closing(NodeLink(out, node_log, namespace, actuators)) as link:
        link.wait_for_node(lambda: process.poll() is None)
        yield link
