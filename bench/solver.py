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

1. ``qp``: ours, one OSQP problem per configuration, updated and warm-started (and
   ``nonlinear`` where the vehicle has rotatable thrusters);
2. ``qp, fresh OSQP``: the same problem, but a new OSQP object set up and solved cold every
   sample (what several open-source allocators do);
3. ``pseudoinverse (clip)`` and ``pseudoinverse (scale)``: weighted pseudo-inverse with
   clipping, and with uniform scale-down (the common ROS thruster-manager pattern);
4. ``qp, quadprog``: the same problem solved by quadprog's dense active-set method, as a
   speed reference (the benchmark swaps the solver call; everything else is the same);
5. the optimum of (1.44), static (no rate limits, forbidden sectors ignored), by scipy SLSQP
   from three starts, on the attainable samples among every 40th, as the reference for power.

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
import osqp
import quadprog
from scipy.optimize import minimize

from allocator_pkg import Allocator, load_vehicle
from allocator_pkg.actuators import drag_gain, lift_gain
from allocator_pkg.capability import Capability
from allocator_pkg.configuration_matrix import configuration_matrix
from allocator_pkg.methods.sparse_rows import ACCEPTED, Solution
from allocator_pkg.model import Model

WARM_UP = 200
SAMPLES = 2000
REFERENCE_EVERY = 40
SPEED = 2.0


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


# -- the solver swaps of patterns 2 and 4 ------------------------------------------------------

def timed(problem, store: list) -> None:
    """Record the time of each solver call (bounds update and solve) of one ScaledProblem."""
    solve = problem.solve

    def timed_solve(low, up):
        begin = time.perf_counter()
        solution = solve(low, up)
        store.append(time.perf_counter() - begin)
        return solution

    problem.solve = timed_solve


def fresh_osqp(problem):
    """Patch one ScaledProblem to set up a new OSQP object and solve cold every sample."""
    settings = problem.solver.settings

    def solve(low, up):
        cache = problem.solver._derivative_cache
        solver = osqp.OSQP()
        solver.setup(P=cache["P"], q=cache["q"], A=cache["A"], l=np.maximum(low * problem.row_scale, -1e30),
                     u=np.minimum(up * problem.row_scale, 1e30), verbose=False, scaling=0,
                     eps_abs=settings.eps_abs, eps_rel=settings.eps_rel, max_iter=settings.max_iter,
                     check_termination=settings.check_termination, polishing=False)
        result = solver.solve(raise_error=False)
        x = np.array(result.x) * problem.column_scale
        return Solution(x=x, status=result.info.status, iterations=int(result.info.iter),
                        usable=result.info.status_val in ACCEPTED and bool(np.all(np.isfinite(x))))

    problem.solve = solve


def dense_active_set(problem):
    """Patch one ScaledProblem to solve its (normalised) QP with quadprog every sample; the
    time of quadprog's call alone goes to ``problem.quadprog_times`` (the dense conversion,
    benchmark plumbing, is left out of it)."""
    problem.quadprog_times = []

    def solve(low, up):
        cache = problem.solver._derivative_cache
        p = cache["P"].toarray()
        p = p + p.T - np.diag(np.diag(p)) + 1e-9 * np.eye(p.shape[0])
        a = cache["A"].toarray()
        low, up = low * problem.row_scale, up * problem.row_scale
        equal = np.isclose(low, up)
        lower = ~equal & np.isfinite(low)
        upper = ~equal & np.isfinite(up)
        constraints = np.vstack([a[equal], a[lower], -a[upper]]).T
        bounds = np.concatenate([low[equal], low[lower], -up[upper]])
        try:
            begin = time.perf_counter()
            z = quadprog.solve_qp(p, -cache["q"], constraints, bounds, meq=int(equal.sum()))[0]
            problem.quadprog_times.append(time.perf_counter() - begin)
            status, usable = "solved", True
        except ValueError as error:
            z, status, usable = np.zeros(p.shape[0]), f"quadprog: {error}", False
        return Solution(x=z * problem.column_scale, status=status, iterations=0, usable=usable)

    problem.solve = solve


def keep_cache(problem) -> None:
    """OSQP's wrapper keeps P, q, A in ``_derivative_cache`` only through its public update();
    our direct calls bypass it, so mirror A's values there for the swapped solvers."""
    original = problem.update_matrix

    def update_matrix(values, index=None):
        original(values, index)
        cache = problem.solver._derivative_cache["A"]
        scaled = values * (problem._entry_scale if index is None else problem._entry_scale[index])
        if index is None:
            cache.data[:] = scaled
        else:
            cache.data[index] = scaled

    problem.update_matrix = update_matrix
    original_objective = problem.update_objective

    def update_objective(p_diagonal=None, q=None):
        original_objective(p_diagonal, q)
        cache = problem.solver._derivative_cache
        if p_diagonal is not None:
            cache["P"] = problem._p(p_diagonal)
        if q is not None:
            cache["q"] = problem._q(q)

    problem.update_objective = update_objective


def allocators(vehicle) -> dict[str, Allocator]:
    """Every method of the comparison, each its own Allocator on the same vehicle."""
    result = {"qp": Allocator(vehicle, method="qp")}
    fresh = Allocator(vehicle, method="qp")
    keep_cache(fresh._method._main.qp)
    fresh_osqp(fresh._method._main.qp)
    result["qp, fresh OSQP"] = fresh
    dense = Allocator(vehicle, method="qp")
    keep_cache(dense._method._main.qp)
    dense_active_set(dense._method._main.qp)
    result["qp, quadprog"] = dense
    if any(a.rotatable for a in vehicle.actuators):
        result["nonlinear"] = Allocator(vehicle, method="nonlinear")
    result["pseudoinverse (clip)"] = Allocator(vehicle, method="pseudoinverse")
    scaled = replace(vehicle, saturation="preserve_direction")
    result["pseudoinverse (scale)"] = Allocator(scaled, method="pseudoinverse")
    for allocator in result.values():
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


def run_sequence(vehicle, requests: np.ndarray) -> dict:
    capability = Capability(vehicle, method="nonlinear", speed=SPEED)
    rows = list(vehicle.dof_indices)
    authority = Model.build(vehicle, 1.0 / vehicle.rate_hz).dof_scale
    attainable = np.array([capability.scale(tau) >= 1.0 for tau in requests[WARM_UP:]])
    methods = allocators(vehicle)
    results = {}
    rng = np.random.default_rng(7)
    reference = {}
    start = None
    for k in range(WARM_UP, len(requests), REFERENCE_EVERY):
        if attainable[k - WARM_UP]:
            found = power_optimum(vehicle, requests[k], start, rng)
            if found is not None:
                reference[k], start = found
    for name, allocator in methods.items():
        solver_times: list[float] = []
        problem = getattr(allocator._method, "_main", None)
        if problem is not None and name != "qp, quadprog":
            timed(problem.qp, solver_times)
        elif name == "nonlinear":
            timed(allocator._method._qp, solver_times)
        for tau in requests[:WARM_UP]:
            allocator.allocate(tau)
        solver_times.clear()
        if name == "qp, quadprog":
            problem.qp.quadprog_times.clear()
        times, errors, iterations, power_ratio, saturated = [], [], [], [], 0
        previous = allocator.azimuth
        travel = 0.0
        for k, tau in enumerate(requests[WARM_UP:], start=WARM_UP):
            begin = time.perf_counter()
            result = allocator.allocate(tau)
            times.append(time.perf_counter() - begin)
            iterations.append(result.iterations)
            saturated += result.saturated
            errors.append(float(np.max(np.abs(result.achieved[rows] - tau[rows]) / authority)))
            travel += float(np.sum(np.abs(np.angle(np.exp(1j * (result.azimuth - previous))))))
            previous = result.azimuth
            if k in reference and reference[k] > 0.0 and errors[-1] < 1e-3:
                power_ratio.append(result.power / reference[k])
        errors = np.array(errors)
        if name == "qp, quadprog":
            solver_times = problem.qp.quadprog_times
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
        }
    return {"samples": len(requests) - WARM_UP, "attainable": int(attainable.sum()),
            "reference_samples": len(reference), "methods": results}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--configs", nargs="*", default=None, help="vehicle files (default: every shipped one)")
    parser.add_argument("--samples", type=int, default=SAMPLES)
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
