"""What the node reports on /diagnostics: counters kept between reports, and the status built
from them as a pure function (no node, no clock), so that it is tested on its own."""

from __future__ import annotations

from dataclasses import dataclass

from diagnostic_msgs.msg import DiagnosticStatus, KeyValue

from .allocator import AllocationResult, Allocator
from .faults import FaultMode


@dataclass
class Counters:
    """What the diagnostics report; the per-period ones are reset every report."""

    rejected_wrenches: int = 0
    rejected_odometry: int = 0
    rejected_in_period: int = 0
    samples: int = 0
    saturated: int = 0
    fallbacks: int = 0
    max_solve_time: float = 0.0

    def count(self, result: AllocationResult) -> None:
        """One sample's outcome."""
        self.samples += 1
        self.saturated += result.saturated
        self.fallbacks += result.status.startswith("fallback")
        self.max_solve_time = max(self.max_solve_time, result.solve_time)

    def reset_period(self) -> None:
        self.samples = self.saturated = self.fallbacks = self.rejected_in_period = 0
        self.max_solve_time = 0.0


def diagnostic_status(name: str, hardware_id: str, allocator: Allocator, counters: Counters, stale: bool,
                      last: AllocationResult | None) -> DiagnosticStatus:
    """OK while allocating; WARN with faults, saturated samples, fallbacks, rejected inputs or
    unreachable DOFs; ERROR while the input is stale (zero thrust commanded)."""
    modes = allocator.modes()
    problems = []
    level = DiagnosticStatus.OK
    if stale:
        level = DiagnosticStatus.ERROR
        problems.append("stale wrench input: commanding zero thrust")
    warnings = [f"{actuator} {FaultMode(mode).name}" for actuator, mode in zip(allocator.names, modes) if mode]
    if counters.saturated:
        warnings.append(f"{counters.saturated} saturated samples")
    if counters.fallbacks:
        warnings.append(f"{counters.fallbacks} solver fallbacks")
    if counters.rejected_in_period:
        warnings.append(f"{counters.rejected_in_period} rejected inputs")
    warnings += allocator.warnings
    if warnings and level == DiagnosticStatus.OK:
        level = DiagnosticStatus.WARN
    problems += warnings
    status = DiagnosticStatus(level=level, name=name, hardware_id=hardware_id,
                              message="; ".join(problems) if problems else "allocating")
    values = {
        "method": allocator.method,
        "rate_hz": f"{allocator.vehicle.rate_hz:g}",
        "samples in period": str(counters.samples),
        "saturated in period": str(counters.saturated),
        "fallbacks in period": str(counters.fallbacks),
        "fallbacks total": str(allocator.stats.fallbacks),
        "solver setups": str(allocator.stats.solver_setups),
        "max solve time in period [s]": f"{counters.max_solve_time:.6f}",
        "rejected wrenches": str(counters.rejected_wrenches),
        "rejected odometry": str(counters.rejected_odometry),
        "stale input": str(stale).lower(),
    }
    if last is not None:
        values["solver status"] = last.status
        values["iterations"] = str(last.iterations)
    if allocator.vehicle.has_surfaces:
        values["speed [m/s]"] = f"{allocator.speed:g}"
        unavailable = [a.name for a, ok in zip(allocator.vehicle.actuators, last.available) if not ok] \
            if last is not None else []
        values["unavailable"] = ", ".join(unavailable) or "none"
    if allocator.notes:
        values["actuation"] = "; ".join(allocator.notes)
    for actuator, mode in zip(allocator.names, modes):
        values[f"mode {actuator}"] = FaultMode(mode).name
    status.values = [KeyValue(key=key, value=value) for key, value in values.items()]
    return status
