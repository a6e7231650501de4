"""What the diagnostics say about power per source (docs/power.md): the draw of the last sample
and the available power of every source, where the available power comes from, the actuators
the power holds back, the state of the bus ties, a restore ramp under way, the redundancy groups
failed. Pure functions, as in
:mod:`~allocator_pkg.ros.diagnostics`."""

from __future__ import annotations

from ..allocation.allocator import Allocator
from ..allocation.power_budget import PowerBudget
from ..allocation.result import AllocationResult


def power_diagnostics(allocator: Allocator, last: AllocationResult | None, supply: tuple[str, bool, bool] | None,
                      rejected: int) -> tuple[list[str], list[str], dict[str, str]]:
    """(errors, warnings, values) of the power per source; none without sources. ``supply`` is
    the power input's (topic, whether the capacities stand in, whether its messages stopped),
    ``rejected`` how many of its messages were rejected. An error for a stale input (the values
    held named); a warning for a failed group, a source at 0 kW and a source drawn to its limit."""
    budget, limit = allocator.power, allocator.power_limit
    if limit is None:
        return [], [], {}
    errors: list[str] = []
    warnings: list[str] = []
    values: dict[str, str] = {}
    available = budget.available
    draw = budget.draw(last.thrust, limit) if last is not None else 0.0 * available
    for source, kilowatts, most in zip(budget.sources, draw.tolist(), available.tolist()):
        values[f"power {source} [kW]"] = f"{kilowatts:.1f} of {most:g} available"
    if supply is not None:
        topic, fallback, stale = supply
        values["available power from"] = ("power.<source>.capacity (no power_available)" if fallback else
                                          f"{topic} (stale: held at {available_text(budget)})" if stale else topic)
        values["rejected power messages"] = str(rejected)
        if stale:
            errors.append(f"stale available power: nothing valid on {topic} for power_timeout, holding "
                          f"{available_text(budget)}")
    lost = [s for s, most in zip(budget.sources, available.tolist()) if most == 0.0]
    if lost:
        warnings.append(f"no power from {', '.join(lost)}")
    held = [f"{name} {bound:.6g} N" for name, narrowed, bound in
            zip(allocator.names, limit.limited.tolist(), allocator.power_bounds.tolist()) if narrowed]
    values["thrust limited by power"] = ", ".join(held) or "none"
    if last is not None and limit.holds(last.thrust):
        warnings.append("power-limited: thrust held back by the available power")
    if budget.ties.ties:
        values["bus ties"] = budget.ties.text()
    if budget.ramp.rising(budget.target):
        values["restoring available power"] = (f"{available_text(budget)} in use, rising at capacity / "
                                               f"{budget.ramp.seconds:g} s")
    values["failed redundancy groups"] = ", ".join(allocator.group_faults) or "none"
    if allocator.group_faults:
        warnings.append(f"redundancy group failed: {', '.join(allocator.group_faults)}")
    return errors, warnings, values


def available_text(budget: PowerBudget) -> str:
    """The available power in force, in words: ``swbd_a 1000 kW, swbd_b 0 kW``."""
    return ", ".join(f"{source} {kilowatts:g} kW"
                     for source, kilowatts in zip(budget.sources, budget.available.tolist()))
