"""allocator-sim: the real ``allocator_node`` holding a simulated vehicle on station, in
lock-step on ROS 2 sim time.

    allocator-sim SCENARIO --out DIR [--seed N] [--method M] [--duration-scale S] [--live [SECONDS]]
    allocator-sim compare SCENARIO --methods qp lp ... --out DIR [--duration-scale S]

The node runs as its own process, unchanged, with ``use_sim_time`` and ``trigger: input``.
This process publishes ``/clock``, the vehicle's ``odometry``, its ``battery_state`` and the
controller's ``wrench_command``, and integrates the vehicle on the ``thruster_commands`` it
gets back. The clock advances one step (1 / rate_hz) only when the node has answered the
step's wrench (its ``allocation_status`` stamped with the step's time and echoing the
wrench), so a run is deterministic for a seed and runs as fast as the node answers.

Writes ``metrics.json``, ``run.mcap`` (every topic, for Foxglove and ``ros2 bag play``),
``footprint.png`` and ``timeline.png`` into DIR; ``compare`` writes one such folder per
method, ``compare.md`` and ``compare.png``. Frames: odometry and set-point in NED (frame_id
``ned``), the body in FRD (``base_link``), as the models are written.
"""

from __future__ import annotations

import argparse
import ctypes
import json
import math
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..configuration.parameters import load_vehicle
from ..methods import METHODS
from ..simulation.controller import StationKeeping
from ..simulation.environment import Environment
from ..simulation.kinematics import euler, quaternion
from ..simulation.metrics import run_metrics
from ..simulation.plant import PLANAR, Plant
from ..simulation.rov import Rov
from ..simulation.scenario import Event, Scenario, ScenarioError, load_scenario
from ..simulation.thrusters import Thrusters
from ..simulation.trace import Trace
from ..simulation.vessel import Vessel, VesselParameters
from ..vehicle.config import Vehicle

START_NS = 100_000_000_000
"""Sim time [ns] of the first warm-up step; the run starts after the warm-up."""
WARM_UP_TIMEOUT = 60.0
"""[s] of wall time the node has to come into step."""
PR_SET_PDEATHSIG = 1
"""prctl option: the signal a process gets when its parent ends (linux/prctl.h)."""
ANSWER_TIMEOUT = 30.0
"""[s] of wall time to wait for the node's answer to a step before sending it again. Long: a
node that did get the step and answers late (a busy machine) would take a second wrench of the
same step as one waiting for the next period, and sample twice in one step; a lost message is
rare on loopback."""
RETRIES = 3
TOPICS = {"clock": "/clock", "odometry": "/odometry", "setpoint": "/setpoint", "battery": "/battery_state",
          "wrench": "/wrench_command", "commands": "/thruster_commands", "status": "/allocation_status"}


class SimulationError(RuntimeError):
    pass


_RECORDABLE: dict[type, type] = {}


def _plain(value):
    if hasattr(value, "get_fields_and_field_types"):
        return {name: _plain(getattr(value, name)) for name in value.get_fields_and_field_types()}
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def recordable(message):
    """``message`` as the MCAP writer takes every field of it (fixed-size arrays, which rclpy
    holds as numpy arrays, as lists): a mapping of its fields whose type has the message's
    name and package, so that the recording finds its schema."""
    kind = type(message)
    if kind not in _RECORDABLE:
        _RECORDABLE[kind] = type(kind.__name__, (dict,), {"__module__": kind.__module__})
    return _RECORDABLE[kind](_plain(message))


@dataclass
class RunResult:
    metrics: dict[str, float]
    trace: Trace
    vehicle: Vehicle
    fault_intervals: list[tuple[float, float]]


def build_plant(scenario: Scenario, vehicle: Vehicle) -> Plant:
    if scenario.model == "dp_vessel":
        hull = Vessel(VesselParameters(coefficients=scenario.particulars.coefficients))
    else:
        hull = Rov()
    thrusters = Thrusters(vehicle, scenario.thruster_time_constant, scenario.voltage)
    environment = Environment(scenario.environment, scenario.seed, scenario.particulars)
    return Plant(hull, thrusters, environment, np.array(scenario.initial_position),
                 np.array([0.0, 0.0, scenario.initial_heading]))


def setpoint_vector(scenario: Scenario, planar: bool) -> np.ndarray:
    n, e, d = scenario.setpoint_position
    if planar:
        return np.array([n, e, scenario.setpoint_heading])
    return np.array([n, e, d, 0.0, 0.0, scenario.setpoint_heading])


def node_command(scenario: Scenario, vehicle: Vehicle, log_level: str = "warn") -> list[str]:
    binary = os.path.join(os.path.dirname(sys.executable), "allocator_node")
    command = [binary, "--ros-args", "--params-file", str(scenario.vehicle), "-p", "use_sim_time:=true",
               "-p", "trigger:=input", "-p", f"method:={scenario.method}", "--log-level", log_level]
    for name, value in scenario.parameters.items():
        command += ["-p", f"{name}:={json.dumps(value) if not isinstance(value, str) else value}"]
    return command


class Voltage:
    """The supply voltage at a sim time: the scenario's, then each ramp linearly to its end value."""

    def __init__(self, scenario: Scenario):
        self.start = scenario.voltage
        self.ramps = [e for e in scenario.events if e.kind == "battery_ramp"]

    def at(self, t: float) -> float | None:
        voltage = self.start
        for ramp in self.ramps:
            if voltage is None or t < ramp.time:
                continue
            share = 1.0 if ramp.duration == 0.0 else min(1.0, (t - ramp.time) / ramp.duration)
            voltage = voltage + share * (float(ramp.value) - voltage)
        return voltage


def run(scenario: Scenario, out: Path, live: float = 0.0, log=print) -> RunResult:
    """One closed-loop run of ``scenario`` with the node as a process; outputs into ``out``;
    with ``live`` > 0 a line of the live table every ``live`` simulated seconds."""
    import rclpy
    from geometry_msgs.msg import PoseStamped
    from nav_msgs.msg import Odometry
    from rclpy.executors import SingleThreadedExecutor
    from rosgraph_msgs.msg import Clock
    from sensor_msgs.msg import BatteryState

    from allocator_msgs.msg import AllocationStatus, ThrusterCommands

    from ..ros.conversions import array_to_wrench, wrench_to_array
    from .ctl import Controller, format_sample
    from .recording import Recording

    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    os.environ.setdefault("ROS_DOMAIN_ID", "42")
    out.mkdir(parents=True, exist_ok=True)
    vehicle = load_vehicle(scenario.vehicle)
    period_ns = round(1e9 / vehicle.rate_hz)
    period = period_ns * 1e-9
    plant = build_plant(scenario, vehicle)
    planar = plant.planar
    dofs = PLANAR if planar else list(range(6))
    controller = StationKeeping(scenario.gains)
    controller.settle(plant.eta, plant.environment_force())
    setpoint = setpoint_vector(scenario, planar)
    voltage = Voltage(scenario)
    steps = round(scenario.duration / period)
    trace = Trace(names=list(vehicle.names), period=period, horizontal=scenario.horizontal)
    faults: list[tuple[float, float]] = []

    with open(out / "node.log", "w") as node_log:
        process = subprocess.Popen(node_command(scenario, vehicle), stdout=node_log, stderr=subprocess.STDOUT,
                                   preexec_fn=_ends_with_parent)
    context = rclpy.Context()
    rclpy.init(context=context)
    node = rclpy.create_node("allocator_sim", context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    services = Controller(node)
    clock = node.create_publisher(Clock, "/clock", 10)
    odometry_publisher = node.create_publisher(Odometry, "odometry", 10)
    battery_publisher = node.create_publisher(BatteryState, "battery_state", 10)
    answers: dict[str, object] = {}
    node.create_subscription(AllocationStatus, "allocation_status", lambda m: answers.__setitem__("status", m), 10)
    node.create_subscription(ThrusterCommands, "thruster_commands", lambda m: answers.__setitem__("commands", m), 10)
    recording = Recording(out / "run.mcap")

    def exchange(t_ns: int, wrench: np.ndarray, required: bool) -> tuple | None:
        """Publish the clock at ``t_ns`` and the wrench; (status, commands, clock, wrench) once the
        node has answered that wrench at that time, None if not (``required``: raise)."""
        stamp = Clock()
        stamp.clock.sec, stamp.clock.nanosec = divmod(t_ns, 1_000_000_000)
        message = array_to_wrench(wrench)
        for attempt in range(RETRIES if required else 1):
            answers.clear()
            clock.publish(stamp)
            if attempt == 0 or not required:
                services.wrench.publish(message)
            deadline = time.monotonic() + ANSWER_TIMEOUT
            while time.monotonic() < deadline:
                executor.spin_once(timeout_sec=0.05)
                status, commands = answers.get("status"), answers.get("commands")
                if status is None or commands is None:
                    continue
                status_ns = status.header.stamp.sec * 1_000_000_000 + status.header.stamp.nanosec
                commands_ns = commands.header.stamp.sec * 1_000_000_000 + commands.header.stamp.nanosec
                if status_ns == t_ns == commands_ns and status.outcome != AllocationStatus.OUTCOME_STOPPED \
                        and np.allclose(wrench_to_array(status.requested), wrench, rtol=1e-9, atol=1e-9):
                    return status, commands, stamp, message
            if attempt == 1:
                services.wrench.publish(message)
        if required:
            raise SimulationError(f"allocator_node did not answer the wrench of t = {t_ns * 1e-9:.3f} s "
                                  f"(see {out / 'node.log'})")
        return None

    def stamped(t_ns: int) -> int | None:
        """The stamp [ns] of the node's latest answer if it is a sample (not a stop) at ``t_ns``."""
        status = answers.get("status")
        if status is None or status.outcome == AllocationStatus.OUTCOME_STOPPED:
            return None
        return t_ns if status.header.stamp.sec * 1_000_000_000 + status.header.stamp.nanosec == t_ns else None

    def warm_up(t_ns: int) -> int:
        """Zero requests, one clock step each from ``t_ns``, until the node has answered three
        in a row each in its own step; the time of the run's first step. A wrench that reached
        the node before its clock step waits for the next one; the node then answers on the
        clock alone, and that step sends no wrench, so that nothing waits at the first real
        step. The allocator stays at zero thrust."""
        in_step, started = 0, time.monotonic()
        while in_step < 3:
            if time.monotonic() - started > WARM_UP_TIMEOUT:
                raise SimulationError(f"allocator_node did not answer in lock-step (see {out / 'node.log'})")
            stamp = Clock()
            stamp.clock.sec, stamp.clock.nanosec = divmod(t_ns, 1_000_000_000)
            answers.clear()
            publish_battery(t_ns, voltage.at(0.0))
            clock.publish(stamp)
            deadline = time.monotonic() + 0.02
            while time.monotonic() < deadline:
                executor.spin_once(timeout_sec=0.005)
            if stamped(t_ns) is not None:                # a waiting wrench, answered on the clock
                in_step = 0
            else:
                answers.clear()
                services.wrench.publish(array_to_wrench(np.zeros(6)))
                deadline = time.monotonic() + 1.0
                while stamped(t_ns) is None and time.monotonic() < deadline:
                    executor.spin_once(timeout_sec=0.01)
                in_step = in_step + 1 if stamped(t_ns) is not None else 0
            t_ns += period_ns
        return t_ns

    def publish_battery(t_ns: int, value: float | None) -> BatteryState | None:
        if value is None:
            return None
        message = BatteryState(voltage=float(value), present=True)
        message.header.stamp.sec, message.header.stamp.nanosec = divmod(t_ns, 1_000_000_000)
        battery_publisher.publish(message)
        return message

    def apply(event: Event, state: dict) -> None:
        if event.kind == "fault":
            value = 0.0 if event.mode == "failed" else event.value
            if value is None:                           # stuck where it is
                value = float(plant.thrusters.angle[vehicle.names.index(event.actuator)])
            response = services.set_fault(event.actuator, event.mode, value)
            if not response.success:
                raise SimulationError(f"set_actuator_fault refused: {response.message}")
            plant.thrusters.set_fault(event.actuator, event.mode, value)
            state["fault_start"] = state.get("fault_start", event.time)
            log(f"sim: {event.time:7.1f} s  {response.message}")
        elif event.kind == "clear_faults":
            log(f"sim: {event.time:7.1f} s  {services.clear_faults().message}")
            plant.thrusters.clear_faults()
            if "fault_start" in state:
                faults.append((state.pop("fault_start"), event.time))
        elif event.kind == "parameter":
            result = services.set_parameters({event.name: event.value})
            if not result.successful:
                raise SimulationError(f"parameter {event.name} refused: {result.reason}")
            log(f"sim: {event.time:7.1f} s  {event.name} = {event.value}")

    try:
        started = time.monotonic()
        while services.wrench.get_subscription_count() == 0 or clock.get_subscription_count() == 0:
            executor.spin_once(timeout_sec=0.05)
            if process.poll() is not None or time.monotonic() - started > 30.0:
                raise SimulationError(f"allocator_node did not start (see {out / 'node.log'})")
        start_ns = warm_up(START_NS)

        pending = list(scenario.events)
        state: dict = {}
        wall_start = time.monotonic()
        printed = -math.inf
        for k in range(steps):
            t = k * period
            t_ns = start_ns + k * period_ns
            while pending and pending[0].time <= t + 1e-9:
                apply(pending.pop(0), state)
            supply = voltage.at(t)
            if supply is not None:
                plant.thrusters.set_voltage(supply)
            battery = publish_battery(t_ns, supply)
            pose = plant.pose()
            odometry = Odometry()
            odometry.header.stamp.sec, odometry.header.stamp.nanosec = divmod(t_ns, 1_000_000_000)
            odometry.header.frame_id, odometry.child_frame_id = "ned", "base_link"
            p, o = odometry.pose.pose.position, odometry.pose.pose.orientation
            p.x, p.y, p.z = (float(v) for v in pose.position)
            o.x, o.y, o.z, o.w = quaternion(*pose.attitude)
            v, w = odometry.twist.twist.linear, odometry.twist.twist.angular
            v.x, v.y, v.z = (float(x) for x in pose.velocity)
            w.x, w.y, w.z = (float(x) for x in pose.angular_velocity)
            odometry_publisher.publish(odometry)
            goal = PoseStamped()
            goal.header = odometry.header
            goal.pose.position.x, goal.pose.position.y, goal.pose.position.z = scenario.setpoint_position
            g = goal.pose.orientation
            g.x, g.y, g.z, g.w = quaternion(0.0, 0.0, scenario.setpoint_heading)

            wrench = np.zeros(6)
            wrench[dofs] = controller.wrench(plant.eta, plant.nu, setpoint)
            status, commands, stamp, message = exchange(t_ns, wrench, required=True)
            for topic, item in (("clock", stamp), ("battery", battery), ("odometry", odometry),
                                ("setpoint", goal), ("wrench", message), ("commands", commands),
                                ("status", status)):
                if item is not None:
                    recording.write(TOPICS[topic], recordable(item) if topic == "odometry" else item, t_ns)
            thrust, azimuth = np.array(commands.thrust), np.array(commands.azimuth)
            trace.add(t, pose.position, pose.attitude, scenario.setpoint_position, scenario.setpoint_heading,
                      thrust, azimuth, status.saturated, status.power, "fault_start" in state, status.voltage)
            if live > 0.0 and t - printed >= live - 1e-9:
                printed = t
                error = trace.position_errors()[-1]
                log(f"{t:6.1f} s  err {error:6.2f} m  " + format_sample(commands, status))
            controller.integrate(plant.eta, setpoint, period, wrench_to_array(status.unallocated)[dofs])
            plant.step(thrust, azimuth, period)
        wall = time.monotonic() - wall_start
    finally:
        recording.close()
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
        executor.shutdown()
        node.destroy_node()
        rclpy.try_shutdown(context=context)
    if "fault_start" in state:
        faults.append((state["fault_start"], scenario.duration))
    metrics = trace.metrics(vehicle)
    metrics["realtime_factor"] = scenario.duration / wall if wall > 0 else math.inf
    (out / "metrics.json").write_text(json.dumps({"scenario": scenario.name, "method": scenario.method,
                                                  "seed": scenario.seed, "duration": scenario.duration,
                                                  "metrics": metrics}, indent=2) + "\n")
    return RunResult(metrics, trace, vehicle, faults)


def _ends_with_parent() -> None:
    """In the node's process, before it starts: SIGTERM when the simulator's process ends
    (Linux's PR_SET_PDEATHSIG), so that a simulator killed mid-run leaves no node answering in
    its domain, where it would take the next run's wrenches for its own."""
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)


def metrics_from_recording(path: Path, vehicle: Vehicle, horizontal: bool) -> dict[str, float]:
    """The metrics of a run again, from its ``run.mcap`` alone (odometry, set-point, commands, status)."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    rows: dict[str, list] = {topic: [] for topic in ("/odometry", "/setpoint", "/thruster_commands",
                                                     "/allocation_status")}
    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        for _, channel, _, message in reader.iter_decoded_messages(topics=list(rows)):
            rows[channel.topic].append(message)
    position = np.array([[m.pose.pose.position.x, m.pose.pose.position.y, m.pose.pose.position.z]
                         for m in rows["/odometry"]])
    heading = np.array([euler(m.pose.pose.orientation.x, m.pose.pose.orientation.y, m.pose.pose.orientation.z,
                              m.pose.pose.orientation.w)[2] for m in rows["/odometry"]])
    setpoint = np.array([[m.pose.position.x, m.pose.position.y, m.pose.position.z] for m in rows["/setpoint"]])
    setpoint_heading = np.array([euler(m.pose.orientation.x, m.pose.orientation.y, m.pose.orientation.z,
                                       m.pose.orientation.w)[2] for m in rows["/setpoint"]])
    commands = rows["/thruster_commands"]
    return run_metrics(position=position, position_setpoint=setpoint, heading=heading,
                       heading_setpoint=setpoint_heading, horizontal=horizontal,
                       thrust=np.array([list(m.thrust) for m in commands]),
                       angles=np.array([list(m.azimuth) for m in commands]),
                       saturated=np.array([m.saturated for m in rows["/allocation_status"]]),
                       power_coefficients=np.array([a.power_coefficient for a in vehicle.actuators]),
                       thrust_scale=np.array([max(abs(a.thrust_min), abs(a.thrust_max)) for a in vehicle.actuators]),
                       period=1.0 / vehicle.rate_hz)


def _scenario(arguments: argparse.Namespace) -> Scenario:
    scenario = load_scenario(arguments.scenario)
    if arguments.duration_scale != 1.0:
        scenario = scenario.scaled(arguments.duration_scale)
    if getattr(arguments, "seed", None) is not None:
        from dataclasses import replace
        scenario = replace(scenario, seed=arguments.seed)
    return scenario


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    from . import sim_plots

    if argv[:1] == ["compare"]:
        parser = argparse.ArgumentParser(prog="allocator-sim compare",
                                         description="The same scenario under several methods, side by side.")
        parser.add_argument("scenario")
        parser.add_argument("--methods", nargs="+", required=True)
        parser.add_argument("--out", required=True)
        parser.add_argument("--seed", type=int, default=None)
        parser.add_argument("--duration-scale", type=float, default=1.0)
        arguments = parser.parse_args(argv[1:])
        try:
            scenario = _scenario(arguments)
            out = Path(arguments.out)
            results = {}
            vehicle = load_vehicle(scenario.vehicle)
            for method in arguments.methods:
                if method not in METHODS:
                    raise ValueError(f"--methods: {method!r} is not one of {', '.join(METHODS)}")
                unfit = METHODS[method].problems(vehicle)
                if unfit:
                    print(f"sim: {method} left out: it cannot serve this vehicle: {'; '.join(unfit)}", flush=True)
                    continue
                print(f"sim: {scenario.name} with {method}", flush=True)
                result = run(scenario.with_method(method), out / method)
                sim_plots.plot_run(out / method, result, scenario.with_method(method))
                results[method] = result
        except (ScenarioError, SimulationError, ValueError) as error:
            print(f"allocator-sim: {error}", file=sys.stderr)
            return 1
        table = sim_plots.compare_table(scenario, {m: r.metrics for m, r in results.items()})
        (out / "compare.md").write_text(table)
        sim_plots.plot_compare(out / "compare.png", scenario, results)
        print(table)
        print(f"sim: comparison written to {out.resolve()}")
        return 0

    parser = argparse.ArgumentParser(prog="allocator-sim", description=__doc__.split("\n\n")[0])
    parser.add_argument("scenario", help="scenario file (config/scenarios/*.yaml)")
    parser.add_argument("--out", required=True, help="output folder")
    parser.add_argument("--seed", type=int, default=None, help="environment seed (default: the scenario's)")
    parser.add_argument("--method", default=None, help="allocation method (default: the scenario's)")
    parser.add_argument("--duration-scale", type=float, default=1.0,
                        help="scale the duration and every event time (short runs)")
    parser.add_argument("--live", type=float, nargs="?", const=1.0, default=0.0, metavar="SECONDS",
                        help="a live table, one line every SECONDS of simulated time (default 1)")
    arguments = parser.parse_args(argv)
    try:
        scenario = _scenario(arguments)
        if arguments.method:
            scenario = scenario.with_method(arguments.method)
        out = Path(arguments.out)
        print(f"sim: {scenario.name}, {scenario.method}, {scenario.duration:g} s, seed {scenario.seed}", flush=True)
        result = run(scenario, out, live=arguments.live, log=lambda text: print(text, flush=True))
    except (ScenarioError, SimulationError, ValueError) as error:
        print(f"allocator-sim: {error}", file=sys.stderr)
        return 1
    sim_plots.plot_run(out, result, scenario)
    for name, value in result.metrics.items():
        print(f"sim: {name:20s} {value:.4g}")
    print(f"sim: outputs written to {out.resolve()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
