"""Power-limited references for the allocator's tests, sharing no code with it:

- :class:`Reference`, the exact one: the largest scale lambda of a direction d that the
  actuators reach with every source within its power, max lambda s.t. T f = lambda d, |f_i|
  within its range, sum_i w_ij P_i |f_i|^(3/2) <= A_j, by scipy's SLSQP from several starts
  (the power exact, no chords, no polygon);
- :func:`reference_utilisation`, the consequence analysis' utilisation from its definition
  (test/capability/test_consequence.py): forces in units of each thruster's rating, surge, sway
  and yaw from the positions, each azimuth's allowed arc cut into pieces at most 2 pi / 3 wide,
  the 256-gon of method qp, and the rule of docs/power.md after a group's loss with its power
  rows (:func:`power_after`, :func:`power_rows`) written out from the docs, by scipy's linprog.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from scipy.optimize import linprog, minimize

from allocator_pkg.effectiveness.power_rows import BREAKPOINTS, POWER_SIDES, SPACING

SIDES = 256                    # method qp: the thrust circle as an inscribed 256-gon
APOTHEM = math.cos(math.pi / SIDES)
WIDEST_PIECE = 2.0 * math.pi / 3.0

SMOOTH = 1e-4
"""|f|^(3/2) is taken as (f^2 + (SMOOTH F)^2)^(3/4) in the constraints: smooth at zero and never
below |f|^(3/2) (the reference stays within the power; it overstates an actuator's draw by at
most P (SMOOTH F)^(3/2) = 1e-6 of its rated power)."""


class Reference:
    """The reference problem of one vehicle at one set of available powers ``available`` [W]
    with feed weights ``weights`` (actuators x sources). ``columns`` (6 x r) and ``across``
    (6 x r): each actuator's wrench per newton along its direction at azimuth 0 and, for a
    rotatable thruster, at azimuth pi/2; ``low``/``high`` its thrust range; ``dofs`` the rows
    of the controlled DOFs; ``scale`` each DOF's unit (d is a unit vector in these units)."""

    def __init__(self, columns, across, rotatable, low, high, coefficient, weights, available, dofs, scale):
        self.t0, self.t1 = columns[dofs], across[dofs]
        self.rot = np.asarray(rotatable, dtype=bool)
        self.low, self.high = np.asarray(low, float), np.asarray(high, float)
        self.range = np.maximum(np.abs(self.low), np.abs(self.high))
        self.coefficient, self.weights, self.available = coefficient, weights, np.asarray(available, float)
        self.scale = np.asarray(scale, float)

    def _split(self, x):
        r = self.range.size
        return x[:r] * self.range, np.where(self.rot, x[r:2 * r], 0.0) * self.range, x[-1]

    def power(self, along, across):
        """The exact draw [W] of each source at forces (along, across) per actuator."""
        return (self.coefficient * np.hypot(along, across) ** 1.5) @ self.weights

    def _smooth_power(self, along, across):
        delta = SMOOTH * self.range
        return (self.coefficient * (along ** 2 + across ** 2 + delta ** 2) ** 0.75) @ self.weights

    def largest(self, direction, starts: int = 6, seed: int = 0) -> float:
        """lambda*: the largest scale of the unit ``direction`` (in DOF units) with the power
        exact; the best of SLSQP from ``starts`` starts, each answer checked feasible."""
        direction = np.asarray(direction, float) * self.scale
        r = self.range.size
        rng = np.random.default_rng(seed)
        wrench_scale = np.abs(self.t0 * self.range).sum(axis=1) + np.abs(self.t1 * self.range).sum(axis=1) + 1.0
        lam_scale = float(np.max(np.abs(direction) / wrench_scale)) or 1.0

        def equality(x):
            along, across, lam = self._split(x)
            return (self.t0 @ along + self.t1 @ across - lam / lam_scale * direction) / wrench_scale

        def inequality(x):
            along, across, _ = self._split(x)
            circle = 1.0 - (along ** 2 + across ** 2) / np.maximum(self.range, 1e-9) ** 2
            box = np.concatenate(((along - self.low) / self.range, (self.high - along) / self.range))
            room = np.where(np.isfinite(self.available), self.available, 1e30)
            norm = np.maximum(self.coefficient * self.range ** 1.5 @ self.weights, 1.0)
            power = (np.minimum(room, 1e30) - self._smooth_power(along, across)) / norm
            return np.concatenate((np.where(self.rot, circle, 1.0), np.where(self.rot, 1.0, box[:r]),
                                   np.where(self.rot, 1.0, box[r:]), power))

        best = 0.0
        for k in range(starts):
            x0 = np.zeros(2 * r + 1) if k == 0 else np.append(rng.uniform(-0.5, 0.5, 2 * r), 0.0)
            answer = minimize(lambda x: -x[-1], x0, method="SLSQP",
                              constraints=[{"type": "eq", "fun": equality}, {"type": "ineq", "fun": inequality}],
                              options={"maxiter": 500, "ftol": 1e-12})
            along, across, lam = self._split(answer.x)
            lam = lam / lam_scale
            feasible = (np.all(inequality(answer.x) >= -1e-7) and np.all(np.abs(equality(answer.x)) <= 1e-7)
                        and np.all(self.power(along, across) <= self.available * (1 + 1e-6) + 1e-6))
            if feasible:
                best = max(best, lam)
        return best


def power_after(parameters, group, low, high, available, efficiency=None):
    """Every actuator's force range and the power rows after ``group``'s loss, from docs/power.md:
    its own thrusters at 0, the group's sources at 0 kW and the others at ``available`` [kW];
    a feed of share s gives e = min(s, A / R) of the rated power R = P F^1.5 (a single live feed
    its s; a DEGRADED thruster of ``efficiency`` eta < 1 draws its set-point's power, P / eta^1.5
    on its delivered force); S = sum e; the range derated to S^(2/3) F; the weights w = e / S. Returns (low, high,
    weights (actuators x sources), available [W], rated power R)."""
    names, sources = parameters["actuators.names"], parameters["power.sources"]
    members = parameters[f"redundancy_groups.{group}.actuators"]
    watts = np.array([0.0 if s in parameters[f"redundancy_groups.{group}.sources"] else available[s] * 1000.0
                      for s in sources])
    low = np.array([0.0 if n in members else low[i] for i, n in enumerate(names)])
    high = np.array([0.0 if n in members else high[i] for i, n in enumerate(names)])
    weights, rated = np.zeros((len(names), len(sources))), np.zeros(len(names))
    bound = np.zeros(len(names))
    for i, name in enumerate(names):
        feeds = parameters[f"actuators.{name}.feeds"]
        rating = max(parameters[f"actuators.{name}.thrust_max"], -parameters.get(f"actuators.{name}.thrust_min", 0.0))
        eta = 1.0 if efficiency is None or not 0.0 < efficiency[i] < 1.0 else efficiency[i]
        rated[i] = parameters[f"actuators.{name}.power_coefficient"] / eta ** 1.5 * rating ** 1.5
        for feed, share in zip(feeds, parameters[f"actuators.{name}.feed_shares"]):
            j = sources.index(feed)
            room = watts[j] / rated[i] if len(feeds) > 1 else math.inf
            weights[i, j] = min(share, room) if watts[j] > 0.0 else 0.0
        total = weights[i].sum()
        bound[i] = total ** (2 / 3) * rating
        weights[i] = weights[i] / total if total > 0.0 else 0.0
    return np.clip(low, -bound, bound), np.clip(high, -bound, bound), weights, watts, rated


def chords():
    """(slope, intercept) of the chords of r^1.5 between (k / K)^SPACING, k = 0 ... K."""
    r = (np.arange(BREAKPOINTS + 1) / BREAKPOINTS) ** SPACING
    slope = np.diff(r ** 1.5) / np.diff(r)
    return slope, r[:-1] ** 1.5 - slope * r[:-1]


def power_rows(columns, size, u, power):
    """The chord rows of every actuator on q_i (units of its rated power; an azimuth's on its
    magnitude rho_i over the POWER_SIDES-gon inscribed in its circle) and the source rows
    sum_i w_ij R_i q_i <= u A_j, as (A_ub rows, b_ub, extra columns); forces in units of rating."""
    weights, watts, rated = power
    slope, intercept = chords()
    rows, rhs, extra = [], [], 0
    q_of = {}
    apothem = math.cos(math.pi / POWER_SIDES)
    normals = [((k + 0.5) * 2 * math.pi / POWER_SIDES) for k in range(POWER_SIDES)]
    column = 0
    for kind, i, _, _ in columns:
        width = 1 if kind == "fixed" else 2
        q = size + extra
        q_of[i] = q
        extra += 1 if kind == "fixed" else 2
        total = size + 2 * len(columns)
        if kind == "fixed":
            for sign in (1.0, -1.0):
                for s, c in zip(slope, intercept):                # -q + s sign t <= -c
                    row = np.zeros(total)
                    row[q], row[column] = -1.0, sign * s
                    rows.append(row)
                    rhs.append(-c)
        else:
            rho = q + 1
            for angle in normals:                                 # n . x - apothem rho <= 0
                row = np.zeros(total)
                row[column], row[column + 1], row[rho] = math.cos(angle), math.sin(angle), -apothem
                rows.append(row)
                rhs.append(0.0)
            for s, c in zip(slope, intercept):
                row = np.zeros(total)
                row[q], row[rho] = -1.0, s
                rows.append(row)
                rhs.append(-c)
        column += width
    for j in range(weights.shape[1]):                             # sum w R q - u A <= 0
        row = np.zeros(size + 2 * len(columns))
        for _, i, _, _ in columns:
            row[q_of[i]] = weights[i, j] * rated[i]
        row[u] = -watts[j]
        rows.append(row)
        rhs.append(0.0)
    return [row[:size + extra] for row in rows], rhs, extra


def reference_utilisation(vehicle, parameters, group, low, high, stuck, load, available, efficiency=None):
    """min u with T f = load, |f_i| <= u R_i in the 256-gon and a piece of its allowed arc (or
    their reverse, with the reverse radius), for the actuators the group leaves within their
    derated ranges, and every source's chord-row draw within u times its power
    (:func:`power_after`, the DEGRADED ones' ``efficiency``), by scipy's linprog."""
    low, high, weights, watts, rated = power_after(parameters, group, low, high, available, efficiency)
    names = list(vehicle.names)
    columns, unit_choices, scale = [], [], []
    for i, name in enumerate(names):
        rating = parameters[f"actuators.{name}.thrust_max"]
        x, y, _ = parameters[f"actuators.{name}.position"]
        if parameters[f"actuators.{name}.type"] == "fixed":
            columns.append(("fixed", i, np.array([0.0, rating, x * rating]), high[i] / rating))
        else:
            columns.append(("azimuth", i, np.array([[rating, 0.0], [0.0, rating], [-y * rating, x * rating]]),
                            None))
            unit_choices.append(azimuth_pieces(parameters.get(f"actuators.{name}.forbidden_sectors"), stuck.get(i),
                                               high[i] / rating, -low[i] / rating))
        scale.append(rating)
    dof_scale = np.array([sum(scale), sum(scale), sum(scale) * 40.0])
    power = (weights, watts, rated)
    best = math.inf
    for combination in itertools.product(*unit_choices):
        best = min(best, solve_reference(columns, combination, np.asarray(load)[[0, 1, 5]] / dof_scale, dof_scale,
                                         power))
    return best


def azimuth_pieces(sector, stuck, forward, reverse):
    """(start, end, radius) cones of the allowed forces, none wider than WIDEST_PIECE, ahead with
    the radius ``forward`` and astern (the cones turned by pi) with ``reverse``; ("whole",
    radius) for a free disk; None: nothing."""
    if max(forward, reverse) <= 0.0:
        return [None]
    if stuck is not None:
        if sector is not None and (stuck - sector[0]) % (2 * math.pi) <= sector[1] - sector[0]:
            return [None]
        return [(stuck, stuck, forward)] + ([(stuck + math.pi, stuck + math.pi, reverse)] if reverse > 0.0 else [])
    if sector is None:
        return [("whole", max(forward, reverse))]
    start, width = sector[1], 2 * math.pi - (sector[1] - sector[0])
    count = math.ceil(width / WIDEST_PIECE)
    cones = [(start + k * width / count, start + (k + 1) * width / count) for k in range(count)]
    return [(a, b, forward) for a, b in cones] + ([(a + math.pi, b + math.pi, reverse) for a, b in cones]
                                                  if reverse > 0.0 else [])


def solve_reference(columns, pieces, rhs, dof_scale, power):
    size = sum(1 if kind == "fixed" else 2 for kind, *_ in columns) + 1
    u = size - 1
    a_eq = np.zeros((3, size))
    a_ub, b_ub, bounds = [], [], [(None, None)] * u + [(0.0, None)]
    column, azimuth = 0, 0
    for kind, _, matrix, radius in columns:
        if kind == "fixed":
            a_eq[:, column] = matrix / dof_scale
            for sign in (1.0, -1.0):
                row = np.zeros(size)
                row[column], row[u] = sign, -radius
                a_ub.append(row)
                b_ub.append(0.0)
            column += 1
            continue
        piece = pieces[azimuth]
        azimuth += 1
        a_eq[:, column:column + 2] = matrix / dof_scale[:, None]
        if piece is None or piece[-1] <= 0.0:
            bounds[column] = bounds[column + 1] = (0.0, 0.0)
            column += 2
            continue
        for k in range(SIDES):
            row = np.zeros(size)
            row[column], row[column + 1] = math.cos(2 * math.pi * k / SIDES), math.sin(2 * math.pi * k / SIDES)
            row[u] = -piece[-1] * APOTHEM
            a_ub.append(row)
            b_ub.append(0.0)
        if len(piece) == 3:
            start, end, _ = piece                             # left of start, right of end; a ray: along it
            normals = [(math.sin(start), -math.cos(start)), (-math.sin(end), math.cos(end))]
            for normal in normals + ([(-math.cos(start), -math.sin(start))] if start == end else []):
                row = np.zeros(size)
                row[column], row[column + 1] = normal
                a_ub.append(row)
                b_ub.append(0.0)
        column += 2
    rows, limits, extra = power_rows(columns, size, u, power)
    a_ub = [np.r_[row, np.zeros(extra)] for row in a_ub] + rows
    b_ub = b_ub + limits
    bounds = bounds + [(None, None)] * extra
    cost = np.zeros(size + extra)
    cost[u] = 1.0
    result = linprog(cost, A_ub=np.array(a_ub), b_ub=b_ub, A_eq=np.hstack((a_eq, np.zeros((3, extra)))), b_eq=rhs,
                     bounds=bounds, method="highs")
    return float(result.x[u]) if result.status == 0 else math.inf
