"""Allocation method ``nonlinear``: the nonlinear problem (1.44) by sequential linearised QPs
(1.45), after Johansen et al. (2004).

Each QP, on one warm-started OSQP problem, takes the force changes of every actuator, the angle
changes of the rotatable thrusters and the slack: the power replaced near f0 by a quadratic with
its gradient, angle steps weighted by the curvature of the Lagrangian, the singularity term as a
linear cost, and an idle thruster sent toward the steepest descent. The variables are scaled to
forces, so that ADMM sees no direction far flatter than the others. docs/theory.md (section
`nonlinear`) has the QP and why each term is as it is; docs/performance.md the cost.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..effectiveness.model import Model, SampleLimits
from ..effectiveness.zones import potential_rotations
from ..solvers import BackendFactory
from ..solvers.problem import Rows, ScaledProblem, entry_index
from ..vehicle.config import SolverSettings, Vehicle
from .base import CIRCLE_SIDES, AllocationMethod, MethodOutput

POWER_CURVATURE = 1.25
"""The power's curvature in each linearised QP, as a multiple of its true curvature at f0,
3/4 P_i / sqrt(|f0_i|). 2 is c_i f_i^2 with c_i = 3/4 P_i / sqrt(|f0_i|), which lies above
P_i |f_i|^(3/2) everywhere and so never overshoots, but each step goes only half way and the
angles settle slowly; 1 is Newton's step, which overshoots where angles and forces trade
against each other. docs/theory.md (`nonlinear`) gives the cases; bench/settling.py measures
them."""

TOLERANCE_SHARE = 0.1
"""The linearised QPs are solved to this share of ``solver.eps_abs`` and ``eps_rel`` (and a
stopped solve's iterate is used within this share of the usual residual). The iteration runs
across samples on the QPs' answers, primal and dual (the multipliers set the angles'
curvature), and a warm-started solve stops as soon as it is within tolerance: where the
optimum lies in a nearly flat valley (both azimuths at full thrust, the tunnels trading yaw),
answers within the usual tolerance let the angles drift along it (docs/theory.md, `nonlinear`)."""

IDLE_PRICE = 1e-2
"""An idle thruster turns toward the direction of steepest descent only when a push along it is
worth at least this share of the largest price (|y' t|) of any actuator: noise in the
multipliers turns nothing."""

FORCE_FLOOR = 1e-2
"""|f0| is taken as at least this fraction of the force range in c_i, infinite at zero force."""

TRUST_STEP = 0.25 * math.pi
"""[rad] The largest angle change of one linearisation when no rate limit bounds it: (1.45)
is a model of T(alpha) near alpha_0 only."""


def _settings(model: Model) -> SolverSettings:
    """The configured solver settings with the tolerances tightened (TOLERANCE_SHARE)."""
    solver = model.vehicle.solver
    return replace(solver, eps_abs=TOLERANCE_SHARE * solver.eps_abs, eps_rel=TOLERANCE_SHARE * solver.eps_rel)


def _reference_curvature(model: Model) -> np.ndarray:
    """c_i at half of each actuator's force range."""
    force = 0.5 * model.force_scale
    return np.where(model.power > 0.0, 0.75 * model.power / np.sqrt(force), model.weight)


def _turning_curvature(power: np.ndarray, force: np.ndarray) -> np.ndarray:
    """Curvature of the Lagrangian of (1.44) along a thruster's angle, -f y't(alpha): at an
    unsaturated optimum y't = -d(P|f|^(3/2))/df, so it equals 3/2 P |f|^(3/2)."""
    return 1.5 * power * force ** 1.5


class NonlinearAllocation(AllocationMethod):
    """Allocation method ``nonlinear``."""

    name = "nonlinear"

    def __init__(self, model: Model, backend: BackendFactory):
        super().__init__(model, backend)
        self._setup(model)

    @classmethod
    def thrust_region_sides(cls, vehicle: Vehicle) -> int | None:
        return CIRCLE_SIDES

    def update_model(self, model: Model) -> None:
        """Take a configuration with the same structure: values only, no new set-up."""
        self._use(model)
        self._qp.update_objective(self._p(model))
        self._qp.update_settings(_settings(model))

    def _use(self, model: Model) -> None:
        """The configuration and its per-configuration constants of the per-sample path."""
        self.model = model
        rot = model.rot
        self._first, self._second = model.t_ec[:, model.rot_columns[:, 0]], model.t_ec[:, model.rot_columns[:, 1]]
        self._t_fixed = np.zeros((model.n, model.r))
        self._t_fixed[:, model.scalar] = model.t_ec[:, model.scalar_columns]
        self._no_turning = np.zeros((model.n, 0))
        self._powered = model.power > 0.0
        self._all_powered = bool(self._powered.all())
        # The QP's coefficient of Delta f^2 is POWER_CURVATURE / 2 times c_i = 3/4 P_i / sqrt|f0_i|
        # where the cost is the power (W_ii where it is the quadratic W_ii f_i^2 itself), and q
        # keeps the true gradient 2 c_i f0_i: 2 sqrt(coefficient) f0 * q_gain in the QP's units.
        share = np.where(self._powered, 0.5 * POWER_CURVATURE, 1.0)
        self._c_gain = 0.75 * model.power * share
        self._q_gain = 2.0 / share
        rotations = potential_rotations(model.vehicle)
        self._cut = [(k, i) for k, i in enumerate(rot.tolist())
                     if not (rotations[i].continuous and not rotations[i].forbidden_sectors)]
        self._hold = model.hold[rot].tolist()
        self._missing = model.dof_tolerance
        self._turning_gain = 1.5 * model.power[rot]
        self._multipliers = np.zeros(model.n)
        self._trust = np.minimum(model.angle_step[model.rot], TRUST_STEP)
        self._p_diagonal = self._p(model)
        self._floor = FORCE_FLOOR * np.maximum(model.force_scale, 1e-6)
        self._dof_scale = model.dof_scale

    @staticmethod
    def _p(model: Model) -> np.ndarray:
        """P's diagonal at a reference point (half of each force range); the angles' part
        changes with every linearisation."""
        lever = 0.5 * model.force_scale[model.rot]
        turning = model.vehicle.weights.azimuth_change + _turning_curvature(model.power[model.rot], lever)
        return np.concatenate((np.full(model.r, 2.0), 2.0 * turning / (lever * lever),
                               2.0 * model.slack_weights(_reference_curvature(model))))

    def _setup(self, model: Model) -> None:
        self._use(model)
        r, p, n = model.r, model.rot.size, model.n
        rows = Rows()
        equality = [
            rows.add([(j, 1.0) for j in range(r)] + [(r + k, 1.0) for k in range(p)] + [(r + p + d, -1.0)])
            for d in range(n)
        ]
        for j in range(r + p):
            rows.add([(j, 1.0)])
        a = rows.matrix(r + p + n)
        index_force = [[entry_index(a, row, j) for j in range(r)] for row in equality]
        index_angle = [[entry_index(a, row, r + k) for k in range(p)] for row in equality]
        self._ax_index = np.concatenate((np.array(index_force, np.int64).ravel(),
                                         np.array(index_angle, np.int64).reshape(-1)))
        self._equality = np.array(equality, int)
        force = model.force_scale
        c = _reference_curvature(model)
        column_scale = np.concatenate((np.sqrt(c) * force, force[model.rot], np.maximum(model.authority, 1e-9)))
        self._q = np.zeros(r + p + n)
        self._qp = ScaledProblem(self._p(model), self._q, a, column_scale, _settings(model), effort=np.arange(r),
                                 backend=self.backend())
        self.setups += 1

    def solve(self, tau: np.ndarray, limits: SampleLimits) -> MethodOutput:
        model = self.model
        rot = model.rot
        qp = self._qp
        n, r, p = model.n, model.r, rot.size
        low, high = limits.low, limits.high
        force = np.minimum(np.maximum(limits.thrust, low), high)
        angle = limits.angle.copy()
        angle_low = np.array([lim.low for lim in limits.azimuth])
        angle_high = np.array([lim.high for lim in limits.azimuth])
        angle[rot] = np.minimum(np.maximum(angle[rot], angle_low), angle_high)
        trust, omega, floor = self._trust, model.vehicle.weights.azimuth_change, self._floor
        iterations = 0
        status = ""
        passes = model.vehicle.nonlinear_max_iterations
        miss = math.inf
        t, dt = self._matrices(angle[rot])
        for _ in range(passes):
            size = np.maximum(np.abs(force), floor)
            c = self._c_gain / np.sqrt(size) if self._all_powered else \
                np.where(self._powered, self._c_gain / np.sqrt(size), model.weight)
            root = np.sqrt(c)
            spun, lever = force[rot], size[rot]
            curvature = np.maximum(self._turning_gain * lever ** 1.5, -spun * (self._multipliers @ t[:, rot]))
            self._p_diagonal[r:r + p] = (2.0 * (omega + curvature)) / (lever * lever)
            qp.update_matrix(np.concatenate(((t / root).ravel(), (dt * (spun / lever)).ravel())), self._ax_index,
                             self._p_diagonal)
            qp.low[:n] = qp.up[:n] = tau - t @ force
            qp.low[n:n + r] = root * (low - force)
            qp.up[n:n + r] = root * (high - force)
            here = angle[rot]
            qp.low[n + r:] = np.maximum(angle_low - here, -trust) * lever
            qp.up[n + r:] = np.minimum(angle_high - here, trust) * lever
            self._q[:r] = self._q_gain * root * force
            if p and model.vehicle.singularity_rho > 0.0:
                self._q[r:r + p] = self._singularity_gradient(t, dt, limits) / lever
            solution = qp.solve(qp.low, qp.up, q=self._q)
            iterations += solution.iterations
            status = solution.status
            if not solution.usable:
                return MethodOutput(force=np.zeros(model.m), status=status, iterations=iterations,
                                    outcome=solution.outcome)
            self._multipliers = solution.y[:n]
            x = solution.x
            new_force = np.minimum(np.maximum(force + x[:r] / root, low), high)
            new_angle = angle.copy()
            new_angle[rot] = np.minimum(np.maximum(here + x[r:r + p] / lever, angle_low), angle_high)
            if passes > 1:
                # Another pass linearises around the new point; from a poor one (thrusters at
                # rest: dT/dalpha f = 0) it can overshoot, so a pass that misses tau by more
                # than the last one (each DOF against its authority, as the default Q weighs
                # them) is dropped and the passes stop.
                t_new, dt_new = self._matrices(new_angle[rot])
                new_miss = float(np.sum(((t_new @ new_force - tau) / self._dof_scale) ** 2))
                if new_miss >= miss:
                    break
                miss, t, dt = new_miss, t_new, dt_new
            force, angle = new_force, new_angle
        extended = force[model.extended_owner]
        turn = None
        if p:
            spun = angle[rot]
            extended[model.rot_columns[:, 0]] *= np.cos(spun)
            extended[model.rot_columns[:, 1]] *= np.sin(spun)
            if self._idle_turning(limits):
                idle = [k for k, (f, hold) in enumerate(zip(force[rot].tolist(), self._hold)) if abs(f) <= hold]
                if idle:
                    turn = self._idle_turns(tau, extended, limits, idle)
        return MethodOutput(force=extended, status=status, iterations=iterations, angle=angle, turn=turn)

    def _idle_turning(self, limits: SampleLimits) -> bool:
        """Whether idle thrusters may be sent turning this sample: when every rotatable
        thruster whose forces a sector cuts (a flushing zone counted even while it is lifted) is
        out of play (failed, its static range zero, or stuck), as the piece planner then has no
        side to choose."""
        if not self._cut:
            return True
        range_low = limits.low if limits.range_low is None else limits.range_low
        range_high = limits.high if limits.range_high is None else limits.range_high
        return all(limits.azimuth[k].line or range_high[i] <= range_low[i] for k, i in self._cut)

    def _idle_turns(self, tau: np.ndarray, extended: np.ndarray, limits: SampleLimits,
                    idle: list[int]) -> dict[int, float] | None:
        """Directions for the ``idle`` rotatable thrusters (indices into ``model.rot``) to turn
        toward, while the wrench misses the request: with y the multipliers of the last QP's
        equality rows and a, b a thruster's columns of T_e, a push F along angle beta changes
        the Lagrangian of (1.44) by F y'(a cos beta + b sin beta) (the power's gradient is zero
        at zero thrust), which falls fastest along -(y'a, y'b). A thruster whose push along its
        own angle (on its side sigma) would not lower it is sent that way; one whose push would
        is left to the next QP, which pushes. The angle judged is the thruster's own: an idle
        thruster's angle in the QPs' answer is not commanded."""
        model = self.model
        if not np.any(np.abs(model.t_ec @ extended - tau) > self._missing):
            return None
        y = self._multipliers
        price_x, price_y = (y @ self._first).tolist(), (y @ self._second).tolist()
        prices = [math.hypot(x, z) for x, z in zip(price_x, price_y)]
        largest = max(max(prices), float(np.max(np.abs(y @ self._t_fixed))))
        turns = {}
        for k in idle:
            i = int(model.rot[k])
            lim = limits.azimuth[k]
            if lim.line or lim.magnitude_max == 0.0 or prices[k] <= IDLE_PRICE * largest:
                continue
            alpha = float(limits.angle[i])
            if lim.sigma * (price_x[k] * math.cos(alpha) + price_y[k] * math.sin(alpha)) < 0.0:
                continue
            direction = math.atan2(-price_y[k], -price_x[k])
            turns[i] = direction if lim.sigma > 0 else direction + math.pi
        return turns or None

    def _matrices(self, spun: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """T(alpha) (n x r) and dT/dalpha of the rotatable thrusters (n x p) on the
        controlled DOFs, from the constant T_e, at the rotatable thrusters' angles ``spun``."""
        t = self._t_fixed.copy()
        if not spun.size:
            return t, self._no_turning
        cos, sin = np.cos(spun), np.sin(spun)
        t[:, self.model.rot] = cos * self._first + sin * self._second
        return t, cos * self._second - sin * self._first

    def _singularity_gradient(self, t: np.ndarray, dt: np.ndarray, limits: SampleLimits) -> np.ndarray:
        """Gradient over the rotatable angles of rho / (eps + det(T W^-1 T')), the
        linearised singularity term of (1.45): d det(M) = tr(adj(M) dM)."""
        model = self.model
        pinned = (limits.low == 0.0) & (limits.high == 0.0)
        inverse_weight = np.where(pinned, 0.0, 1.0 / model.weight)
        m = (t * inverse_weight) @ t.T
        values, vectors = np.linalg.eigh(m)
        determinant = float(np.prod(values))
        others = np.array([np.prod(np.delete(values, i)) for i in range(len(values))])
        adjugate = (vectors * others) @ vectors.T
        rot = model.rot
        d_det = 2.0 * inverse_weight[rot] * np.einsum("ik,ij,jk->k", t[:, rot], adjugate, dt[:, rot])
        rho, epsilon = model.vehicle.singularity_rho, model.vehicle.singularity_epsilon
        return -rho * d_det / (epsilon + determinant) ** 2
