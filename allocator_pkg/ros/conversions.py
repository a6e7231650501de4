"""ROS messages to and from the library's arrays and results. No node here: ``ctl``, the
demo and the benches build and read the same messages without importing the node."""

from __future__ import annotations

import array
import math

import numpy as np
from geometry_msgs.msg import Wrench
from std_msgs.msg import Header

from allocator_msgs.msg import AllocationStatus, ThrusterCommands

from ..allocation.power_budget import SourcePower
from ..allocation.result import AllocationResult
from ..solvers.outcome import Outcome
from ..vehicle.node_settings import FLU, FRD

OUTCOME_CODES = {Outcome.SOLVED: AllocationStatus.OUTCOME_SOLVED,
                 Outcome.INACCURATE: AllocationStatus.OUTCOME_INACCURATE,
                 Outcome.ITERATION_LIMIT: AllocationStatus.OUTCOME_ITERATION_LIMIT,
                 Outcome.FALLBACK: AllocationStatus.OUTCOME_FALLBACK, Outcome.STOPPED: AllocationStatus.OUTCOME_STOPPED}
"""``AllocationStatus.outcome`` of each sample outcome (``Outcome.FAILED`` never ends a sample)."""
OUTCOME_NAMES = {code: outcome.value for outcome, code in OUTCOME_CODES.items()}
"""The outcome's name of each ``AllocationStatus.outcome`` code, for people and CSV files."""


def wrench_to_array(wrench: Wrench) -> np.ndarray:
    """[X, Y, Z, K, M, N] of a Wrench."""
    return np.array([wrench.force.x, wrench.force.y, wrench.force.z,
                     wrench.torque.x, wrench.torque.y, wrench.torque.z])


def array_to_wrench(values) -> Wrench:
    """A Wrench of [X, Y, Z, K, M, N]."""
    return fill_wrench(Wrench(), values)


def fill_wrench(wrench: Wrench, values) -> Wrench:
    """``wrench`` with its components set to [X, Y, Z, K, M, N] (a message's own Wrench is
    filled in place: making one costs several times more)."""
    force, torque = wrench.force, wrench.torque
    force.x, force.y, force.z, torque.x, torque.y, torque.z = np.asarray(values, dtype=float).tolist()
    return wrench


def fill_wrench_in(wrench: Wrench, values: np.ndarray, frame: str) -> Wrench:
    """``wrench`` set to [X, Y, Z, K, M, N] given in FRD, written in the body frame ``frame``
    (``wrench_between`` for six numbers, without making an array)."""
    x, y, z, k, m, n = values.tolist()
    if frame == FLU:
        y, z, m, n = -y, -z, -m, -n
    force, torque = wrench.force, wrench.torque
    force.x, force.y, force.z, torque.x, torque.y, torque.z = x, y, z, k, m, n
    return wrench


def doubles(values: np.ndarray) -> array.array:
    """A float64 sequence field's own type: the generated setter takes it without checking
    every element."""
    field = array.array("d")
    field.frombytes(np.ascontiguousarray(values, dtype=np.float64).tobytes())
    return field


def commands_message(result: AllocationResult, names: tuple[str, ...], header: Header,
                     message: ThrusterCommands | None = None) -> ThrusterCommands:
    """Every actuator's thrust, set-point, angle and fault mode of one sample, in ``message``
    (every field set; a publisher serialises at publish, so one message can serve each sample)
    or a new one."""
    message = ThrusterCommands() if message is None else message
    message.header = header
    if tuple(message.name) != names:
        message.name = list(names)
    message.thrust = doubles(result.thrust)
    message.command = doubles(result.command)
    message.azimuth = doubles(result.azimuth)
    mode = array.array("B")
    mode.frombytes(result.mode.astype(np.uint8).tobytes())
    message.mode = mode
    return message


def status_message(result: AllocationResult, solver_status: str, header: Header, frame: str = FRD,
                   voltage: float | None = None, message: AllocationStatus | None = None,
                   power: SourcePower | None = None) -> AllocationStatus:
    """Requested, achieved and unallocated wrench (in the body frame convention ``frame``),
    saturation, per-actuator limit flags, the supply voltage in use (None: NaN), the power per
    source (None: no sources) and solver figures of one sample, in ``message`` (every field
    set) or a new one."""
    message = AllocationStatus() if message is None else message
    message.header = header
    fill_wrench_in(message.requested, result.requested, frame)
    fill_wrench_in(message.achieved, result.achieved, frame)
    message.saturated = result.saturated
    message.method = result.method
    message.solver_status = solver_status
    message.outcome = OUTCOME_CODES[result.outcome]
    message.iterations = result.iterations
    message.solve_time = result.solve_time
    message.power = result.power
    fill_wrench_in(message.unallocated, result.unallocated, frame)
    message.at_thrust_limit = result.at_thrust_limit.tolist()
    message.at_rate_limit = result.at_rate_limit.tolist()
    message.voltage = math.nan if voltage is None else float(voltage)
    if power is None:
        if message.power_source:                  # a message that carried power per source before
            message.power_source, message.source_power, message.source_available = [], [], []
            message.power_limited = False
    else:
        message.power_source = list(power.source)
        message.source_power, message.source_available = doubles(power.power), doubles(power.available)
        message.power_limited = power.limited
    return message
