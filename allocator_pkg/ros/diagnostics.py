"""What the node reports on /diagnostics: counters kept between reports, and the statuses
built from them as pure functions (no node, no clock), so that they are tested on their own.
A rejected input is counted here and logged at most once per :data:`LOG_THROTTLE` seconds.

Every status is named after the node's full name, so that allocators in several namespaces
stay apart in a diagnostic aggregator: ``/rov1/thrust_allocator: thrust allocation`` for the
allocation, ``/rov1/thrust_allocator: actuator <name>`` for each actuator."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

from diagnostic_msgs.msg import DiagnosticStatus, KeyValue

from ..allocation.allocator import Allocator
from ..allocation.result import AllocationResult
from ..effectiveness.faults import Fault, FaultMode
from ..effectiveness.model import AT_LIMIT
from ..solvers.outcome import Outcome
from .power_report import power_diagnostics

LOG_THROTTLE = 5.0           # s between two log lines of one kind of rejected input
ACTUATOR_LEVELS = {FaultMode.NOMINAL: DiagnosticStatus.OK, FaultMode.DEGRADED: DiagnosticStatus.WARN,
                   FaultMode.STUCK: DiagnosticStatus.WARN, FaultMode.FAILED: DiagnosticStatus.ERROR}


@dataclass
class Counters:
    """What the diagnostics report; the per-period ones are reset every report."""

    rejected_wrenches: int = 0
    rejected_frames: int = 0
    rejected_odometry: int = 0
    rejected_battery: int = 0
    rejected_power: int = 0
    rejected_in_period: int = 0
    samples: int = 0
    saturated: int = 0
    fallbacks: int = 0
    max_solve_time: float = 0.0
    short: set[str] = field(default_factory=set)

    def count(self, result: AllocationResult) -> None:
        """One sample: its outcome, and the DOFs it fell short in."""
        self.samples += 1
        self.saturated += result.saturated
        self.fallbacks += result.outcome is Outcome.FALLBACK
        self.max_solve_time = max(self.max_solve_time, result.solve_time)
        self.short.update(result.short)

    def reset_period(self) -> None:
        self.samples = self.saturated = self.fallbacks = self.rejected_in_period = 0
        self.max_solve_time = 0.0
        self.short = set()


def diagnostic_statuses(node_name: str, allocator: Allocator, counters: Counters, stale: bool,
                        last: AllocationResult | None, foreign: Sequence[str] = (),
                        battery: tuple[str, bool] | None = None,
                        power: tuple[str, bool, bool] | None = None) -> list[DiagnosticStatus]:
    """The allocation's status, then one per actuator (:func:`actuator_status`)."""
    statuses = [allocation_status(node_name, allocator, counters, stale, last, foreign, battery, power)]
    if last is not None:
        low, high = allocator.ranges
        faults = allocator.faults
        statuses += [actuator_status(node_name, allocator, i, last, (low[i], high[i]), faults.get(name))
                     for i, name in enumerate(allocator.names)]
    return statuses


def allocation_status(node_name: str, allocator: Allocator, counters: Counters, stale: bool,
                      last: AllocationResult | None, foreign: Sequence[str] = (),
                      battery: tuple[str, bool] | None = None,
                      power: tuple[str, bool, bool] | None = None) -> DiagnosticStatus:
    """OK while allocating; WARN with faults, saturated samples (and the DOFs short), fallbacks,
    rejected inputs, publishers of the wrong type, unreachable DOFs (of the configuration, or of
    the working actuators under the faults in force) or no battery voltage (the thrust limits at
    nominal_voltage); ERROR while the wrench input is stale (zero thrust
    commanded) or the available power is (held, not known).
    ``battery`` is (topic, whether the nominal voltage stands in) when the thrust tables follow
    a battery voltage; ``power`` the power input's report, with power sources
    (:func:`~allocator_pkg.ros.power_report.power_diagnostics`)."""
    modes = allocator.modes()
    problems = []
    level = DiagnosticStatus.OK
    if stale:
        level = DiagnosticStatus.ERROR
        problems.append("stale wrench input: commanding zero thrust")
    warnings = [f"{actuator} {FaultMode(mode).name}" for actuator, mode in zip(allocator.names, modes) if mode]
    short = [dof for dof in allocator.dofs if dof in counters.short]
    if counters.saturated:
        warnings.append(f"{counters.saturated} saturated samples (short in {', '.join(short)})")
    if counters.fallbacks:
        warnings.append(f"{counters.fallbacks} solver fallbacks")
    if counters.rejected_in_period:
        warnings.append(f"{counters.rejected_in_period} rejected inputs")
    if foreign:
        warnings.append(f"wrench_command publishers of another type: {', '.join(foreign)}")
    if battery is not None and battery[1]:
        warnings.append(f"no valid battery voltage on {battery[0]}: thrust limits at nominal_voltage "
                        f"{allocator.voltage:g} V")
    power_errors, power_warnings, power_values = power_diagnostics(allocator, last, power, counters.rejected_power)
    if power_errors:
        level = DiagnosticStatus.ERROR
        problems += power_errors
    warnings += power_warnings
    warnings += allocator.warnings
    warnings += allocator.lost_reach
    if warnings and level == DiagnosticStatus.OK:
        level = DiagnosticStatus.WARN
    problems += warnings
    status = DiagnosticStatus(level=level, name=f"{node_name}: thrust allocation", hardware_id=node_name,
                              message="; ".join(problems) if problems else "allocating")
    values = {
        "method": allocator.method,
        "rate_hz": f"{allocator.vehicle.rate_hz:g}",
        "samples in period": str(counters.samples),
        "saturated in period": str(counters.saturated),
        "short DOFs in period": ", ".join(short) or "none",
        "fallbacks in period": str(counters.fallbacks),
        "fallbacks total": str(allocator.stats.fallbacks),
        "solver setups": str(allocator.stats.solver_setups),
        "max solve time in period [s]": f"{counters.max_solve_time:.6f}",
        "rejected wrenches": str(counters.rejected_wrenches),
        "rejected wrench frames": str(counters.rejected_frames),
        "rejected odometry": str(counters.rejected_odometry),
        "rejected battery states": str(counters.rejected_battery),
        "stale input": str(stale).lower(),
        "wrong-type publishers": ", ".join(foreign) or "none",
    }
    if last is not None:
        values["solver status"] = last.status
        values["iterations"] = str(last.iterations)
    if allocator.vehicle.has_surfaces:
        values["speed [m/s]"] = f"{allocator.speed:g}"
        unavailable = [a.name for a, ok in zip(allocator.vehicle.actuators, last.available) if not ok] \
            if last is not None else []
        values["unavailable"] = ", ".join(unavailable) or "none"
    if allocator.voltage is not None:
        values["voltage [V]"] = f"{allocator.voltage:g}"
    if battery is not None:
        values["voltage source"] = "nominal_voltage (no battery voltage)" if battery[1] else battery[0]
    values.update(power_values)
    if allocator.notes:
        values["actuation"] = "; ".join(allocator.notes)
    values["lost to faults"] = "; ".join(allocator.lost_reach) or "none"
    for actuator, mode in zip(allocator.names, modes):
        values[f"mode {actuator}"] = FaultMode(mode).name
    status.values = [KeyValue(key=key, value=value) for key, value in values.items()]
    return status


def actuator_status(node_name: str, allocator: Allocator, index: int, last: AllocationResult,
                    limits: tuple[float, float], fault: Fault | None) -> DiagnosticStatus:
    """One actuator: OK when NOMINAL, WARN when DEGRADED (its efficiency) or STUCK (its angle),
    ERROR when FAILED (its fault now, which a service may have changed since ``last``); its
    last thrust as a fraction of the limit in force on that side (fault and, for a control
    surface, speed included)."""
    actuator = allocator.vehicle.actuators[index]
    mode = FaultMode.NOMINAL if fault is None else fault.mode
    thrust = float(last.thrust[index])
    limit = limits[1] if thrust >= 0.0 else limits[0]
    fraction = abs(thrust / limit) if limit != 0.0 else 0.0
    words = [mode.name]
    values = {"mode": mode.name, "thrust [N]": f"{thrust:.6g}", "fraction of limit": f"{fraction:.3f}",
              "limits in force [N]": f"[{limits[0] + 0.0:.6g}, {limits[1] + 0.0:.6g}]"}
    if mode == FaultMode.DEGRADED:
        words.append(f"efficiency {fault.efficiency:g}")
        values["efficiency"] = f"{fault.efficiency:g}"
    if mode == FaultMode.STUCK:
        words.append(f"stuck at {fault.angle:g} rad ({math.degrees(fault.angle):.1f} deg)")
        values["stuck angle [rad]"] = f"{fault.angle:g}"
    if actuator.rotatable:
        values["azimuth [rad]"] = f"{float(last.azimuth[index]):.6g}"
    if not last.available[index]:
        words.append("unavailable")
    elif limit != 0.0 and fraction >= 1.0 - AT_LIMIT:
        words.append("at its limit")
    words.append(f"{100.0 * fraction:.0f} % of its limit")
    status = DiagnosticStatus(level=ACTUATOR_LEVELS[mode], name=f"{node_name}: actuator {actuator.name}",
                              hardware_id=node_name, message=", ".join(words))
    status.values = [KeyValue(key=key, value=value) for key, value in values.items()]
    return status
