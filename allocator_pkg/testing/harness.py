"""An allocator node and a probe node in one in-process executor, on simulated time: what a
test of a vehicle's configuration needs before its first assertion.

The probe publishes ``/clock``, so the node's timers fire only when the test steps the clock
(:meth:`Harness.step`, :meth:`Harness.tick`) and every timing is deterministic. The probe
sends wrenches and the available power and calls the node's services the way any client does
(``~/set_actuator_fault``, ``~/set_group_fault``, ``~/set_bus_tie``, ``~/clear_faults``, ``~/set_parameters``,
``~/get_capability``), and keeps every
``thruster_commands``, ``allocation_status`` and ``/diagnostics`` message it receives.

The probe takes only its own node's output: commands whose actuator names are not the
vehicle's, or a publisher on the node's topics that is not the node (name and namespace),
stop the harness with a ForeignNodeError naming that node. The plugin gives every harness a
namespace of its own, so that another run's node cannot answer.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import rclpy
from builtin_interfaces.msg import Time
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Wrench, WrenchStamped
from rcl_interfaces.srv import SetParameters, SetParametersAtomically
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.parameter import Parameter
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Trigger

from allocator_msgs.msg import ActuatorFault, AllocationStatus, PowerAvailable, ThrusterCommands
from allocator_msgs.srv import GetCapability, SetActuatorFault, SetBusTie, SetGroupFault

from ..effectiveness.faults import FaultMode
from ..ros.conversions import array_to_wrench, wrench_to_array
from ..ros.lifecycle_node import AllocatorLifecycleNode
from ..ros.node import AllocatorNode
from ..ros.process import UNKNOWN_NODE, node_of
from ..ros.wrench_input import message_type
from ..vehicle.node_settings import NODE_NAME

PLAIN = "plain"
LIFECYCLE = "lifecycle"
NODE_KINDS = {PLAIN: AllocatorNode, LIFECYCLE: AllocatorLifecycleNode}

START_NS = 1_000_000_000
"""The simulated time of the first /clock message [ns]."""


class ForeignNodeError(RuntimeError):
    """Another node than the harness's answers on its topics."""


class Harness:
    """The node of a params file (with ``parameters`` set over it) and a probe, in a context
    of their own. ``node`` is ``plain`` (``allocator_node``) or ``lifecycle``
    (``allocator_lifecycle_node``, configured and activated here). Construction returns once
    the first sample's commands and status have arrived. ``timeout`` [s, wall clock] bounds
    every wait (a TimeoutError then)."""

    def __init__(self, context: Context, params_file: str | Path, parameters: Mapping[str, Any] | None = None,
                 node: str = PLAIN, timeout: float = 10.0):
        if node not in NODE_KINDS:
            raise ValueError(f"node must be one of {', '.join(NODE_KINDS)}, not '{node}'")
        self.timeout = timeout
        self.time_ns = START_NS
        overrides = [Parameter("use_sim_time", value=True),
                     *(Parameter(name, value=value) for name, value in (parameters or {}).items())]
        self.node = NODE_KINDS[node](context=context, parameter_overrides=overrides,
                                     cli_args=["--ros-args", "--params-file", str(params_file)])
        self.probe = rclpy.create_node("allocator_probe", context=context)
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)
        self.executor.add_node(self.probe)
        self.commands: list[ThrusterCommands] = []
        self.status: list[AllocationStatus] = []
        self.diagnostics: list[DiagnosticArray] = []
        probe = self.probe
        self._commands = probe.create_subscription(ThrusterCommands, "thruster_commands", self._on_commands, 100)
        self._status = probe.create_subscription(AllocationStatus, "allocation_status", self._on_status, 100)
        probe.create_subscription(DiagnosticArray, "/diagnostics", self.diagnostics.append, 100)
        self.clock = probe.create_publisher(Clock, "/clock", 10)
        services = f"{NODE_NAME}/"
        self.fault_client = probe.create_client(SetActuatorFault, services + "set_actuator_fault")
        self.clear_client = probe.create_client(Trigger, services + "clear_faults")
        self.group_client = probe.create_client(SetGroupFault, services + "set_group_fault")
        self.tie_client = probe.create_client(SetBusTie, services + "set_bus_tie")
        self.power = probe.create_publisher(PowerAvailable, "power_available", 10)
        self.parameters_client = probe.create_client(SetParameters, services + "set_parameters")
        self.atomic_parameters_client = probe.create_client(SetParametersAtomically,
                                                            services + "set_parameters_atomically")
        self.capability_client = probe.create_client(GetCapability, services + "get_capability")
        if node == LIFECYCLE:
            self.node.trigger_configure()
            self.node.trigger_activate()
        if self.node.runtime is None:
            raise RuntimeError(f"{self.node.get_fully_qualified_name()} is not configured (see its log)")
        self._wrench_type = message_type(self.node.runtime.settings)
        self.wrench = probe.create_publisher(self._wrench_type, "wrench_command", 10)
        self.spin_until(lambda: self.wrench.get_subscription_count() > 0 and self.clock.get_subscription_count() > 0)
        self.tick(0)
        # The jump from time 0 to the first /clock makes the timer fire once.
        self.spin_until(lambda: self.node.samples >= 1 and len(self.commands) >= 1 and len(self.status) >= 1)
        if self.foreign_nodes():
            raise self._foreign("publishers on the node's topics")

    # -- whose output --------------------------------------------------------------------

    def foreign_nodes(self) -> list[str]:
        """Every node other than the harness's that publishes on its ``thruster_commands`` or
        ``allocation_status``, with the topic."""
        own = self.node.get_fully_qualified_name()
        return [f"{node_of(info)} on {subscription.topic_name}" for subscription in (self._commands, self._status)
                for info in self.probe.get_publishers_info_by_topic(subscription.topic_name)
                if node_of(info) != own and info.node_name != UNKNOWN_NODE]

    def _foreign(self, what: str) -> ForeignNodeError:
        found = self.foreign_nodes()
        return ForeignNodeError(f"{what}: not from {self.node.get_fully_qualified_name()} of this harness; "
                                f"{'other nodes publishing: ' + ', '.join(found) if found else 'no other node seen'}")

    @property
    def actuators(self) -> list[str]:
        """The actuator names of the node's vehicle, configuration order (none before it is configured)."""
        runtime = self.node.runtime
        return [] if runtime is None else [actuator.name for actuator in runtime.allocator.vehicle.actuators]

    def _on_commands(self, message: ThrusterCommands) -> None:
        if self.actuators and list(message.name) != self.actuators:
            raise self._foreign(f"thruster commands of actuators {', '.join(message.name)} (this vehicle's: "
                                f"{', '.join(self.actuators)})")
        self.commands.append(message)

    def _on_status(self, message: AllocationStatus) -> None:
        if self.actuators and len(message.at_thrust_limit) != len(self.actuators):
            raise self._foreign(f"an allocation status of {len(message.at_thrust_limit)} actuators (this vehicle "
                                f"has {len(self.actuators)})")
        self.status.append(message)

    # -- spinning and time ----------------------------------------------------------------

    def spin_until(self, predicate: Callable[[], bool], timeout: float | None = None) -> None:
        """Spin until ``predicate()`` holds; TimeoutError after ``timeout`` s of wall clock."""
        deadline = time.monotonic() + (self.timeout if timeout is None else timeout)
        while not predicate():
            if time.monotonic() > deadline:
                raise TimeoutError("condition not reached")
            self.executor.spin_once(timeout_sec=0.01)

    def spin_for(self, seconds: float) -> None:
        """Spin for ``seconds`` of wall clock (simulated time stands still)."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.01)

    def step(self, seconds: float) -> None:
        """Advance simulated time by ``seconds`` (rounded to whole allocation periods), one
        period at a time, and spin until the node has seen each step and the probe has
        every message it published."""
        for _ in range(round(seconds / self.node.period)):
            self.time_ns += round(self.node.period * 1e9)
            expected = self.node.samples + (self._samples_on_timer())
            self._publish_clock()
            self.spin_until(lambda expected=expected: self._caught_up() and self.node.samples >= expected
                            and len(self.commands) >= self.node.samples and self._has_every_status())

    def tick(self, periods: int = 1, period: float | None = None) -> None:
        """Advance simulated time by whole allocation periods (of ``period`` s if given), waiting
        for each sample's output (the timer trigger: one sample a period)."""
        period = period if period is not None else self.node.period
        for _ in range(periods):
            expected = self.node.samples + 1
            self.time_ns += round(period * 1e9)
            self._publish_clock()
            self.spin_until(lambda expected=expected: self.node.samples >= expected
                            and len(self.commands) >= expected and self._has_every_status())
        if periods == 0:
            self._publish_clock()
            self.spin_until(self._caught_up)

    def advance(self, seconds: float) -> None:
        """Advance simulated time without waiting for samples (the input trigger samples on input)."""
        self.time_ns += round(seconds * 1e9)
        self._publish_clock()
        self.spin_until(self._caught_up)
        self.spin_for(0.05)

    def _samples_on_timer(self) -> int:
        runtime = self.node.runtime
        return int(runtime is not None and runtime.active and runtime.settings.trigger == "timer")

    def _has_every_status(self) -> bool:
        """Whether the probe has every status the node published (one per sample, or fewer with
        ``status_rate_hz`` above 0)."""
        runtime = self.node.runtime
        return runtime is None or len(self.status) >= runtime.statuses_published

    def _caught_up(self) -> bool:
        return self.node.get_clock().now().nanoseconds >= self.time_ns

    def _publish_clock(self) -> None:
        self.clock.publish(Clock(clock=Time(sec=self.time_ns // 10**9, nanosec=self.time_ns % 10**9)))

    def diagnostics_after_a_second(self) -> dict[str, str]:
        """Step the clock one second and return the key-values of the diagnostics that follow."""
        count = len(self.diagnostics)
        self.tick(round(1.0 / self.node.period))
        self.spin_until(lambda: len(self.diagnostics) > count)
        return {kv.key: kv.value for kv in self.diagnostics[-1].status[0].values}

    # -- input --------------------------------------------------------------------------

    def sent(self, publisher, message) -> None:
        """Publish a message to the node and spin until it has taken it."""
        received = self.node.wrenches_received
        publisher.publish(message)
        self.spin_until(lambda: self.node.wrenches_received > received)

    def send_wrench(self, wrench: Iterable[float] | Wrench | WrenchStamped, frame_id: str | None = None) -> None:
        """Send [X, Y, Z, K, M, N] (in the node's ``frame``), a Wrench or a WrenchStamped, as the
        node's ``wrench_type`` wants it: a stamped one in ``frame_id`` (default: the message's
        own, else the node's ``base_frame``). Returns once the node has taken it."""
        if isinstance(wrench, WrenchStamped):
            frame_id = wrench.header.frame_id if frame_id is None else frame_id
            wrench = wrench.wrench
        elif not isinstance(wrench, Wrench):
            wrench = array_to_wrench(list(wrench))
        if self._wrench_type is WrenchStamped:
            message = WrenchStamped(wrench=wrench)
            message.header.frame_id = self.node.runtime.settings.base_frame if frame_id is None else frame_id
            message.header.stamp = self.node.get_clock().now().to_msg()
        else:
            message = wrench
        self.sent(self.wrench, message)

    def send_power(self, available: Mapping[str, float]) -> None:
        """Send the available power [kW] of the sources named on ``power_available``; returns
        once the node has taken it (valid or not)."""
        power_input = self.node.runtime.power_input
        if power_input is None:
            raise ValueError("the vehicle has no power.sources")
        self.spin_until(lambda: self.power.get_subscription_count() > 0)
        received = power_input.received
        self.power.publish(PowerAvailable(source=list(available), available=[float(v) for v in available.values()]))
        self.spin_until(lambda: power_input.received > received)

    # -- services -------------------------------------------------------------------------

    def call(self, client, request, attempts: int = 3):
        """Call a service of the node and return its response. A request whose reply does not
        come within the timeout is sent again (right after start a service can be visible
        before the way back is matched, and a first reply lost)."""
        self.spin_until(client.service_is_ready)
        for _ in range(attempts):
            future = client.call_async(request)
            try:
                self.spin_until(future.done, self.timeout / attempts)
            except TimeoutError:
                client.remove_pending_request(future)
                continue
            return future.result()
        raise TimeoutError(f"{client.srv_name} did not answer")

    def set_fault(self, actuator: str, mode: FaultMode | str, efficiency: float = 0.0,
                  angle: float = 0.0) -> tuple[bool, str]:
        """Set one actuator's fault through ``~/set_actuator_fault``: ``mode`` a FaultMode or its
        name (``failed``, ``degraded`` with ``efficiency``, ``stuck`` at ``angle`` [rad],
        ``nominal``). (success, the node's message); the fault holds from the next sample."""
        if isinstance(mode, str):
            try:
                mode = FaultMode[mode.upper()]
            except KeyError:
                raise ValueError(f"unknown fault mode '{mode}'; modes: "
                                 f"{', '.join(m.name.lower() for m in FaultMode)}") from None
        fault = ActuatorFault(actuator=actuator, mode=int(mode), efficiency=float(efficiency), azimuth=float(angle))
        response = self.call(self.fault_client, SetActuatorFault.Request(fault=fault))
        return response.success, response.message

    def set_group_fault(self, group: str) -> tuple[bool, str]:
        """Fail a redundancy group through ``~/set_group_fault``: (success, the node's message);
        its actuators FAILED and its sources at 0 kW from the next sample."""
        response = self.call(self.group_client, SetGroupFault.Request(group=group))
        return response.success, response.message

    def set_bus_tie(self, name: str, closed: bool) -> tuple[bool, str]:
        """Open or close a bus tie through ``~/set_bus_tie``: (success, the node's message)."""
        response = self.call(self.tie_client, SetBusTie.Request(name=name, closed=closed))
        return response.success, response.message

    def clear_faults(self) -> str:
        """Every actuator back to nominal, every source back to its available power
        (``~/clear_faults``); the node's message."""
        return self.call(self.clear_client, Trigger.Request()).message

    def set_parameters(self, values: Mapping[str, Any]) -> tuple[bool, str]:
        """Set parameters by name (dotted: ``actuators.main_port.thrust_max``) through
        ``~/set_parameters``, checked and applied as a whole: (successful, reason)."""
        request = SetParameters.Request(parameters=[Parameter(name, value=value).to_parameter_msg()
                                                    for name, value in values.items()])
        result = self.call(self.parameters_client, request).results[0]
        return result.successful, result.reason

    def capability(self, direction: Iterable[float]) -> tuple[float, np.ndarray]:
        """``~/get_capability`` along a wrench direction [X, Y, Z, K, M, N] in the node's frame:
        the largest scale the actuators reach along it now, and the wrench there. A refused
        question (no controlled component, not finite) raises ValueError with the node's reason."""
        request = GetCapability.Request(direction=array_to_wrench(list(direction)))
        response = self.call(self.capability_client, request)
        if not response.success:
            raise ValueError(response.message)
        return response.scale, wrench_to_array(response.achieved)

    def close(self) -> None:
        """Stop the executor and destroy both nodes (the context is the caller's)."""
        self.executor.shutdown()
        self.node.release()
        self.node.destroy_node()
        self.probe.destroy_node()
