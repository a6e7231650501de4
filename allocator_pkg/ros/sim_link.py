"""The node's link of an ``allocator-sim`` run (a :class:`~allocator_pkg.simulation.closed_loop.Link`):
``/clock``, the vehicle's ``odometry`` and ``battery_state``, the power plant's
``power_available`` and the controller's ``wrench_command`` out, the node's
``allocation_status`` and ``thruster_commands`` in, its services, and the recording of every step into ``run.mcap``.

The clock advances only when the node has answered the step's wrench: its status stamped with
the step's time and echoing the wrench, and its commands of the same stamp. Before the run,
``synchronise`` brings the node onto this clock without a wrench (it allocates nothing) and
``first_sample`` has it allocate the first one at a known step, so that the node allocates the
same requests in every run.

The run's node and this link share a namespace of the run's own (``/clock`` in it too), so
that runs beside each other never take each other's messages; the link takes only its node's:
a publisher on the node's topics or a subscriber of its wrench that is not the node (name and
namespace), or commands of other actuators than the vehicle's, stop the run with an error
naming the foreign node."""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import numpy as np
import rclpy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
from rclpy.executors import SingleThreadedExecutor
from rclpy.qos import QoSProfile
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import BatteryState

from allocator_msgs.msg import AllocationStatus, PowerAvailable, ThrusterCommands

from ..simulation.closed_loop import Answer
from ..simulation.kinematics import quaternion
from ..simulation.plant import Pose
from ..simulation.run_setup import SimulationError
from ..vehicle.node_settings import NODE_NAME
from . import qos
from .conversions import array_to_wrench, wrench_to_array
from .echo import format_sample
from .node_client import Controller
from .process import UNKNOWN_NODE, namespace_arguments, node_of
from .sim_recording import RunRecording

START_TIMEOUT = 30.0
"""[s] of wall time the node has to subscribe to the wrench and the clock."""
WARM_UP_TIMEOUT = 60.0
"""[s] of wall time the node has to come into step."""
ANSWER_TIMEOUT = 30.0
"""[s] of wall time to wait for the node's answer to a step before sending it again. Long: a
node that did get the step and answers late (a busy machine) would take a second wrench of the
same step as one waiting for the next period, and sample twice in one step; a lost message is
rare on loopback."""
RETRIES = 3
FIRST_WRENCH_DELAY = 0.1
"""[s] of wall time between the first wrench and the clock step that is to allocate it."""
POWER_DELAY = 0.1
"""[s] of wall time between new available power and the clock step that is to allocate with it."""
TOPICS = {"clock": "/clock", "odometry": "/odometry", "setpoint": "/setpoint", "battery": "/battery_state",
          "power": "/power_available",
          "wrench": "/wrench_command", "commands": "/thruster_commands", "status": "/allocation_status"}


def _clock(t_ns: int) -> Clock:
    stamp = Clock()
    stamp.clock.sec, stamp.clock.nanosec = divmod(t_ns, 1_000_000_000)
    return stamp


def _nanoseconds(message) -> int:
    return message.header.stamp.sec * 1_000_000_000 + message.header.stamp.nanosec


def _answer(status: AllocationStatus, commands: ThrusterCommands) -> Answer:
    return Answer(np.array(commands.thrust), np.array(commands.azimuth), status.saturated, status.power,
                  status.voltage, wrench_to_array(status.unallocated),
                  source_power=np.array(status.source_power) if status.power_source else None,
                  consequence_alarm=bool(status.consequence_alarm))


class NodeLink:
    """The link to the node of one run, in a rclpy context of its own in the run's ``namespace``,
    the node's ``actuators`` named as the vehicle names them; ``close`` ends it."""

    def __init__(self, out: Path, node_log: Path, namespace: str, actuators: list[str]) -> None:
        self.node_log = node_log
        self.actuators = list(actuators)
        self.expected = f"{namespace}/{NODE_NAME}"
        self.context = rclpy.Context()
        rclpy.init(context=self.context, args=["--ros-args", *namespace_arguments(namespace)])
        self.node = rclpy.create_node("allocator_sim", context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.services = Controller(self.node)
        self.clock = self.node.create_publisher(Clock, "/clock", 10)
        self.odometry = self.node.create_publisher(Odometry, "odometry", 10)
        self.battery = self.node.create_publisher(BatteryState, "battery_state", 10)
        self.power = self.node.create_publisher(PowerAvailable, "power_available", 10)
        self.reported: dict[str, float] = {}
        self.answers: dict[str, Any] = {}
        self.last: tuple[AllocationStatus, ThrusterCommands] | None = None
        self._status = self.node.create_subscription(AllocationStatus, "allocation_status", self._on_status, 10)
        self._commands = self.node.create_subscription(ThrusterCommands, "thruster_commands", self._on_commands, 10)
        self.recording = RunRecording(out / "run.mcap", self.node)
        own, node_output = [QoSProfile(depth=10)], [qos.output()]
        self.offered = {"clock": own, "battery": own, "power": own, "odometry": own, "setpoint": [], "wrench": own,
                        "commands": node_output, "status": node_output}
        """What each recorded topic's publishers offer: this process's profile, the node's outputs';
        nothing for the set-point, recorded but not published."""

    def _endpoints(self) -> list[tuple[Any, str]]:
        """The publishers of the node's outputs and the subscribers of its wrench, with the topic."""
        found = [(info, self._status.topic_name) for info in self.node.get_publishers_info_by_topic(
            self._status.topic_name)]
        found += [(info, self._commands.topic_name) for info in self.node.get_publishers_info_by_topic(
            self._commands.topic_name)]
        found += [(info, self.services.wrench.topic_name) for info in self.node.get_subscriptions_info_by_topic(
            self.services.wrench.topic_name)]
        return found

    def foreign_nodes(self) -> list[str]:
        """Every node other than the run's that publishes on its ``allocation_status`` or
        ``thruster_commands`` or takes its ``wrench_command``, with the topic."""
        return sorted({f"{node_of(info)} on {topic}" for info, topic in self._endpoints()
                       if node_of(info) != self.expected and info.node_name != UNKNOWN_NODE})

    def _foreign(self, what: str) -> SimulationError:
        found = self.foreign_nodes()
        return SimulationError(f"{what}: not from this run's {self.expected}; "
                               + (f"another node answers: {', '.join(found)}" if found else "no other node seen")
                               + f" (see {self.node_log})")

    def _on_status(self, message: AllocationStatus) -> None:
        if len(message.at_thrust_limit) != len(self.actuators):
            raise self._foreign(f"an allocation status of {len(message.at_thrust_limit)} actuators (the vehicle "
                                f"has {len(self.actuators)})")
        self.answers["status"] = message

    def _on_commands(self, message: ThrusterCommands) -> None:
        if list(message.name) != self.actuators:
            raise self._foreign(f"thruster commands of {', '.join(message.name)} (the vehicle's actuators: "
                                f"{', '.join(self.actuators)})")
        self.answers["commands"] = message

    def close(self) -> None:
        self.recording.close()
        self.executor.shutdown()
        self.node.destroy_node()
        rclpy.try_shutdown(context=self.context)

    def wait_for_node(self, running) -> None:
        """Until the node subscribes to the wrench and the clock; ``running()`` says whether its
        process still runs."""
        started = time.monotonic()
        while self.services.wrench.get_subscription_count() == 0 or self.clock.get_subscription_count() == 0 \
                or any(info.node_name == UNKNOWN_NODE for info, _ in self._endpoints()):
            self.executor.spin_once(timeout_sec=0.05)
            if not running() or time.monotonic() - started > START_TIMEOUT:
                raise SimulationError(f"allocator_node did not start (see {self.node_log})")
        if found := self.foreign_nodes():
            raise SimulationError(f"other nodes than this run's {self.expected} on its topics: {', '.join(found)} "
                                  f"(see {self.node_log})")

    def begin(self, t_ns: int, period_ns: int, supply: float | None, wrench: np.ndarray) -> tuple[int, Answer]:
        """:meth:`synchronise` from ``t_ns``, then :meth:`first_sample` of ``wrench``."""
        return self.first_sample(self.synchronise(t_ns, period_ns, supply), period_ns, wrench, supply)

    def synchronise(self, t_ns: int, period_ns: int, voltage: float | None) -> int:
        """Clock steps from ``t_ns``, no wrench, until the node has stopped (its watchdog's zero
        thrust, which leaves the allocation method untouched) in three steps in a row, each
        stamped with its step's time and at the supply ``voltage``: the node then follows this
        clock and has the battery's voltage. The time of the last of those steps."""
        in_step, started = 0, time.monotonic()
        while in_step < 3:
            if time.monotonic() - started > WARM_UP_TIMEOUT:
                raise SimulationError(f"allocator_node did not come into step with the clock (see {self.node_log})")
            t_ns += period_ns
            self.answers.clear()
            self.publish_battery(t_ns, voltage)
            self.clock.publish(_clock(t_ns))
            deadline = time.monotonic() + 0.5
            while not self._stopped_at(t_ns, voltage) and time.monotonic() < deadline:
                self.executor.spin_once(timeout_sec=0.01)
            in_step = in_step + 1 if self._stopped_at(t_ns, voltage) else 0
        return t_ns

    def _stopped_at(self, t_ns: int, voltage: float | None) -> bool:
        status = self.answers.get("status")
        return status is not None and status.outcome == AllocationStatus.OUTCOME_STOPPED \
            and _nanoseconds(status) == t_ns and (voltage is None or not math.isfinite(status.voltage)
                                                  or abs(status.voltage - voltage) <= 1e-9 * abs(voltage))

    def first_sample(self, t_ns: int, period_ns: int, wrench: np.ndarray,
                     voltage: float | None) -> tuple[int, Answer]:
        """The node's first allocation, after :meth:`synchronise` ended at ``t_ns``: the wrench
        is sent before the next clock step, so that it waits in the node (its last sample, a
        stop, is less than a period old) and is allocated at that step. Should it come after
        the step, the node stops once more and allocates it at the step after. The time of
        the step that allocated it, and the node's answer."""
        self.services.wrench.publish(array_to_wrench(wrench))
        deadline = time.monotonic() + FIRST_WRENCH_DELAY
        while time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.005)
        started = time.monotonic()
        while time.monotonic() - started < WARM_UP_TIMEOUT:
            t_ns += period_ns
            self.answers.clear()
            self.publish_battery(t_ns, voltage)
            self.clock.publish(_clock(t_ns))
            deadline = time.monotonic() + ANSWER_TIMEOUT
            while time.monotonic() < deadline:
                self.executor.spin_once(timeout_sec=0.01)
                if self._answered(t_ns, wrench) or self._stopped_at(t_ns, None):
                    break
            if self._answered(t_ns, wrench):
                self.last = self.answers["status"], self.answers["commands"]
                return t_ns, _answer(*self.last)
        raise SimulationError(f"allocator_node did not allocate the first wrench (see {self.node_log})")

    def _answered(self, t_ns: int, wrench: np.ndarray) -> bool:
        """Whether the latest status and commands are the node's sample of ``wrench`` at ``t_ns``."""
        status, commands = self.answers.get("status"), self.answers.get("commands")
        return status is not None and commands is not None and _nanoseconds(status) == t_ns == \
            _nanoseconds(commands) and status.outcome != AllocationStatus.OUTCOME_STOPPED \
            and np.allclose(wrench_to_array(status.requested), wrench, rtol=1e-9, atol=1e-9)

    def publish_battery(self, t_ns: int, value: float | None) -> BatteryState | None:
        if value is None:
            return None
        message = BatteryState(voltage=float(value), present=True)
        message.header.stamp.sec, message.header.stamp.nanosec = divmod(t_ns, 1_000_000_000)
        self.battery.publish(message)
        return message

    def publish_power(self, t_ns: int, power: dict[str, float] | None) -> PowerAvailable | None:
        """``power_available`` of the sources reported (none: nothing); a change is given
        POWER_DELAY of wall time to reach the node before the clock step that is to use it."""
        if not power:
            return None
        message = PowerAvailable(source=list(power), available=[float(v) for v in power.values()])
        message.header.stamp.sec, message.header.stamp.nanosec = divmod(t_ns, 1_000_000_000)
        self.power.publish(message)
        if power != self.reported:
            self.reported = dict(power)
            deadline = time.monotonic() + POWER_DELAY
            while time.monotonic() < deadline:
                self.executor.spin_once(timeout_sec=0.005)
        return message

    def step(self, t_ns: int, pose: Pose, voltage: float | None, wrench: np.ndarray, setpoint_position,
             setpoint_heading: float, record: bool = True, power: dict[str, float] | None = None) -> Answer:
        """One step at ``t_ns``: battery_state (when there is a voltage), power_available (when
        the power plant reports), the odometry of ``pose``, then the clock and the wrench until
        the node answers; with ``record``, every message of the step and the set-point in force
        (``setpoint_position`` NED [m], ``setpoint_heading`` [rad]) recorded. The node's answer."""
        battery = self.publish_battery(t_ns, voltage)
        available = self.publish_power(t_ns, power)
        odometry = Odometry()
        odometry.header.stamp.sec, odometry.header.stamp.nanosec = divmod(t_ns, 1_000_000_000)
        odometry.header.frame_id, odometry.child_frame_id = "ned", "base_link"
        p, o = odometry.pose.pose.position, odometry.pose.pose.orientation
        p.x, p.y, p.z = (float(v) for v in pose.position)
        o.x, o.y, o.z, o.w = quaternion(*pose.attitude)
        v, w = odometry.twist.twist.linear, odometry.twist.twist.angular
        v.x, v.y, v.z = (float(x) for x in pose.velocity)
        w.x, w.y, w.z = (float(x) for x in pose.angular_velocity)
        self.odometry.publish(odometry)
        goal = PoseStamped()
        goal.header = odometry.header
        goal.pose.position.x, goal.pose.position.y, goal.pose.position.z = (float(v) for v in setpoint_position)
        g = goal.pose.orientation
        g.x, g.y, g.z, g.w = quaternion(0.0, 0.0, setpoint_heading)
        status, commands, clock, message = self.exchange(t_ns, wrench)
        self.last = status, commands
        if not record:
            return _answer(status, commands)
        if self.recording.origin is None:
            self.recording.start(t_ns)
        for topic, item in (("clock", clock), ("battery", battery), ("power", available), ("odometry", odometry),
                            ("setpoint", goal), ("wrench", message), ("commands", commands),
                            ("status", status)):
            if item is not None:
                if TOPICS[topic] not in self.recording:
                    self.recording.add_topic(TOPICS[topic], type(item), self.offered[topic])
                self.recording.write(TOPICS[topic], item, t_ns)
        return _answer(status, commands)

    def live_line(self) -> str:
        return format_sample(self.last[1], self.last[0]) if self.last is not None else ""

    def set_fault(self, actuator: str, mode: str, value: float) -> str:
        """``~/set_actuator_fault``; its message, or SimulationError when the node refuses it."""
        response = self.services.set_fault(actuator, mode, value)
        if not response.success:
            raise SimulationError(f"set_actuator_fault refused: {response.message}")
        return response.message

    def set_group_fault(self, group: str) -> str:
        """``~/set_group_fault``; its message, or SimulationError when the node refuses it."""
        response = self.services.set_group_fault(group)
        if not response.success:
            raise SimulationError(f"set_group_fault refused: {response.message}")
        return response.message

    def set_bus_tie(self, name: str, closed: bool) -> str:
        """``~/set_bus_tie``; its message, or SimulationError when the node refuses it."""
        response = self.services.set_bus_tie(name, closed)
        if not response.success:
            raise SimulationError(f"set_bus_tie refused: {response.message}")
        return response.message

    def clear_faults(self) -> str:
        return self.services.clear_faults().message

    def set_parameter(self, name: str, value: Any) -> str:
        """``~/set_parameters_atomically`` of one parameter; SimulationError when the node refuses it."""
        result = self.services.set_parameters({name: value})
        if not result.successful:
            raise SimulationError(f"parameter {name} refused: {result.reason}")
        return f"{name} = {value}"

    def exchange(self, t_ns: int, wrench: np.ndarray) -> tuple:
        """Publish the clock at ``t_ns`` and the wrench; (status, commands, clock, wrench) once the
        node has answered that wrench at that time. Unanswered, the clock is sent again, then
        the wrench; SimulationError after RETRIES."""
        clock = _clock(t_ns)
        message = array_to_wrench(wrench)
        for attempt in range(RETRIES):
            self.answers.clear()
            self.clock.publish(clock)
            if attempt == 0:
                self.services.wrench.publish(message)
            deadline = time.monotonic() + ANSWER_TIMEOUT
            while time.monotonic() < deadline:
                self.executor.spin_once(timeout_sec=0.05)
                if self._answered(t_ns, wrench):
                    return self.answers["status"], self.answers["commands"], clock, message
            if attempt == 1:
                self.services.wrench.publish(message)
        raise SimulationError(f"allocator_node did not answer the wrench of t = {t_ns * 1e-9:.3f} s "
                              f"(see {self.node_log})")
