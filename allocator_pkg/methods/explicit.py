"""Explicit constrained allocation: the piecewise-affine law of (1.35) (survey section 4.1),
built region by region as the requests visit them.

For actuators whose directions never change, (1.35) is a QP in z = [f, s, fbar] (1.38)
whose data depend affinely on the parameters p = [tau, f_min, f_max] (1.37), beta being a
configuration constant. Its optimum z*(p) is continuous and piecewise affine: wherever the
same constraints are active, the optimality (KKT) conditions are one linear system whose
right-hand side is affine in p, so that z* = K p + k, and the set of p where that active set
is optimal is a polyhedron {p : C p <= d} (primal feasibility of the inactive constraints,
dual feasibility of the multipliers of the active ones) (1.39)-(1.41).

Here the KKT system is solved in the augmented form (z and the multipliers of the equality
T f - s = tau and of the active rows among f_i <= f_max,i, -f_i <= -f_min,i, f_i - fbar <= 0,
-f_i - fbar <= 0; fbar only with beta > 0), normalised (:class:`Law`). A :class:`Region`
holds, for one active set, the law and its checks as one matrix over p_1 = [tau, f_min,
f_max, 1]: a sample in the region it was in before costs one matrix-vector product and one
comparison. The bounds of this sample (faults, rate limits, control surfaces' lift at this
speed) are parameters, not data: none of them invalidates a law. Only T, W, Q and beta are
data; a configuration that changes one of them clears the laws
(:meth:`ExplicitAllocation.update_model`).

When the previous region's checks fail, the violated checks name a neighbour: add the
constraints the law violates, drop those whose multipliers have the wrong sign (a
primal-dual active-set step). A few such moves, each a cached law or one new KKT solve, reach
the region of most requests; otherwise OSQP, warm-started, solves the QP of (1.35), its
active set is read from its answer (by OSQP's own polishing rule), and the moves polish it
to the exact region (if they do not, OSQP once more to a tight tolerance). Only if that also
fails is OSQP's own answer used, within its tolerance, and said so in the status.

The cache of laws is bounded (least recently used first out). A table of every region,
enumerated offline for a small vehicle (``allocator-explicit precompute``, survey 4.1), can be
loaded besides it (``explicit.regions``): its laws are built when the method is set up and
never evicted, so that moves between them need no KKT solve. Rotatable thrusters change
their columns of T every sample, so a law would hold for one sample only: the method refuses
them when the configuration is parsed (:meth:`ExplicitAllocation.problems`), as it refuses
``saturation: preserve_direction``, whose scale multiplies tau (T f = lambda tau is no affine
function of tau), and ``saturation: direct`` (a vertex of the attainable set, not (1.35)'s
optimum).
"""

from __future__ import annotations

import hashlib
import math
import zipfile
from collections import OrderedDict
from dataclasses import dataclass, replace

import numpy as np
from numpy.lib.npyio import NpzFile

from ..effectiveness.model import Model, SampleLimits
from ..solvers import BackendFactory
from ..solvers.outcome import Outcome, Solution
from ..solvers.problem import Rows, ScaledProblem
from ..vehicle.config import Vehicle
from .base import CIRCLE_SIDES, AllocationMethod, MethodOutput

CAPACITY = 512
"""Laws kept (least recently used out first): a BlueROV2 Heavy visits fewer on the
benchmark's sequences, and each law is a few kilobytes."""

MOVES = 4
"""Neighbour moves tried from the previous region before OSQP is asked."""

POLISH_MOVES = 12
"""Neighbour moves tried from the active set read from OSQP's answer."""

PRIMAL_TOLERANCE = 1e-9
"""A constraint counts as met within this fraction of its actuator's force range."""

DUAL_TOLERANCE = 1e-9
"""A multiplier counts as non-negative above -this, in units of its actuator's effort
gradient at full force (2 W_ii times its range): relative to each actuator, so that a large
one does not blunt the checks of a small one."""

NEAR = 1e-3
"""With beta > 0, OSQP's forces within this fraction of their range of the largest count as
equal to it (OSQP stops at 1e-5 of the ranges by default)."""

TIGHT = 1e-10
"""OSQP's tolerances for a second solve when the active set of the first does not lead to a
region (fractions of the variables' ranges)."""

TIGHT_ITERATIONS = 20000
"""OSQP's iteration limit for that second solve; only a converged one (``Outcome.SOLVED``) is used."""

INDEPENDENT = 1e-9
"""A normalised row whose part outside the span of the rows kept is smaller depends on them."""


@dataclass(slots=True)
class Region:
    """One active set's law and checks. ``matrix`` @ p_1 gives the r forces, then the checks,
    each <= 0 inside the region (tolerance included). Check k concerns constraint row
    ``rows[k]``; ``primal[k]`` tells whether it is a row to add when violated (else to drop);
    rows from ``bounds`` on are minimax rows."""

    key: int
    matrix: np.ndarray
    rows: np.ndarray
    primal: np.ndarray
    bounds: int

    def neighbour(self, checks: list[float], single: bool = False) -> tuple[int, int]:
        """The active set one primal-dual step away, and the rows added: violated bounds added,
        of the violated minimax rows only the most violated one (the largest force sets fbar;
        the others may hold once it does), multipliers of the wrong sign dropped. ``single``:
        one change only, the most negative multiplier dropped, else the most violated row
        added (the step that breaks a cycle of full steps)."""
        violated = np.flatnonzero(np.array(checks) > 0.0).tolist()
        if single:
            dual = [k for k in violated if not self.primal[k]]
            k = max(dual or violated, key=checks.__getitem__)
            row = int(self.rows[k])
            return (self.key & ~(1 << row), 0) if not self.primal[k] else (self.key | 1 << row, 1 << row)
        key, added = self.key, 0
        top, worst = -1, 0.0
        for k in violated:
            row = int(self.rows[k])
            if not self.primal[k]:
                key &= ~(1 << row)
            elif row < self.bounds:
                key, added = key | 1 << row, added | 1 << row
            elif checks[k] > worst:
                top, worst = row, checks[k]
        if top >= 0:
            key, added = key | 1 << top, added | 1 << top
        return key, added


class Law:
    """(1.35), normalised, and the KKT solution of any active set (:meth:`region`).

    Variables y = [f, s, fbar] (1.38) (fbar only with beta > 0), each divided by its range
    (a force by its actuator's, a slack by its DOF's authority, fbar by the largest force); the
    cost divided by the largest effort curvature. The equality rows T f - s = tau are always
    active; the inequality rows, each divided by its largest coefficient, are: 2i the upper
    bound of actuator i, 2i + 1 its lower bound, 2r + 2i and 2r + 2i + 1 its minimax rows
    f_i - fbar <= 0 and -f_i - fbar <= 0 (with beta > 0). The slack stays a variable (the
    augmented form): with Q >> W, eliminating it would leave H = 2 (W + T'QT), in which W,
    what a small actuator's multipliers are made of, is lost in the rounding of T'QT.
    Parameters p_1 = [tau (n), f_min (r), f_max (r), 1]."""

    def __init__(self, model: Model):
        t = model.t_ec
        n, r = t.shape
        weight = model.weight
        slack = model.slack_weights(weight)
        beta = float(model.vehicle.weights.minimax)
        self.n, self.r = n, r
        self.minimax = beta > 0.0
        self.size = n + 2 * r + 1
        self.data = (t.tobytes(), weight.tobytes(), slack.tobytes(), beta)
        self.fingerprint = hashlib.sha256(b"".join((*self.data[:3], repr((t.shape, beta)).encode()))).hexdigest()
        d = r + n + 1 if self.minimax else r + n
        scale = np.concatenate((model.force_scale, model.dof_scale, [np.max(model.force_scale)]))[:d]
        # 1/2 y'Hy + y'(L p_1) = f'Wf + s'Qs + beta fbar; E y = tau; G y <= h p_1.
        self.cost = float(np.max(2.0 * weight * model.force_scale ** 2))
        self.curvature = np.concatenate((2.0 * weight, 2.0 * slack, [0.0]))[:d] * scale ** 2 / self.cost
        self.linear = np.zeros((d, self.size))
        equality = np.hstack((t, -np.eye(n), np.zeros((n, d - r - n)))) * scale
        equality_scale = 1.0 / np.max(np.abs(equality), axis=1)
        self.equality = equality * equality_scale[:, None]
        self.equality_h = np.zeros((n, self.size))
        self.equality_h[:, :n] = np.diag(equality_scale)
        rows = 4 * r if self.minimax else 2 * r
        g = np.zeros((rows, d))
        h = np.zeros((rows, self.size))
        index = np.arange(r)
        g[2 * index, index], h[2 * index, n + r + index] = 1.0, 1.0
        g[2 * index + 1, index], h[2 * index + 1, n + index] = -1.0, -1.0
        if self.minimax:
            self.linear[-1, -1] = beta * scale[-1] / self.cost
            g[2 * r + 2 * index, index], g[2 * r + 2 * index + 1, index] = 1.0, -1.0
            g[2 * r:, -1] = -1.0
        g = g * scale
        row_scale = 1.0 / np.max(np.abs(g), axis=1)
        self.g, self.h = g * row_scale[:, None], h * row_scale[:, None]
        self.scale = scale
        self.rows = rows
        self.d = d
        self.even = sum(1 << 2 * i for i in range(r))
        opposite = np.arange(rows) ^ 1
        opposite[2 * r:] = -1
        self.opposite = opposite
        # A row's multiplier in units of its actuator's effort gradient at full force.
        owner = np.tile(index.repeat(2), 2 if self.minimax else 1)
        self.dual_scale = self.curvature[owner] / (row_scale * scale[owner])

    def region(self, key: int, first: int = 0) -> Region | None:
        """The law and checks of the active set ``key`` (bit j: row j active), or None when its
        KKT system is singular (fbar left free). Dependent rows (with beta > 0: fbar equal to a
        bound an actuator has reached) are thinned to independent ones, bounds first, then the
        minimax rows in ``first``, then the others: the region is then the part of the
        degenerate one where those rows decide."""
        active = [j for j in range(self.rows) if key >> j & 1]
        if self.minimax and not any(j >= 2 * self.r for j in active):
            return None
        if (self.minimax or key & key >> 1 & self.even) and np.linalg.matrix_rank(self.g[active]) < len(active):
            active = self._independent(active, first)
            key = sum(1 << j for j in active)
        active = np.array(active, dtype=int)
        rows = np.vstack((self.equality, self.g[active]))
        d, n, k = self.d, self.n, active.size
        kkt = np.zeros((d + n + k, d + n + k))
        kkt[np.arange(d), np.arange(d)] = self.curvature
        kkt[:d, d:] = rows.T
        kkt[d:, :d] = rows
        try:
            solution = np.linalg.solve(kkt, np.vstack((-self.linear, self.equality_h, self.h[active])))
        except np.linalg.LinAlgError:
            return None
        x, multipliers = solution[:d], solution[d + n:]
        inactive = np.ones(self.rows, dtype=bool)
        inactive[active] = False
        inactive[self.opposite[active][self.opposite[active] >= 0]] = False   # f_max >= f_min always
        inactive = np.flatnonzero(inactive)
        primal = self.g[inactive] @ x - self.h[inactive]
        primal[:, -1] -= PRIMAL_TOLERANCE
        dual = -multipliers / self.dual_scale[active][:, None]
        dual[:, -1] -= DUAL_TOLERANCE
        law = self.scale[:self.r, None] * x[:self.r]
        for j in active[active < 2 * self.r].tolist():         # a force at its bound is that bound, exactly
            law[j // 2] = 0.0
            law[j // 2, self.n + (self.r if j % 2 == 0 else 0) + j // 2] = 1.0
        matrix = np.ascontiguousarray(np.vstack((law, primal, dual)))
        return Region(key, matrix, np.concatenate((inactive, active)),
                      np.concatenate((np.ones(inactive.size, bool), np.zeros(k, bool))), 2 * self.r)

    def _independent(self, active: list[int], first: int) -> list[int]:
        """A largest independent subset of the rows ``active``, taken greedily in priority order
        (Gram-Schmidt on the normalised rows)."""
        order = sorted(active, key=lambda j: (j >= 2 * self.r, not first >> j & 1, j))
        basis: list[np.ndarray] = []
        kept = []
        for j in order:
            row = self.g[j].copy()
            for vector in basis:
                row -= (vector @ row) * vector
            norm = float(np.linalg.norm(row))
            if norm > INDEPENDENT:
                basis.append(row / norm)
                kept.append(j)
        return sorted(kept)

    def largest(self, force: np.ndarray) -> int:
        """The minimax row of the largest |f_i| (the first to keep of dependent ones)."""
        if not self.minimax:
            return 0
        i = int(np.argmax(np.abs(force)))
        return 1 << 2 * self.r + 2 * i + int(force[i] < 0.0)

    def near_largest(self, force: np.ndarray, tolerance: np.ndarray) -> int:
        """The minimax rows of the forces within ``tolerance`` of the largest |f_i| (at the
        optimum fbar is the largest, and every force that large has its row active)."""
        if not self.minimax:
            return 0
        top = float(np.max(np.abs(force)))
        key = 0
        for i, (f, near) in enumerate(zip(force.tolist(), tolerance.tolist())):
            if abs(f) >= top - near:
                key |= 1 << 2 * self.r + 2 * i + int(f < 0.0)
        return key


def read_regions(path: str, law: Law) -> list[int]:
    """The active sets of a file written by ``allocator-explicit precompute``; ValueError when
    it cannot be read as one, or was computed for other data (T, W, Q or beta) than ``law``'s."""
    try:
        data = np.load(path, allow_pickle=False)
    except (OSError, ValueError, zipfile.BadZipFile) as error:
        raise ValueError(f"cannot read {path} as a regions file: {error}") from error
    if not isinstance(data, NpzFile):
        raise ValueError(f"{path} is not a regions file of allocator-explicit precompute (not an .npz archive)")
    with data:
        if "fingerprint" not in data or "keys" not in data:
            raise ValueError(f"{path} is not a regions file of allocator-explicit precompute (no fingerprint or keys)")
        if str(data["fingerprint"]) != law.fingerprint:
            raise ValueError(f"{path} was computed for another configuration (T, W, Q or beta differ): "
                             "run allocator-explicit precompute again")
        return [int(key) for key in data["keys"]]


class ExplicitAllocation(AllocationMethod):
    """Allocation method ``explicit``; ``capacity`` bounds the cache of laws, ``table`` holds
    those of a precomputed file. Counters: ``calls``, ``hits`` (the previous region held),
    ``moved`` (a neighbour did), ``solved`` (OSQP was needed), ``inexact`` (OSQP's answer used
    as it came), ``built`` (laws computed while allocating)."""

    name = "explicit"
    saturation_modes = ("weighted",)

    def __init__(self, model: Model, backend: BackendFactory, capacity: int = CAPACITY):
        super().__init__(model, backend)
        self.capacity = capacity
        self.laws: OrderedDict[int, Region] = OrderedDict()
        self.table: dict[int, Region] = {}
        self.calls = self.hits = self.moved = self.solved = self.inexact = self.built = 0
        self._use(model)
        self._load(model.vehicle.explicit_regions)
        self._start()
        self._setup(model)

    @classmethod
    def problems(cls, vehicle: Vehicle) -> list[str]:
        """Rotatable thrusters (their columns of T change every sample: no law holds beyond one)
        are refused by name, as is any saturation but ``weighted``: ``preserve_direction``
        scales the request by a variable (T f = lambda tau is no affine function of tau) and
        ``direct`` answers with a vertex of the attainable set, not (1.35)'s optimum."""
        problems = super().problems(vehicle)
        rotating = [a.name for a in vehicle.actuators if a.rotatable]
        if rotating:
            problems.append(f"it needs actuators of fixed direction (survey 4.1), and {', '.join(rotating)} "
                            "rotate; use qp or nonlinear")
        if vehicle.explicit_regions and not problems:
            try:
                read_regions(vehicle.explicit_regions, Law(Model.build(vehicle, 1.0 / vehicle.rate_hz)))
            except ValueError as error:
                problems.append(f"explicit.regions: {error}")
        return problems

    @classmethod
    def thrust_region_sides(cls, vehicle: Vehicle) -> int | None:
        """Like qp: the box and minimax constraints of (1.35) (no rotatable thruster is served)."""
        return CIRCLE_SIDES

    @property
    def regions(self) -> int:
        """Laws known: the precomputed table's and the cache's (kept as a count for the status)."""
        return self._known

    def statistics(self) -> dict[str, int]:
        """The counters and the number of laws cached (benchmarks, diagnostics)."""
        return {"regions": self.regions, "calls": self.calls, "hits": self.hits, "moved": self.moved,
                "solved": self.solved, "inexact": self.inexact, "built": self.built}

    def _use(self, model: Model) -> None:
        self.model = model
        self.law = Law(model)
        self._p = np.zeros(self.law.size)
        self._p[-1] = 1.0
        self._version: int | None = None
        self._region: Region | None = None
        self._n, self._r = model.n, model.r

    def _load(self, path: str) -> None:
        """The laws of a precomputed file, or none."""
        self.table = {}
        if path:
            regions = (self.law.region(key) for key in read_regions(path, self.law))
            self.table = {region.key: region for region in regions if region is not None}
        self._known = len(self.table) + len(self.laws)

    def _start(self) -> None:
        """Start in the region where no constraint is active (none with beta > 0, where fbar
        needs a minimax row: OSQP finds the first region then)."""
        region = self._law(0)
        if region is not None:
            self._keep(region)

    def update_model(self, model: Model) -> None:
        """Values only: the laws stay when T, W, Q and beta do (new limits are parameters),
        else they are all cleared."""
        old, region, path = self.law.data, self._region, self.model.vehicle.explicit_regions
        self._use(model)
        if self.law.data == old:
            self._region = region
        else:
            self.laws.clear()
            self._known = len(self.table)
        if self.law.data != old or model.vehicle.explicit_regions != path:
            self._load(model.vehicle.explicit_regions)
        if self._region is None:
            self._start()
        a, _ = self._rows(model)
        p, q = self._objective(model)
        self._qp.update_matrix(a.data)
        self._qp.update_objective(p, q)
        self._qp.update_settings(model.vehicle.solver)
        self._constant_bounds(model)

    # -- per sample ---------------------------------------------------------------------

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        p = self._p
        n, r = self._n, self._r
        if limits.version < 0 or limits.version != self._version:
            p[n:n + r] = limits.low
            p[n + r:n + 2 * r] = limits.high
            self._version = limits.version
        p[:n] = tau
        self.calls += 1
        region = self._region
        if region is not None:
            out = region.matrix.dot(p)
            checks = out[r:].tolist()
            if max(checks) <= 0.0:
                self.hits += 1
                return MethodOutput(force=out[:r], status=f"hit; regions {self._known}, hits {self.hits}/{self.calls}")
            found = self._moves(region, checks, p)
            if found is not None:
                self.moved += 1
                return MethodOutput(force=found,
                                    status=f"neighbour; regions {self.regions}, hits {self.hits}/{self.calls}")
        return self._solve(p, limits)

    def _moves(self, region: Region, checks: list[float], p: np.ndarray, moves: int = MOVES) -> np.ndarray | None:
        """Up to ``moves`` primal-dual steps from ``region``; the forces of the region reached,
        which becomes the current one, or None."""
        seen = {region.key}
        for _ in range(moves):
            key, added = region.neighbour(checks)
            if key in seen:
                key, added = region.neighbour(checks, single=True)
            seen.add(key)
            region = self._law(key, added)
            if region is None:
                return None
            out = region.matrix.dot(p)
            checks = out[self._r:].tolist()
            if max(checks) <= 0.0:
                self._keep(region)
                return out[:self._r]
        return None

    def _law(self, key: int, first: int = 0) -> Region | None:
        """The cached law of ``key``, else a new one (cached only once a request is found in it);
        ``first``: see :meth:`Law.region`."""
        region = self.table.get(key)
        if region is not None:
            return region
        region = self.laws.get(key)
        if region is not None:
            self.laws.move_to_end(key)
            return region
        self.built += 1
        return self.law.region(key, first)

    def _keep(self, region: Region) -> None:
        """``region`` holds this sample: the current one, cached (the least recently used out)."""
        self._region = region
        if region.key not in self.laws and region.key not in self.table:
            self.laws[region.key] = region
            if len(self.laws) > self.capacity:
                self.laws.popitem(last=False)
            self._known = len(self.table) + len(self.laws)

    def _solve(self, p: np.ndarray, limits: SampleLimits) -> MethodOutput:
        """OSQP on (1.35), warm-started; its active set polished to the exact region."""
        self.solved += 1
        index, qp = self._index, self._qp
        n, r = self._n, self._r
        qp.low[index["equality"]] = qp.up[index["equality"]] = p[:n]
        qp.low[index["box"]], qp.up[index["box"]] = limits.low, limits.high
        if self.law.minimax:
            qp.up[index["last"]] = max(float(np.max(np.abs(limits.low))), float(np.max(np.abs(limits.high))))
        solution = qp.solve(qp.low, qp.up)
        if not solution.usable:
            return MethodOutput(force=np.zeros(r), status=f"OSQP: {solution.status}; regions {self.regions}, "
                                f"hits {self.hits}/{self.calls}", iterations=solution.iterations,
                                outcome=solution.outcome)
        iterations = solution.iterations
        found = self._polish(solution, p)
        if found is None:
            # A guess from an answer to OSQP's tolerance that the moves do not mend (ill-scaled or
            # degenerate problems): OSQP again, warm-started, to a much tighter tolerance.
            settings = self.model.vehicle.solver
            qp.update_settings(replace(settings, eps_abs=TIGHT, eps_rel=TIGHT, max_iter=TIGHT_ITERATIONS))
            tight = qp.solve(qp.low, qp.up)
            qp.update_settings(settings)
            iterations += tight.iterations
            if tight.outcome is Outcome.SOLVED:
                solution = tight
                found = self._polish(solution, p)
        if found is not None:
            return MethodOutput(force=found, status=f"new region by OSQP; regions {self.regions}, "
                                f"hits {self.hits}/{self.calls}", iterations=iterations)
        self.inexact += 1
        return MethodOutput(force=solution.x[:r].copy(), status=f"OSQP, no exact region ({solution.status}); "
                            f"regions {self.regions}, hits {self.hits}/{self.calls}", iterations=iterations,
                            outcome=solution.outcome, residual=solution.residual)

    def _polish(self, solution: Solution, p: np.ndarray) -> np.ndarray | None:
        """The region of the active set OSQP's answer shows, or one a few moves from it: its
        forces (it becomes the current region), or None."""
        r = self._r
        start = self._law(self._active(solution), self.law.largest(solution.x[:r]))
        if start is None:
            return None
        out = start.matrix.dot(p)
        checks = out[r:].tolist()
        if max(checks) <= 0.0:
            self._keep(start)
            return out[:r]
        return self._moves(start, checks, p, POLISH_MOVES)

    def _active(self, solution: Solution) -> int:
        """The active set OSQP's answer shows: the bounds by OSQP's own polishing rule (in its
        normalised units, a row is active at a bound nearer than its multiplier is large), and
        with beta > 0 the minimax row of the largest force. (OSQP's minimax rows say little: with
        Q >> W in the cost, beta fbar is below its relative tolerance when a request saturates.)"""
        qp, rows = self._qp, self._index["box"]
        value = solution.x[:self._r]
        scale = qp.row_scale[rows]
        y = solution.y[rows] * qp.cost_scale / scale
        upper = (qp.up[rows] - value) * scale < y
        lower = (value - qp.low[rows]) * scale < -y
        r = self._r
        key = 0
        for i in range(r):
            if upper[i] and (y[i] >= 0.0 or not lower[i]):
                key |= 1 << 2 * i
            elif lower[i]:
                key |= 1 << 2 * i + 1
        return key | self.law.near_largest(value, NEAR * self.model.force_scale)

    # -- the OSQP problem of the misses -------------------------------------------------

    @staticmethod
    def _rows(model: Model) -> tuple:
        """z = [f (r), s (n), fbar]: T f - s = tau; f_min <= f <= f_max; -fbar <= f_i <= fbar;
        fbar >= 0 (the minimax rows and fbar switched off by their bounds when beta = 0)."""
        r, n = model.r, model.n
        top = r + n
        rows = Rows()
        equality = [rows.add([(c, float(model.t_ec[k, c])) for c in range(r)] + [(r + k, -1.0)]) for k in range(n)]
        box = [rows.add([(i, 1.0)]) for i in range(r)]
        minimax = [rows.add([(i, 1.0), (top, sign)]) for i in range(r) for sign in (-1.0, 1.0)]
        last = rows.add([(top, 1.0)])
        return rows.matrix(r + n + 1), dict(equality=np.array(equality), box=np.array(box),
                                            minimax=np.array(minimax), last=last)

    @staticmethod
    def _objective(model: Model) -> tuple[np.ndarray, np.ndarray]:
        """Diagonal of P and q of (1.35) (OSQP minimises 1/2 z'Pz + q'z)."""
        q = np.zeros(model.r + model.n + 1)
        q[-1] = model.vehicle.weights.minimax
        return np.concatenate((2.0 * model.weight, 2.0 * model.slack_weights(model.weight), [0.0])), q

    def _constant_bounds(self, model: Model) -> None:
        qp, index = self._qp, self._index
        minimax = model.vehicle.weights.minimax > 0.0
        qp.low[index["minimax"][0::2]], qp.up[index["minimax"][0::2]] = -math.inf, (0.0 if minimax else math.inf)
        qp.low[index["minimax"][1::2]], qp.up[index["minimax"][1::2]] = (0.0 if minimax else -math.inf), math.inf
        qp.low[index["last"]], qp.up[index["last"]] = 0.0, (math.inf if minimax else 0.0)

    def _setup(self, model: Model) -> None:
        a, index = self._rows(model)
        p, q = self._objective(model)
        column_scale = np.concatenate((model.force_scale, np.maximum(model.authority, 1e-9),
                                       [float(np.max(model.force_scale))]))
        self._qp = ScaledProblem(p, q, a, column_scale, model.vehicle.solver, effort=np.arange(model.r),
                                 backend=self.backend())
        self._index = index
        self._constant_bounds(model)
        self.setups += 1
