"""How much of a short source's available power the allocation uses (docs/power.md).

A sweep of request directions x magnitudes on dp_vessel with a source short (a redundancy
group failed, the other switchboard at reduced power) and on a split-fed variant: each request
held until the thrust and angles settle, then the fraction of every short source's available
power the sample draws, and how far along the request's direction the achieved wrench goes,
against an independent reference: the largest scale s* along the direction that the exact power
constraint sum_i w_ij P_i |f_i|^(3/2) <= A_j allows (with the same thrust ranges, derating and
forbidden sectors), from scipy's SLSQP over (s, thrust, azimuth angle), started from many
angles. Also the time of a power-limited sample, and how many samples cut a thrust by more than
its rate step (none: the power rows move no bound between samples).

    python bench/power_use.py [--samples 300] [--methods qp,nonlinear]
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

from allocator_pkg import Allocator, read_parameters, vehicle_from_parameters
from allocator_pkg.allocation.drive_power import KW
from allocator_pkg.effectiveness.faults import static_ranges
from allocator_pkg.vehicle.config import DOF_NAMES

ROOT = Path(__file__).resolve().parents[1]
DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
SCALE = {"surge": 1e6, "sway": 6e5, "yaw": 3e7}
"""[N, N, Nm] The units a request direction is a unit vector in."""
MAGNITUDES = (0.8, 1.0, 1.5)
"""Requests at these multiples of the reference's largest attainable scale s*."""


def vessel(split: bool):
    parameters = read_parameters(DP_VESSEL)
    if split:
        parameters.update({"actuators.azimuth_stbd.feeds": ["swbd_a", "swbd_b"],
                           "actuators.azimuth_stbd.feed_shares": [0.7, 0.3]})
    return vehicle_from_parameters(parameters)


CASES = {
    "group_b_failed_a_1000kW": (False, "switchboard_b", {"swbd_a": 1000.0}),
    "a_1000kW": (False, None, {"swbd_a": 1000.0}),
    "split_a_1200kW_b_2000kW": (True, None, {"swbd_a": 1200.0, "swbd_b": 2000.0}),
}


def directions() -> list[np.ndarray]:
    """Unit vectors in (surge, sway, yaw) scaled units: eight in the horizontal plane, pure yaw
    both ways and four mixed."""
    planar = [np.array([math.cos(a), math.sin(a), 0.0]) for a in np.arange(8) * math.pi / 4]
    mixed = [np.array(v, dtype=float) / np.linalg.norm(v) for v in
             ([0, 0, 1], [0, 0, -1], [1, 0.5, 0.5], [1, -0.5, -0.5], [-1, 0.5, -0.5], [0.3, 1, 1])]
    return planar + mixed


def allowed_angles(actuator) -> tuple[float, float]:
    """One interval of angles [low, high] the azimuth may push in (dp_vessel: at most one
    forbidden sector, on a full circle)."""
    sectors = actuator.rotation.forbidden_sectors
    if not sectors:
        return -math.pi, math.pi
    (low, high), = sectors
    return high, low + 2.0 * math.pi


def reference_scale(allocator: Allocator, direction: np.ndarray, starts: int = 24, seed: int = 0) -> float:
    """Largest s with T(alpha) f = s D direction (D the SCALE units) under the exact power
    constraint per source, the thrust ranges in force without the power bounds (faults and the
    feed limit's derating) and the forbidden sectors: SLSQP from ``starts`` random angles."""
    vehicle, budget, limit = allocator.vehicle, allocator.power, allocator.power_limit
    rows = [DOF_NAMES.index(d) for d in vehicle.dofs]
    target = direction * np.array([SCALE[d] for d in vehicle.dofs])
    r = len(vehicle.actuators)
    rotatable = [i for i, a in enumerate(vehicle.actuators) if a.rotation is not None]
    live = budget.shares * (budget.available > 0)[None, :]
    derated = np.where(budget.fed, live.sum(axis=1) ** (2 / 3) * budget.rated_thrust, np.inf)
    low, high = (np.maximum(b, -derated) if k == 0 else np.minimum(b, derated)
                 for k, b in enumerate(allocator_static_ranges(allocator)))
    available = budget.available * KW
    weights = limit.weights
    norm = np.maximum(high - low, 1.0)

    def unpack(x):
        thrust = x[1:1 + r] * norm
        angle = np.zeros(r)
        angle[rotatable] = x[1 + r:]
        return x[0], thrust, angle

    def wrench(x):
        s, thrust, angle = unpack(x)
        columns = np.array([[math.cos(angle[i]), math.sin(angle[i])] if a.rotation is not None
                            else a.direction[:2] for i, a in enumerate(vehicle.actuators)])
        positions = np.array([a.position[:2] for a in vehicle.actuators])
        forces = columns * thrust[:, None]
        full = np.array([forces[:, 0].sum(), forces[:, 1].sum(), 0.0, 0.0, 0.0,
                         float(np.sum(positions[:, 0] * forces[:, 1] - positions[:, 1] * forces[:, 0]))])
        return (full[rows] - s * target) / np.array([SCALE[d] for d in vehicle.dofs])

    def power_left(x):
        _, thrust, _ = unpack(x)
        draw = (budget.in_force.forward * (thrust ** 2 + 1e-6) ** 0.75) @ weights
        return np.where(available > 0, 1.0 - draw / np.maximum(available, 1.0), 0.0)

    bounds = [(0.0, None)] + [(lo / n, hi / n) for lo, hi, n in zip(low, high, norm)]
    bounds += [allowed_angles(vehicle.actuators[i]) for i in rotatable]
    rng = np.random.default_rng(seed)
    best = 0.0
    for _ in range(starts):
        x0 = np.concatenate([[0.0], [0.3 * rng.uniform(lo, hi) for lo, hi in bounds[1:1 + r]],
                             [rng.uniform(*b) for b in bounds[1 + r:]]])
        solution = minimize(lambda x: -x[0], x0, method="SLSQP", bounds=bounds,
                            constraints=[{"type": "eq", "fun": wrench}, {"type": "ineq", "fun": power_left}],
                            options={"maxiter": 300, "ftol": 1e-10})
        if solution.success and np.max(np.abs(wrench(solution.x))) < 1e-6 and np.min(power_left(solution.x)) > -1e-6:
            best = max(best, float(solution.x[0]))
    return best


def allocator_static_ranges(allocator: Allocator) -> tuple[np.ndarray, np.ndarray]:
    """The thrust ranges faults, speed and voltage leave (no power bound)."""
    return static_ranges(allocator.vehicle, allocator.fault_set, allocator.speed, allocator.voltage)


def settled(allocator: Allocator, tau: np.ndarray, samples: int) -> tuple[object, float, int, float]:
    """The last of ``samples`` allocations of ``tau`` from rest; the mean time of the
    power-limited ones [s]; how many samples cut some thrust by more than its rate step (the
    power's ranges win over the rate limit); and the largest change of thrust over the last
    fifth of the samples, as a share of the rated thrust (0 when it has settled)."""
    allocator.reset()
    step = np.array([a.thrust_rate_max for a in allocator.vehicle.actuators]) * allocator.dt
    rated = allocator.power.rated_thrust
    spent, limited, cuts, wobble, previous = 0.0, 0, 0, 0.0, np.zeros(len(step))
    for k in range(samples):
        start = time.perf_counter()
        result = allocator.allocate(tau)
        elapsed = time.perf_counter() - start
        if allocator.power.reading(result.thrust, allocator.power_limit).limited:
            spent, limited = spent + elapsed, limited + 1
        change = np.abs(result.thrust - previous)
        cuts += bool(np.any(change > step * (1 + 1e-6)))
        if k >= samples - samples // 5:
            wobble = max(wobble, float(np.max(change / rated)))
        previous = result.thrust
    return result, spent / limited if limited else math.nan, cuts, wobble


def run(samples: int, methods: list[str]) -> None:
    for name, (split, group, available) in CASES.items():
        for method in methods:
            allocator = Allocator(vessel(split), method=method)
            if group:
                allocator.set_group_fault(group)
            allocator.set_available_power(available)
            limit = allocator.power_limit
            short = [j for j, a in enumerate(allocator.power.available) if a > 0 and (
                limit.rows.short()[j] if limit.rows is not None else np.any(limit.limited & (limit.weights[:, j] > 0)))]
            used, along, times = {k: [] for k in MAGNITUDES}, {k: [] for k in MAGNITUDES}, []
            cut, wobbles = 0, []
            for direction in directions():
                s_star = reference_scale(allocator, direction)
                if s_star < 1e-6:                           # the direction is out of reach
                    continue
                for k in MAGNITUDES:
                    tau = np.zeros(6)
                    for dof, v in zip(allocator.vehicle.dofs, direction):
                        tau[DOF_NAMES.index(dof)] = k * s_star * v * SCALE[dof]
                    result, spent, cuts, wobble = settled(allocator, tau, samples)
                    times.append(spent)
                    cut, wobbles = cut + cuts, [*wobbles, wobble]
                    draw = allocator.power.draw(result.thrust, allocator.power_limit)
                    if result.saturated:
                        used[k] += [draw[j] / allocator.power.available[j] for j in short]
                    achieved = np.array([result.achieved[DOF_NAMES.index(d)] / SCALE[d]
                                         for d in allocator.vehicle.dofs])
                    along[k].append(min(float(achieved @ direction) / (s_star * min(k, 1.0)), 1.0))
            print(f"{name:26s} {method:10s} " + "  ".join(
                f"k={k}: used {np.mean(used[k]) if used[k] else float('nan'):.3f} (n={len(used[k])}) "
                f"along {np.mean(along[k]):.3f} (min {np.min(along[k]):.3f})" for k in MAGNITUDES)
                + f"  limited sample {1e3 * np.nanmean(times):.3f} ms, cuts {cut}, wobble {max(wobbles):.4f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=300)
    parser.add_argument("--methods", default="qp")
    arguments = parser.parse_args()
    run(arguments.samples, arguments.methods.split(","))


if __name__ == "__main__":
    main()
