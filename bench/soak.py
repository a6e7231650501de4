"""make soak: ``allocator_node`` for minutes at 500 Hz under a 1 kHz wrench stream and one random
fault or parameter change every second, checking every command it publishes.

The node runs as its own process (``allocator_node``, log in build/soak_node.log). This process
publishes the wrench (an Ornstein-Uhlenbeck walk per controlled DOF around +-60 % of the DOF's
authority, so a part is unattainable, and every 10 s a NaN wrench or, for three node periods, a
1e12 one), drives the fault services and parameters, and checks each ThrusterCommands against
the configuration and faults in force at its stamp: finite; thrust within the (fault-adjusted)
limits; a FAILED actuator at zero thrust and its angle held; azimuths in the feasible sector
and, while thrusting, out of forbidden ones; thrust and azimuth steps within their rate limits.
While a change is in flight (from its request until its answer) either configuration's
limits are accepted and rate limits are not checked. Resident memory (VmRSS) of the node is
sampled every 10 s; the first minute, which also goes once through every kind of change, is
warm-up.

Fails (exit 1) on a crash, a non-zero exit, a silence of the node, a violation, a valid change
refused or an invalid one accepted, or RSS growth of 5 MB or more after the warm-up (not
measured in runs shorter than two minutes). Writes bench/results/soak.json.

Missed periods are counted as bench/probe.py counts them, and each late tick is put down to
what came right before it: a disturbance sent within ``DISTURBED`` (a fault, a parameter
change, a NaN or 1e12 wrench), else a sample on either side of it that took longer than
``SLOW_SAMPLE`` to allocate (a sample that long is as often the process held up, by the
machine or the garbage collector, as the solver at work: the pseudo-inverse's p50 is 0.13 ms
and its slowest samples take milliseconds), else nothing the soak did. Beside
the node, bench/ticker.py sleeps to the same 500 Hz deadlines in a process of its own for the
whole run: the share of periods the machine itself costs a deadline loop.

    .venv/bin/python bench/soak.py [--minutes 10] [--config config/dp_vessel.yaml] [--seed 1]
"""

import os

from allocator_pkg.ros.process import dds_environment

os.environ.update(dds_environment())

import argparse
import json
import math
import random
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from figures import memory_mb, percentiles, process_cpu_seconds
from geometry_msgs.msg import Wrench
from probe import Probe, node_process, ros_context, stamp_seconds, summarise
from rcl_interfaces.srv import SetParametersAtomically
from rclpy.context import Context
from rclpy.parameter import Parameter
from soak_records import RATE_HZ, Change, History, State, Tally, failures, late_ticks, memory_summary
from std_srvs.srv import Trigger

from allocator_msgs.msg import ActuatorFault, AllocationStatus, ThrusterCommands
from allocator_msgs.srv import SetActuatorFault
from allocator_pkg import METHODS, ConfigError, FaultMode, read_parameters, vehicle_from_parameters
from allocator_pkg.allocation.solve import check_method
from allocator_pkg.effectiveness.model import Model
from allocator_pkg.effectiveness.sectors import in_feasible_sector, in_forbidden_sector
from allocator_pkg.vehicle.angles import wrap

ROOT = Path(__file__).resolve().parents[1]
WRENCH_HZ = 1000.0
RSS_PERIOD = 10.0            # s between RSS samples
EXTREMES_PERIOD = 10.0       # s between a NaN wrench and a 1e12 wrench
EXTREME_SAMPLES = 6          # wrench periods a 1e12 wrench is held (three node periods)
TICKER = Path(__file__).with_name("ticker.py")
FIRST_ACTIONS = (*(f"method {name}" for name in reversed(METHODS)), "fault DEGRADED", "fault FAILED",
                 "fault STUCK", "fault NOMINAL", "clear", "thrust_max", "weights", "max_iter", "invalid")
"""Warm-up: every kind of change once, so that later allocations are not taken for a leak."""


class SoakProbe(Probe):
    """The benchmark probe with a random wrench stream and a check of every command."""

    def __init__(self, context: Context, history: History, seed: int, tally: Tally) -> None:
        super().__init__(context, WRENCH_HZ)
        self.history = history
        self.rng = random.Random(seed)
        self.tally = tally
        self.previous: ThrusterCommands | None = None
        vehicle = history.latest.vehicle
        model = Model.build(vehicle, 1.0 / RATE_HZ)
        self.authority = np.zeros(6)
        self.authority[model.dof_index] = model.dof_scale
        self.walk = np.zeros(6)
        self.last_extreme = time.monotonic()
        self.extreme_left = 0
        self.solve_by_method: dict[str, list[float]] = {}
        self.solve_at: dict[float, float] = {}      # header stamp -> solve time [s]

    def _publish(self) -> None:
        """One step of the walk (mean reversion over about 2 s), or an extreme wrench."""
        now = time.monotonic()
        dt = self.period
        self.walk += -self.walk * dt / 2.0 + np.array([self.rng.gauss(0.0, 1.0) for _ in range(6)]) * math.sqrt(dt)
        values = 0.6 * self.authority * self.walk
        if now - self.last_extreme > EXTREMES_PERIOD:
            self.last_extreme = now
            if self.rng.random() < 0.5:
                values = self.authority * math.nan
                self.tally.count("NaN wrench")
            else:
                self.extreme_left = EXTREME_SAMPLES
                self.tally.count("1e12 wrench")
        if self.extreme_left:
            self.extreme_left -= 1
            values = self.authority * 1e12
        wrench = Wrench()
        (wrench.force.x, wrench.force.y, wrench.force.z,
         wrench.torque.x, wrench.torque.y, wrench.torque.z) = (float(v) for v in values)
        self.published.append(time.time())
        self.wrench.publish(wrench)

    def _on_status(self, message: AllocationStatus) -> None:
        super()._on_status(message)
        self.solve_by_method.setdefault(message.method, []).append(message.solve_time)
        self.solve_at[stamp_seconds(message)] = message.solve_time
        requested = message.requested
        if max(abs(v) for v in (requested.force.x, requested.force.y, requested.force.z,
                                requested.torque.x, requested.torque.y, requested.torque.z)) > 1e11:
            self.tally.extreme_allocated += 1
        achieved = (message.achieved.force.x, message.achieved.force.y, message.achieved.torque.z)
        if not all(math.isfinite(v) for v in achieved):
            self.tally.violation(f"t={stamp_seconds(message):.3f}: non-finite achieved wrench {achieved}")

    def _on_commands(self, message: ThrusterCommands) -> None:
        super()._on_commands(message)
        self.check(message)
        self.previous = message

    def check(self, message: ThrusterCommands) -> None:
        """Every output finite and within the limits in force; steps within rate limits."""
        self.tally.checked += 1
        stamp = stamp_seconds(message)
        period = 1.0 / RATE_HZ
        before, after, flight = self.history.at(stamp, period)
        previous = self.previous
        steps = 1
        if previous is not None:
            gap = (stamp - stamp_seconds(previous)) / period
            steps = 1 if gap <= 1.2 else math.floor(gap) + 1      # a late tick then a lost one: 2 steps
        for i, actuator in enumerate(after.vehicle.actuators):
            thrust, azimuth, command, mode = message.thrust[i], message.azimuth[i], message.command[i], message.mode[i]
            where = f"t={stamp:.3f} {actuator.name}"
            if not (math.isfinite(thrust) and math.isfinite(azimuth) and math.isfinite(command)):
                self.tally.violation(f"{where}: non-finite output {thrust}, {azimuth}, {command}")
                continue
            (low_a, high_a), (low_b, high_b) = before.limits(i), after.limits(i)
            low, high = min(low_a, low_b), max(high_a, high_b)
            slack = 1e-6 * max(1.0, abs(actuator.thrust_max))
            if not low - slack <= thrust <= high + slack:
                self.tally.violation(f"{where}: thrust {thrust} outside [{low}, {high}]")
            if mode == FaultMode.FAILED and abs(thrust) > slack:
                self.tally.violation(f"{where}: FAILED but thrust {thrust}")
            rotation = actuator.rotation
            if rotation is not None:
                if not in_feasible_sector(rotation, azimuth):
                    self.tally.violation(f"{where}: azimuth {azimuth} outside the feasible sector")
                if abs(thrust) > slack and in_forbidden_sector(rotation, azimuth):
                    self.tally.violation(f"{where}: thrust {thrust} at {azimuth} rad, in a forbidden sector")
            if previous is None or flight or mode != previous.mode[i]:
                continue
            dt = steps * period
            step = thrust - previous.thrust[i]
            if actuator.thrust_rate_max > 0 and abs(step) > actuator.thrust_rate_max * dt * (1 + 1e-6) + slack:
                self.tally.violation(f"{where}: thrust step {step} over {steps} samples")
            if rotation is not None:
                turn = abs(wrap(azimuth - previous.azimuth[i]))
                held = mode in (FaultMode.FAILED, FaultMode.STUCK)
                if held and turn > 1e-9:
                    self.tally.violation(f"{where}: {FaultMode(mode).name} but turned {turn} rad")
                if rotation.rate_max > 0 and turn > rotation.rate_max * dt + 1e-6:
                    self.tally.violation(f"{where}: azimuth step {turn} over {steps} samples")


class Disturber:
    """One fault or parameter change per call, through the node's services."""

    def __init__(self, probe: SoakProbe, parameters: dict, seed: int, tally: Tally) -> None:
        node = probe.node
        self.probe, self.tally, self.parameters = probe, tally, parameters
        self.rng = random.Random(seed)
        self.fault = node.create_client(SetActuatorFault, "thrust_allocator/set_actuator_fault")
        self.clear = node.create_client(Trigger, "thrust_allocator/clear_faults")
        self.set_parameters = node.create_client(SetParametersAtomically,
                                                 "thrust_allocator/set_parameters_atomically")
        self.pending: list = []
        self.actions = iter(FIRST_ACTIONS)

    def wait_for_services(self) -> None:
        for client in (self.fault, self.clear, self.set_parameters):
            if not client.wait_for_service(timeout_sec=30.0):
                raise TimeoutError(f"{client.srv_name} did not appear")

    def act(self) -> None:
        """Send the next warm-up change, or a random one."""
        action = next(self.actions, None) or self.rng.choice(
            ("fault", "fault", "clear", "method", "weights", "thrust_max", "max_iter", "invalid"))
        kind, _, detail = action.partition(" ")
        state = self.probe.history.latest
        actuators = state.vehicle.actuators
        if kind == "fault":
            self.send_fault(state, detail or None)
        elif kind == "clear":
            self.send("clear faults", self.clear, Trigger.Request(), State(state.vehicle, {}), expect=True)
        elif kind == "method":
            self.change_parameters("method", {"method": detail or self.rng.choice(list(METHODS))}, state)
        elif kind == "weights":
            self.change_parameters("weights", {"weights.minimax": self.rng.uniform(0.0, 10.0),
                                               "weights.azimuth_change": self.rng.uniform(0.0, 10.0)}, state)
        elif kind == "thrust_max":
            actuator = self.rng.choice([a for a in actuators if a.thrust_max > 0])
            nominal = self.parameters[f"actuators.{actuator.name}.thrust_max"]
            self.change_parameters("thrust_max", {f"actuators.{actuator.name}.thrust_max":
                                                  nominal * self.rng.uniform(0.5, 1.0)}, state)
        elif kind == "max_iter":
            self.change_parameters("max_iter", {"solver.max_iter": self.rng.randint(50, 4000)}, state)
        else:
            actuator = self.rng.choice(actuators)
            self.change_parameters("invalid", {"weights.minimax": 1.0,
                                               f"actuators.{actuator.name}.thrust_max": -1.0}, state)

    def send_fault(self, state: State, wanted: str | None) -> None:
        """A fault of the ``wanted`` mode (or a random one) on a random actuator; STUCK at the
        angle the actuator was last commanded to."""
        actuators = state.vehicle.actuators
        actuator = self.rng.choice([a for a in actuators if a.rotatable] if wanted == "STUCK" else actuators)
        modes = [FaultMode.NOMINAL, FaultMode.DEGRADED, FaultMode.FAILED]
        if actuator.rotatable:
            modes.append(FaultMode.STUCK)
        mode = FaultMode[wanted] if wanted else self.rng.choice(modes)
        fault = ActuatorFault(actuator=actuator.name, mode=int(mode))
        efficiency = {FaultMode.FAILED: 0.0}.get(mode, 1.0)
        if mode == FaultMode.DEGRADED:
            fault.efficiency = efficiency = self.rng.uniform(0.1, 1.0)
        if mode == FaultMode.STUCK:
            fault.azimuth = self.probe.previous.azimuth[actuators.index(actuator)]
        after = State(state.vehicle, {**state.efficiency, actuator.name: efficiency})
        self.send(f"fault {mode.name}", self.fault, SetActuatorFault.Request(fault=fault), after, expect=True)

    def change_parameters(self, action: str, values: dict, state: State) -> None:
        candidate = {**self.parameters, **values}
        try:
            vehicle = vehicle_from_parameters(candidate)
            check_method(vehicle.method, vehicle)
            after, expect = State(vehicle, state.efficiency), True
        except ConfigError:
            after, expect = state, False
        request = SetParametersAtomically.Request(
            parameters=[Parameter(name, value=value).to_parameter_msg() for name, value in values.items()])
        self.send(f"parameters {action}", self.set_parameters, request, after, expect,
                  on_success=lambda: self.parameters.update(values))

    def send(self, action: str, client, request, after: State, expect: bool, on_success=None) -> None:
        """Send; the answer must report ``expect``. The probe treats the change as in flight until then."""
        self.tally.count(action)
        change = Change(sent=time.time(), state=after)
        self.probe.history.changes.append(change)
        future = client.call_async(request)
        self.pending.append(future)

        def answered(done) -> None:
            self.pending.remove(done)
            change.answered = time.time()
            response = done.result()
            success = response.result.successful if hasattr(response, "result") else response.success
            if success and on_success is not None:
                on_success()
            if not success:
                self.probe.history.forget(change)
            if expect and not success:
                self.tally.refused.append(f"{action}: {getattr(response, 'message', None) or response.result.reason}")
            if not expect and success:
                self.tally.accepted_invalid.append(action)

        future.add_done_callback(answered)


def soak(config: Path, minutes: float, seed: int, log: Path) -> dict:
    """Run the soak and return its figures."""
    parameters = read_parameters(config)
    tally = Tally()
    history = History(State(vehicle_from_parameters(parameters), {}))
    seconds = 60.0 * minutes
    memory: list[tuple[float, dict[str, float]]] = []
    crash = None
    log.parent.mkdir(parents=True, exist_ok=True)
    with node_process(config, RATE_HZ, output=log) as process, ros_context() as context:
        probe = SoakProbe(context, history, seed, tally)
        disturber = Disturber(probe, parameters, seed + 1, tally)
        ticker = None
        try:
            probe.wait_for_node()
            disturber.wait_for_services()
            probe.start_publishing()
            ticker = subprocess.Popen([sys.executable, str(TICKER), str(seconds), str(RATE_HZ)],
                                      stdout=subprocess.PIPE, text=True, env=os.environ)
            begin = time.monotonic()
            start, cpu_start = time.time(), process_cpu_seconds(process.pid)
            next_action, next_memory = begin + 1.0, begin
            while (now := time.monotonic()) < begin + seconds:
                if process.poll() is not None:
                    crash = f"allocator_node exited with {process.returncode} after {now - begin:.0f} s"
                    break
                if now >= next_memory:
                    try:
                        memory.append((round(now - begin, 1), memory_mb(process.pid)))
                    except (OSError, ProcessLookupError):
                        continue
                    next_memory += RSS_PERIOD
                if now >= next_action:
                    disturber.act()
                    next_action += 1.0
                probe.executor.spin_once(timeout_sec=0.01)
            end = time.time()
            cpu_end = process_cpu_seconds(process.pid) if process.poll() is None else cpu_start
            probe.stop_publishing()
            probe.spin_for(1.0)
            unanswered = len(disturber.pending)
            figures = summarise(probe, RATE_HZ, (start, end), 100.0 * (cpu_end - cpu_start) / (end - start))
            receipts = np.array([receipt for receipt, _ in probe.commands if start <= receipt < end])
            longest_silence = float(np.max(np.diff(np.concatenate(([start], receipts, [end])))))
            by_method = {method: {"samples": len(times),
                                  **percentiles([t * 1e3 for t in times], 50, 99, maximum=True)}
                         for method, times in probe.solve_by_method.items()}
            stamps = [stamp for receipt, stamp in probe.commands if start <= receipt < end]
            causes = late_ticks(stamps, probe.solve_at, tally.times)
            reference = json.loads(ticker.communicate(timeout=60.0)[0]) if crash is None else None
        finally:
            if ticker is not None and ticker.poll() is None:
                ticker.kill()
                ticker.wait()
            probe.close()
    exit_code = process.returncode
    figures.pop("publish_to_commands_ms", None)
    return {
        "config": str(config.relative_to(ROOT)) if config.is_relative_to(ROOT) else str(config),
        "minutes": minutes, "seed": seed, "rate_hz": RATE_HZ, "wrench_hz": WRENCH_HZ,
        "commands_checked": tally.checked, "actions": tally.actions, "extreme_allocated": tally.extreme_allocated,
        "valid_changes_refused": tally.refused, "invalid_changes_accepted": tally.accepted_invalid,
        "unanswered": unanswered, "violations": tally.violations, "violation_examples": tally.examples,
        "crash": crash, "exit_code": exit_code, "longest_silence_s": round(longest_silence, 3),
        "rss_mb": memory_summary(memory), "solve_ms_by_method": by_method, **figures,
        "missed_by_cause": causes, "bare_ticker": reference,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--minutes", type=float, default=10.0, help="duration (default: 10)")
    parser.add_argument("--config", type=Path, default=ROOT / "config" / "dp_vessel.yaml",
                        help="vehicle params file (default: config/dp_vessel.yaml)")
    parser.add_argument("--seed", type=int, default=1, help="random seed of wrenches and changes (default: 1)")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "soak.json")
    arguments = parser.parse_args(argv)
    result = soak(arguments.config.resolve(), arguments.minutes, arguments.seed, ROOT / "build" / "soak_node.log")
    arguments.out.parent.mkdir(parents=True, exist_ok=True)
    arguments.out.write_text(json.dumps(result, indent=1) + "\n")
    rss = result["rss_mb"]
    memory = (f"RSS {rss['baseline']:.1f} MB after warm-up, growth {rss['growth']} MB (max {rss['max_growth']}, "
              f"slope {rss['slope_mb_per_min']} MB/min)" if rss["growth"] is not None
              else "RSS growth not measured (run shorter than two minutes)")
    bare = (f"a bare {RATE_HZ:g} Hz loop beside it missed {result['bare_ticker']['missed_percent']} %"
            if result["bare_ticker"] else "no bare loop figure (the run ended early)")
    print(f"soak: {result['commands_checked']} commands checked over {arguments.minutes:g} min at "
          f"{result['achieved_hz']} Hz; missed {result['missed']} ({result['missed_percent']} %), "
          f"lost {result['lost']} ({result['lost_percent']} %); longest silence {result['longest_silence_s']} s; "
          f"{memory}; {result['extreme_allocated']} samples of a 1e12 wrench; actions {result['actions']}; "
          f"missed by cause {result['missed_by_cause']}; {bare}; results in {arguments.out}")
    reasons = failures(result)
    for reason in reasons:
        print(f"soak: FAIL: {reason}", file=sys.stderr)
    return 1 if reasons else 0


if __name__ == "__main__":
    sys.exit(main())
