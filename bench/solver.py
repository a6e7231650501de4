"""Solver-level benchmark: time per sample, wrench error, power and azimuth travel of the
allocation methods and of the patterns other allocators use, on the same sequences.

For every shipped vehicle, two sequences of 2000 samples after 200 of warm-up:

- ``smooth``: what a controller produces, a slowly turning and varying request;
- ``random``: independent requests, some of them beyond what the vehicle can give.

A sample is "attainable" when the vehicle's actuators can give it at all (a linear programme
on the static limits, Capability.scale >= 1); rate limits can still make it unattainable in the
sample it is asked for. Wrench errors are per DOF, as a fraction of that DOF's authority (the
largest force or moment all actuators together can give in it), the largest over the DOFs.

Methods, each timed as a whole sample (``Allocator.allocate``, Python included):

1. every registered method (``allocator_pkg.METHODS``) that can serve the vehicle: ``qp`` on
   one OSQP problem per configuration, updated and warm-started, ``pseudoinverse`` with
   clipping, ``nonlinear``, ``lp`` on HiGHS, ``dynamic``, ``svd_filter`` (vehicles with
   rotatable thrusters), ``explicit`` (vehicles without them; with its cache of laws: the
   regions cached at the end, and over the timed samples the share of solves the previous
   region answered, those a neighbouring region answered and those OSQP was needed for);
2. ``pseudoinverse (scale)``: the weighted pseudo-inverse with uniform scale-down (the common
   ROS thruster-manager pattern); ``qp (direct)`` and ``pseudoinverse (direct)``: Durham's
   direct method for unattainable requests (``saturation: direct``);
3. ``qp`` on other solver backends (``allocator_pkg.solvers.BACKENDS``): ``qp, fresh OSQP``,
   a new OSQP object set up and solved cold every sample (what several open-source allocators
   do), and the dense active-set solvers ``qp, quadprog`` and ``qp, DAQP`` as exact speed
   anchors; everything but the solver call is the same;
4. the optimum of (1.44), static (no rate limits, forbidden sectors ignored), by scipy SLSQP
   from three starts, on the attainable samples among every 40th, as the reference for power.

Solver calls are timed through the backend seam (bounds and solve, in the backend).

Each method's distance to ``qp`` per sample (the largest difference of an extended force, as a
fraction of its actuator's range) says how far it lags the QP's optimum on the smooth
sequence. Convergence (``convergence``): requests held from rest in every 45 deg of the plane
of the first two controlled DOFs at half the vehicle's capability in that direction (an LP,
Capability), ``HELD`` samples each; the number of samples after which a method stays within
1e-3 of each actuator's range of qp's settled answer (None: it never gets there, as a method
with another criterion does not).

Run by ``make bench``; writes JSON to stdout or ``--out``.
"""

from __future__ import annotations

import argparse
import gc
import json
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

from allocator_pkg import METHODS, Allocator, load_vehicle
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.effectiveness.actuators import drag_gain, lift_gain
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix
from allocator_pkg.effectiveness.model import Model
from allocator_pkg.solvers import BACKENDS, DEFAULT_BACKEND

WARM_UP = 200
SAMPLES = 2000
REFERENCE_EVERY = 40
SPEED = 2.0
HELD = 300
HELD_DIRECTIONS = 8
CLOSE = 1e-3


def sequences(vehicle, samples: int, seed: int = 1) -> dict[str, np.ndarray]:
    """The smooth and the random request sequences, sized by each DOF's authority."""
    model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
    authority = np.zeros(6)
    authority[model.dof_index] = model.authority
    t = np.arange(samples) / vehicle.rate_hz
    turn = 2.0 * math.pi * t / (samples / vehicle.rate_hz)
    smooth = np.zeros((samples, 6))
    horizontal = 0.3 * min(a for a in authority[:2] if a > 0) if np.any(authority[:2] > 0) else 0.0
    smooth[:, 0] = horizontal * np.cos(turn) if authority[0] else 0.0
    smooth[:, 1] = horizontal * np.sin(turn) if authority[1] else 0.0
    for k, (frequency, share) in zip(range(2, 6), ((3.0, 0.2), (5.0, 0.1), (4.0, 0.1), (2.0, 0.15))):
        smooth[:, k] = share * authority[k] * np.sin(frequency * turn + k)
    rng = np.random.default_rng(seed)
    random = authority * rng.uniform(-0.5, 0.5, size=(samples, 6))
    return {"smooth": smooth, "random": random}


# -- solver backends, each timed through the seam ---------------------------------------------

class Timed:
    """A backend factory whose backends record the time of each solve call (bounds update
    and solve) in ``times``."""

    def __init__(self, backend: str):
        self.factory = BACKENDS[backend]
        self.times: list[float] = []

    def __call__(self):
        backend = self.factory()
        solve = backend.solve
        times = self.times

        def timed_solve(low, up, q=None):
            begin = time.perf_counter()
            result = solve(low, up, q)
            times.append(time.perf_counter() - begin)
            return result

        backend.solve = timed_solve
        return backend


PATTERNS = {"qp, fresh OSQP": "osqp_fresh", "qp, quadprog": "quadprog", "qp, DAQP": "daqp"}
"""Other solvers on the same QP (name in the report: backend)."""


def allocators(vehicle) -> dict[str, tuple[Allocator, Timed]]:
    """Every method of the comparison, each its own Allocator on the same vehicle, with the
    record of its solver calls."""
    result = {}
    for name in METHODS:
        if METHODS[name].problems(vehicle):
            continue
        timed_backend = Timed(DEFAULT_BACKEND)
        result[name] = (Allocator(vehicle, method=name, backend=timed_backend), timed_backend)
    for name, backend in PATTERNS.items():
        if backend in BACKENDS:
            timed_backend = Timed(backend)
            result[name] = (Allocator(vehicle, method="qp", backend=timed_backend), timed_backend)
    scaled = replace(vehicle, saturation="preserve_direction")
    result["pseudoinverse (scale)"] = (Allocator(scaled, method="pseudoinverse"), Timed(DEFAULT_BACKEND))
    direct = replace(vehicle, saturation="direct")
    for name in ("qp", "pseudoinverse"):
        timed_backend = Timed(DEFAULT_BACKEND)
        result[f"{name} (direct)"] = (Allocator(direct, method=name, backend=timed_backend), timed_backend)
    for allocator, _ in result.values():
        allocator.set_speed(SPEED)
    return result


# -- reference 5: the static optimum of (1.44) ------------------------------------------------

def power_optimum(vehicle, tau: np.ndarray, start: np.ndarray | None, rng) -> tuple[float, np.ndarray] | None:
    """min sum P_i |f_i|^1.5 s.t. T(alpha) f = tau on the controlled DOFs, static limits; a
    control surface's force is its lift, within k_L delta_max at SPEED, and its drag
    k_D (L / k_L)^2 is taken off surge (1.57), as the allocator does."""
    actuators = vehicle.actuators
    rows = list(vehicle.dof_indices)
    rot = [i for i, a in enumerate(actuators) if a.rotatable]
    r = len(actuators)
    surfaces = [i for i, a in enumerate(actuators) if a.is_surface]
    lift = np.array([lift_gain(actuators[i].surface, vehicle.water_density, SPEED) for i in surfaces])
    drag = np.array([drag_gain(actuators[i].surface, vehicle.water_density, SPEED) for i in surfaces])
    low, high = [], []
    for i, actuator in enumerate(actuators):
        if actuator.is_surface:
            reach = lift[surfaces.index(i)] * actuator.surface.deflection_max
            low.append(-reach)
            high.append(reach)
        else:
            low.append(actuator.thrust_min)
            high.append(actuator.thrust_max)
    power = np.array([a.power_coefficient for a in actuators])
    size = np.maximum(np.abs(tau[rows]), 1.0)

    def angles(x):
        full = np.zeros(r)
        full[rot] = x[r:]
        return full

    def residual(x):
        achieved = configuration_matrix(actuators, angles(x)) @ x[:r]
        if surfaces:
            deflection = np.divide(x[surfaces], lift, out=np.zeros(len(surfaces)), where=lift > 0.0)
            achieved[0] -= float(np.sum(drag * deflection ** 2))
        return (achieved[rows] - tau[rows]) / size

    def cost(x):
        return float(np.sum(power * np.abs(x[:r]) ** 1.5) + 1e-9 * np.sum(x[:r] ** 2))

    starts = [] if start is None else [start]
    while len(starts) < 3:
        starts.append(np.concatenate((rng.uniform(low, high) * 0.3, rng.uniform(-math.pi, math.pi, len(rot)))))
    best = None
    for x0 in starts:
        result = minimize(cost, x0, method="SLSQP", constraints=[{"type": "eq", "fun": residual}],
                          bounds=list(zip(low, high)) + [(None, None)] * len(rot),
                          options={"maxiter": 300, "ftol": 1e-10})
        if result.success and np.max(np.abs(residual(result.x))) < 1e-6 and (best is None or result.fun < best.fun):
            best = result
    return (float(np.sum(power * np.abs(best.x[:r]) ** 1.5)), best.x) if best is not None else None


# -- running ------------------------------------------------------------------------------

def percentiles(values) -> dict[str, float]:
    values = np.asarray(values, dtype=float)
    if values.size == 0:
        return {}
    return {"median": float(np.median(values)), "p90": float(np.percentile(values, 90)),
            "p99": float(np.percentile(values, 99)), "max": float(np.max(values))}


def extended(result) -> np.ndarray:
    """The extended forces (1.16) of a sample, each actuator's x and y components."""
    return np.concatenate((result.thrust * np.cos(result.azimuth), result.thrust * np.sin(result.azimuth)))


def convergence(vehicle, directions: int = HELD_DIRECTIONS, samples: int = HELD) -> dict[str, dict]:
    """Per method, the samples each held request takes to stay within CLOSE of qp's settled
    answer (see the module)."""
    model = Model.build(vehicle, 1.0 / vehicle.rate_hz)
    capability = Capability(vehicle, method="qp", speed=SPEED)
    first, second = model.dof_index[:2]
    scale = np.tile(model.force_scale, 2)
    names = [name for name in METHODS if not METHODS[name].problems(vehicle)]
    reached: dict[str, list] = {name: [] for name in names}
    for angle in np.arange(directions) * 2.0 * math.pi / directions:
        unit = np.zeros(6)
        unit[first] = model.authority[0] * math.cos(angle)
        unit[second] = model.authority[1] * math.sin(angle)
        tau = 0.5 * min(capability.scale(unit), 10.0) * unit
        answers = {}
        for name in names:
            allocator = Allocator(vehicle, method=name)
            allocator.set_speed(SPEED)
            answers[name] = np.array([extended(allocator.allocate(tau)) for _ in range(samples)])
        optimum = answers["qp"][-1]
        for name in names:
            distance = np.max(np.abs(answers[name] - optimum) / scale, axis=1)
            far = np.flatnonzero(distance >= CLOSE)
            reached[name].append(None if far.size and far[-1] == samples - 1 else int(far[-1] + 1) if far.size else 0)
    return {name: {"samples": values, "never": sum(v is None for v in values),
                   "median": float(np.median([v for v in values if v is not None])) if any(
                       v is not None for v in values) else None,
                   "max": max((v for v in values if v is not None), default=None)}
            for name, values in reached.items()}


def region_figures(before: dict[str, int], after: dict[str, int]) -> dict[str, float]:
    """The explicit method's cache over the timed samples: laws cached at the end, and the
    shares of its solves (several a sample with the drag feed-forward) that the previous region,
    a neighbouring one, or OSQP answered."""
    calls = max(after["calls"] - before["calls"], 1)
    return {"regions": after["regions"], "hit_rate": (after["hits"] - before["hits"]) / calls,
            "neighbour_rate": (after["moved"] - before["moved"]) / calls,
            "osqp_rate": (after["solved"] - before["solved"]) / calls,
            "inexact": after["inexact"] - before["inexact"]}


def run_sequence(vehicle, requests: np.ndarray) -> dict:
    capability = Capability(vehicle, method="nonlinear", speed=SPEED)
    rows = list(vehicle.dof_indices)
    authority = Model.build(vehicle, 1.0 / vehicle.rate_hz).dof_scale
    attainable = np.array([capability.scale(tau) >= 1.0 for tau in requests[WARM_UP:]])
    methods = allocators(vehicle)
    results = {}
    forces = {}
    scale = np.tile(Model.build(vehicle, 1.0 / vehicle.rate_hz).force_scale, 2)
    rng = np.random.default_rng(7)
    reference = {}
    start = None
    for k in range(WARM_UP, len(requests), REFERENCE_EVERY):
        if attainable[k - WARM_UP]:
            found = power_optimum(vehicle, requests[k], start, rng)
            if found is not None:
                reference[k], start = found
    for name, (allocator, timed_backend) in methods.items():
        for tau in requests[:WARM_UP]:
            allocator.allocate(tau)
        solver_times = timed_backend.times
        solver_times.clear()
        statistics = getattr(allocator._solver.method, "statistics", None)
        before = statistics() if statistics else None
        times, errors, iterations, power_ratio, saturated = [], [], [], [], 0
        previous = allocator.azimuth
        travel = 0.0
        forces[name] = []
        for k, tau in enumerate(requests[WARM_UP:], start=WARM_UP):
            begin = time.perf_counter()
            result = allocator.allocate(tau)
            times.append(time.perf_counter() - begin)
            forces[name].append(extended(result))
            iterations.append(result.iterations)
            saturated += result.saturated
            errors.append(float(np.max(np.abs(result.achieved[rows] - tau[rows]) / authority)))
            travel += float(np.sum(np.abs(np.angle(np.exp(1j * (result.azimuth - previous))))))
            previous = result.azimuth
            if k in reference and reference[k] > 0.0 and errors[-1] < 1e-3:
                power_ratio.append(result.power / reference[k])
        errors = np.array(errors)
        results[name] = {
            "time_us": {key: value * 1e6 for key, value in percentiles(times).items()},
            "solver_us": {key: value * 1e6 for key, value in percentiles(solver_times).items()},
            "iterations": percentiles(iterations),
            "error_attainable": percentiles(errors[attainable]),
            "error_unattainable": percentiles(errors[~attainable]),
            "saturated_flags": saturated,
            "power_vs_reference": percentiles(power_ratio),
            "azimuth_travel_rad": travel,
            "fallbacks": allocator.stats.fallbacks,
            "solver_setups": allocator.stats.solver_setups,
            "distance_to_qp": percentiles(np.max(np.abs(np.array(forces[name]) - np.array(forces["qp"])) / scale,
                                                 axis=1)),
        }
        if before is not None:
            results[name]["regions"] = region_figures(before, statistics())
    return {"samples": len(requests) - WARM_UP, "attainable": int(attainable.sum()),
            "reference_samples": len(reference), "methods": results}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--configs", nargs="*", default=None, help="vehicle files (default: every shipped one)")
    parser.add_argument("--samples", type=int, default=SAMPLES)
    parser.add_argument("--held-directions", type=int, default=HELD_DIRECTIONS,
                        help="held requests per vehicle for the convergence rows (default %(default)s)")
    parser.add_argument("--out", type=Path, default=None)
    arguments = parser.parse_args(argv)
    root = Path(__file__).resolve().parents[1]
    configs = arguments.configs or sorted(str(p) for p in (root / "config").glob("*.yaml") if p.stem != "default")
    gc.enable()
    report = {"gc": "enabled", "warm_up": WARM_UP, "vehicles": {}}
    for config in configs:
        vehicle = load_vehicle(config)
        stem = Path(config).stem
        report["vehicles"][stem] = {
            "actuators": len(vehicle.actuators), "dofs": list(vehicle.dofs),
            "sequences": {name: run_sequence(vehicle, requests)
                          for name, requests in sequences(vehicle, arguments.samples + WARM_UP).items()},
            "convergence": convergence(vehicle, arguments.held_directions),
        }
        print(f"bench: {stem} done", file=sys.stderr, flush=True)
    text = json.dumps(report, indent=1)
    if arguments.out:
        arguments.out.write_text(text)
    else:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
