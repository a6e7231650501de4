"""The independent optimum a held request is judged by: the wrench closest to the request that
the actuators can give with their static ranges, every rotatable thruster anywhere in its
allowed angles, found by SLSQP over every combination of convex pieces from (1.5) alone,
sharing no code with the allocator. ``bench/settling.py`` judges the settling sweep by it, and
``test/allocation/test_generated.py`` the generated azimuth vessels."""

from itertools import product

import numpy as np
from scipy.optimize import minimize


def _allowed_arcs(azimuth_min, azimuth_max, sectors):
    """Arcs of angles where a thruster may push: [min, max] less each sector [start, end]
    (counter-clockwise from start); written here again, apart from allocator_pkg.effectiveness.sectors."""
    two_pi = 2.0 * np.pi
    full = azimuth_max - azimuth_min >= two_pi - 1e-9
    low, high = (-np.pi, np.pi) if full else (azimuth_min, azimuth_max)
    arcs = [(low, high)]
    for start, end in sectors:
        width = (end - start) % two_pi
        base = (start + np.pi) % two_pi - np.pi
        for shift in (-two_pi, 0.0, two_pi):
            cut = (base + shift, base + shift + width)
            arcs = [piece for a, b in arcs for piece in ((a, min(b, cut[0])), (max(a, cut[1]), b))
                    if piece[1] > piece[0]]
    if full and len(arcs) > 1 and np.isclose(arcs[0][0], -np.pi) and np.isclose(arcs[-1][1], np.pi):
        arcs = [(arcs[-1][0], arcs[0][1] + two_pi), *arcs[1:-1]]
    return arcs


def _cones(rotation, low, high):
    """Convex pieces (start, end, radius) of one rotatable thruster's forces: cones at most
    pi wide, reverse side too when it is reversible; (None, None, R) for the whole disk."""
    if rotation.azimuth_max - rotation.azimuth_min >= 2.0 * np.pi - 1e-9 and not rotation.forbidden_sectors:
        return [(None, None, max(high, -low))]
    arcs = _allowed_arcs(rotation.azimuth_min, rotation.azimuth_max, rotation.forbidden_sectors)
    sides = [(0.0, high)] + ([(np.pi, -low)] if low < 0.0 else [])
    cones = []
    for shift, radius in sides:
        for start, end in arcs:
            start, end = start + shift, end + shift
            while end - start > np.pi:
                cones.append((start, start + np.pi, radius))
                start += np.pi
            cones.append((start, end, radius))
    return cones


def best_attainable_wrench(vehicle, tau, weights, low, high, starts=3, seed=0):
    """The wrench closest to ``tau`` (controlled DOFs; sum_k weights_k (achieved_k - tau_k)^2)
    that the actuators can give with static signed thrust ranges [low, high]: every
    rotatable thruster anywhere in its allowed angles with |f| <= its range, no rate limits.
    A union of convex pieces per rotatable thruster: SLSQP on every combination, from a few
    starts, keeping the best. Written from (1.5) alone: returns the achieved controlled
    wrench."""
    actuators = vehicle.actuators
    rows = list(vehicle.dof_indices)
    columns = []                                     # (actuator index, basis direction) per variable
    for i, actuator in enumerate(actuators):
        if actuator.rotatable:
            e1, e2 = (np.eye(3)[0], np.eye(3)[1]) if actuator.type == "azimuth" else (np.eye(3)[2], np.eye(3)[0])
            columns += [(i, e1), (i, e2)]
        else:
            columns.append((i, np.asarray(actuator.direction, dtype=float)))
    t = np.array([np.concatenate((d, np.cross(np.asarray(actuators[i].position, dtype=float), d)))
                  for i, d in columns]).T[rows]
    scale = np.array([max(high[i], -low[i], 1e-9) for i, _ in columns])
    target = np.asarray(tau, dtype=float)[rows]
    authority = np.abs(t) @ scale
    norm = np.where(authority > 0, authority, 1.0)
    weights = np.asarray(weights, dtype=float) * norm ** 2 / np.max(np.asarray(weights) * norm ** 2)
    rotatable = [i for i, a in enumerate(actuators) if a.rotatable]
    first = {i: next(k for k, (j, _) in enumerate(columns) if j == i) for i in rotatable}

    def objective(x):
        miss = (t @ (x * scale) - target) / norm
        return float(weights @ (miss * miss))

    rng = np.random.default_rng(seed)
    best_value, best_wrench = np.inf, None
    pieces = [_cones(actuators[i].rotation, low[i], high[i]) for i in rotatable]
    for combination in product(*pieces):
        bounds = [(low[i] / scale[k], high[i] / scale[k]) if not actuators[i].rotatable else (-1.0, 1.0)
                  for k, (i, _) in enumerate(columns)]
        constraints = []
        for i, (start, end, radius) in zip(rotatable, combination):
            k = first[i]
            r = radius / scale[k]
            constraints.append({"type": "ineq", "fun": lambda x, k=k, r=r: r * r - x[k] ** 2 - x[k + 1] ** 2})
            if start is not None:
                constraints.append({"type": "ineq", "fun": lambda x, k=k, a=start:
                                    -np.sin(a) * x[k] + np.cos(a) * x[k + 1]})
                constraints.append({"type": "ineq", "fun": lambda x, k=k, b=end:
                                    np.sin(b) * x[k] - np.cos(b) * x[k + 1]})
        for attempt in range(starts):
            x0 = np.zeros(len(columns)) if attempt == 0 else rng.uniform(-0.5, 0.5, len(columns))
            result = minimize(objective, x0, method="SLSQP", bounds=bounds, constraints=constraints,
                              options={"maxiter": 500, "ftol": 1e-14})
            feasible = all(c["fun"](result.x) >= -1e-7 for c in constraints)
            if feasible and result.fun < best_value:
                best_value, best_wrench = result.fun, t @ (result.x * scale)
    return best_wrench
