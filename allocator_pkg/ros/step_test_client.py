"""allocator-ctl step-test: a direction check on the bench (docs/step_test.md).

Each controlled DOF in turn, positive then negative, the tool asks ``~/get_capability`` for the
largest wrench along it, commands a stated share of that for ``hold`` seconds on
``wrench_command``, then zero for ``rest`` seconds, and prints what every actuator was
commanded at the end of the step and which way the vehicle should move. With ``--actuators``
it holds one actuator at a time instead, through the node's ``~/hold_actuator`` (refused
unless the node's ``step_test.enabled``, and while its input is stale), sending zero wrenches
all along (service calls included) so that the watchdog keeps working, the first hold only
once a sample has taken them, and prints which way that actuator alone pushes the vehicle. The test ends by
itself: every step is bounded, and the last thing sent is a zero wrench.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import TextIO

import numpy as np
import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node

from allocator_msgs.msg import AllocationStatus, ThrusterCommands
from allocator_msgs.srv import HoldActuator

from ..vehicle.config import DOF_NAMES
from ..vehicle.node_settings import FLU, FRD
from .conversions import array_to_wrench, wrench_to_array

MOTIONS = {
    FRD: {"surge": ("move forward", "move backward"), "sway": ("move to starboard", "move to port"),
          "heave": ("move down", "move up"), "roll": ("roll starboard side down", "roll port side down"),
          "pitch": ("pitch nose up", "pitch nose down"), "yaw": ("turn nose to starboard", "turn nose to port")},
    FLU: {"surge": ("move forward", "move backward"), "sway": ("move to port", "move to starboard"),
          "heave": ("move up", "move down"), "roll": ("roll starboard side down", "roll port side down"),
          "pitch": ("pitch nose down", "pitch nose up"), "yaw": ("turn nose to port", "turn nose to starboard")},
}
"""Which way a positive and a negative force or moment along each DOF moves the vehicle, in each
body frame convention. Moments by the right-hand rule: in FRD (z down) a positive yaw turns x
toward y, the nose to starboard; in FLU (y to port, z up) toward port."""

INPUT_TIMEOUT = 5.0
"""[s] How long ``--actuators`` waits for the node to take its zero wrenches before the first hold."""
UNITS = {"surge": "N", "sway": "N", "heave": "N", "roll": "N m", "pitch": "N m", "yaw": "N m"}


def motion(dof: str, value: float, frame: str) -> str:
    """Which way ``value`` of ``dof`` (in the frame convention ``frame``) moves the vehicle."""
    return MOTIONS[frame][dof][0 if value > 0 else 1]


def describe(wrench: np.ndarray, dofs: list[str], frame: str, share: float = 0.05) -> str:
    """The components of a wrench in the controlled DOFs that count (at least ``share`` of the
    largest force, or of the largest moment), each with the way it moves the vehicle."""
    parts = []
    largest = {unit: max((abs(wrench[DOF_NAMES.index(d)]) for d in dofs if UNITS[d] == unit), default=0.0)
               for unit in set(UNITS.values())}
    for dof in dofs:
        value = float(wrench[DOF_NAMES.index(dof)])
        if largest[UNITS[dof]] > 0.0 and abs(value) >= share * largest[UNITS[dof]]:
            parts.append(f"{dof} {value:+.1f} {UNITS[dof]} ({motion(dof, value, frame)})")
    return ", ".join(parts) or "nothing in the controlled DOFs"


def actuator_lines(commands: ThrusterCommands) -> list[str]:
    """One line per actuator: its thrust, set-point and, for a rotatable one, its angle."""
    lines = []
    for name, thrust, command, azimuth, mode in zip(commands.name, commands.thrust, commands.command,
                                                    commands.azimuth, commands.mode):
        angle = f"  azimuth {math.degrees(azimuth) + 0.0:7.1f} deg" if azimuth != 0.0 else ""
        held_out = "  (held out)" if mode == 2 else ""
        lines.append(f"    {name:<16} {thrust:9.2f} N  command {command:9.3f}{angle}{held_out}")
    return lines


class DirectionCheck:
    """Drives one allocator through the steps; ``controller`` is allocator-ctl's Controller."""

    def __init__(self, controller, out: TextIO, share: float, hold: float, rest: float, rate: float):
        self.controller = controller
        self.node: Node = controller.node
        self.out = out
        self.share, self.hold, self.rest, self.period = share, hold, rest, 1.0 / rate
        self.commands: ThrusterCommands | None = None
        self.status: AllocationStatus | None = None
        self.held: int | None = None          # the index of the actuator held, with --actuators
        self.live = False                     # a sample allocated a wrench (not stopped) since the last reset
        self.executor = self.node.executor    # one executor for the topics and the Controller's services
        if self.executor is None:
            self.executor = SingleThreadedExecutor(context=self.node.context)
            self.executor.add_node(self.node)
        self.node.create_subscription(ThrusterCommands, controller.topic("thruster_commands"), self._on_commands, 10)
        self.node.create_subscription(AllocationStatus, controller.topic("allocation_status"), self._on_status, 10)
        self.message = array_to_wrench([0.0] * 6)
        # Wrenches go out every period whenever the executor spins, the Controller's service calls
        # included, so that the node's watchdog never finds the input stale between two steps.
        self.node.create_timer(self.period, self._publish)

    def _publish(self) -> None:
        self.controller.wrench.publish(self.message)

    def _on_commands(self, message: ThrusterCommands) -> None:
        """The last commands of a step; of a hold, those with the held actuator's largest thrust."""
        i = self.held
        if i is None or self.commands is None or abs(message.thrust[i]) >= abs(self.commands.thrust[i]):
            self.commands = message

    def _on_status(self, message: AllocationStatus) -> None:
        """The last status of a step; of a hold, the one with the largest requested wrench (the
        held thrust's, while the hold lasts). A status not stopped says the node takes the wrenches."""
        self.live = self.live or message.outcome != AllocationStatus.OUTCOME_STOPPED
        if self.held is None or self.status is None or \
                np.linalg.norm(wrench_to_array(message.requested)) >= np.linalg.norm(wrench_to_array(
                    self.status.requested)):
            self.status = message

    def _print(self, text: str) -> None:
        print(text, file=self.out, flush=True)

    def _send(self, wrench: list[float], seconds: float) -> None:
        """Publish ``wrench`` now and every period (the timer) for ``seconds``, spinning."""
        self.message = array_to_wrench(wrench)
        self._publish()
        self._spin_until(lambda: False, seconds)

    def _spin_until(self, done: Callable[[], bool], seconds: float) -> bool:
        """Spin until ``done()`` or for ``seconds``; whether ``done()``."""
        end = time.monotonic() + seconds
        while rclpy.ok(context=self.node.context) and not done() and (left := end - time.monotonic()) > 0.0:
            self.executor.spin_once(timeout_sec=min(left, self.period))
        return done()

    def _input_taken(self) -> bool:
        """Zero wrenches until a sample allocates one, within ``INPUT_TIMEOUT``: the node holds an
        actuator only while its input is not stale, and its watchdog ends the hold at the first
        sample that finds it stale."""
        self.live = False
        self.message = array_to_wrench([0.0] * 6)
        self._publish()
        return self._spin_until(lambda: self.live, INPUT_TIMEOUT)

    def _settings(self) -> tuple[list[str], str]:
        values = self.controller.get_parameters(["dofs", "frame"])
        return list(values["dofs"]), str(values["frame"])

    def run_dofs(self) -> int:
        """Each controlled DOF positive then negative at ``share`` of the capability along it."""
        dofs, frame = self._settings()
        self._print(f"step test: {len(dofs)} DOFs ({', '.join(dofs)}), each +/- at {self.share:.0%} of what the "
                    f"actuators can give along it now, {self.hold:g} s each, {self.rest:g} s of zero between; "
                    f"frame {frame.upper()}; about {2 * len(dofs) * (self.hold + self.rest):.0f} s")
        try:
            for dof in dofs:
                for sign in (1.0, -1.0):
                    direction = [0.0] * 6
                    direction[DOF_NAMES.index(dof)] = sign
                    response = self.controller.capability(direction)
                    label = f"{dof} {'+' if sign > 0 else '-'}"
                    if not response.success or not response.scale > 0.0:
                        self._print(f"{label}: skipped, no capability ({response.message})")
                        continue
                    size = self.share * response.scale
                    wrench = [sign * size if i == DOF_NAMES.index(dof) else 0.0 for i in range(6)]
                    self._print(f"{label}: {sign * size:+.1f} {UNITS[dof]} ({self.share:.0%} of "
                                f"{response.scale:.1f} {UNITS[dof]}): the vehicle should "
                                f"{motion(dof, sign, frame)}")
                    self._step(wrench)
        finally:
            self._send([0.0] * 6, self.period)
        return 0

    def run_actuators(self, thrust_share: float) -> int:
        """Each actuator alone at ``thrust_share`` of its largest thrust, through ~/hold_actuator."""
        dofs, frame = self._settings()
        names = list(self.controller.get_parameters(["actuators.names"])["actuators.names"])
        self._print(f"step test: {len(names)} actuators one at a time at {thrust_share:.0%} of their largest "
                    f"thrust, {self.hold:g} s each, {self.rest:g} s of zero between; frame {frame.upper()}")
        failures = 0
        try:
            if not self._input_taken():
                self._print(f"no sample took this tool's wrenches within {INPUT_TIMEOUT:g} s (is the allocator "
                            "active, with wrench_type wrench?)")
                return 1
            for name in names:
                key = f"actuators.{name}.thrust_max"
                thrust_max = self.controller.get_parameters([key])[key]       # none: a control surface
                if thrust_max is None:
                    self._print(f"{name}: skipped, a control surface")
                    continue
                thrust = thrust_share * thrust_max
                request = HoldActuator.Request(actuator=name, thrust=thrust, duration=self.hold)
                response = self.controller.call(HoldActuator, "hold_actuator", request)
                if not response.success:
                    self._print(f"{name}: refused: {response.message}")
                    failures += 1
                    continue
                self._print(f"{name}: {thrust:+.1f} N alone")
                self.held = names.index(name)
                self._step([0.0] * 6, pushes=(dofs, frame))
                self.held = None
        finally:
            self._send([0.0] * 6, self.period)
        return 1 if failures else 0

    def _step(self, wrench: list[float], pushes: tuple[list[str], str] | None = None) -> None:
        """Hold ``wrench`` for the step, print the last commands (and, for a held actuator, which
        way the requested wrench pushes), then zero for the rest."""
        self.commands = self.status = None
        self._send(wrench, self.hold)
        if self.commands is None:
            self._print("    no thruster_commands received (is the allocator active?)")
        else:
            for line in actuator_lines(self.commands):
                self._print(line)
        if pushes is not None and self.status is not None:
            dofs, frame = pushes
            self._print(f"    pushes the vehicle: {describe(wrench_to_array(self.status.requested), dofs, frame)}")
        self._send([0.0] * 6, self.rest)
