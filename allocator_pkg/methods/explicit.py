"""Allocation method ``explicit``: (1.35) answered by the piecewise-affine law of
:mod:`~.explicit_law` (survey section 4.1), region by region as the requests reach them.

A sample in the previous sample's region costs one matrix-vector product; otherwise a few
primal-dual moves lead to a neighbouring region, else OSQP solves (1.35), warm-started, and
its active set is polished to the exact region. Laws are cached (least recently used out)
beside an optional precomputed table (``explicit.regions``). Faults, rate limits, speed and
voltage are parameters of the law; only T, W, Q and beta are data. Rotatable thrusters and
saturation other than ``weighted`` are refused. docs/theory.md (section `explicit`) has the
theory, docs/performance.md the cost.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import replace

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from ..solvers import BackendFactory
from ..solvers.outcome import Outcome, Solution
from ..solvers.problem import Rows, ScaledProblem
from ..vehicle.config import Vehicle
from .base import CIRCLE_SIDES, AllocationMethod, MethodOutput
from .explicit_law import Law, Region, read_regions

CAPACITY = 512
"""Laws kept (least recently used out first), each a few kilobytes; docs/performance.md shows
how many the benchmark's sequences visit."""

MOVES = 4
"""Neighbour moves tried from the previous region before OSQP is asked."""

POLISH_MOVES = 12
"""Neighbour moves tried from the active set read from OSQP's answer."""

NEAR = 1e-3
"""With beta > 0, OSQP's forces within this fraction of their range of the largest count as
equal to it (OSQP stops at 1e-5 of the ranges by default)."""

TIGHT = 1e-10
"""OSQP's tolerances for a second solve when the active set of the first does not lead to a
region (fractions of the variables' ranges)."""

TIGHT_ITERATIONS = 20000
"""OSQP's iteration limit for that second solve; only a converged one (``Outcome.SOLVED``) is used."""


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
