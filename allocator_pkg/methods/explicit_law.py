"""The piecewise-affine law of (1.35) for actuators of fixed direction (survey section 4.1,
(1.37)-(1.41)): the optimum of one active set as an affine function of the parameters
p = [tau, f_min, f_max].

:class:`Law` is the normalised problem and solves the optimality (KKT) conditions of any
active set; :class:`Region` holds one set's forces and checks as one matrix over
p_1 = [p, 1] and names the neighbouring set when a check fails; :func:`read_regions` reads
the active sets ``allocator-explicit precompute`` wrote. docs/theory.md (section `explicit`)
derives it.
"""

from __future__ import annotations

import hashlib
import zipfile
from dataclasses import dataclass

import numpy as np
from numpy.lib.npyio import NpzFile

from ..effectiveness.model import Model

PRIMAL_TOLERANCE = 1e-9
"""A constraint counts as met within this fraction of its actuator's force range."""

DUAL_TOLERANCE = 1e-9
"""A multiplier counts as non-negative above -this, in units of its actuator's effort
gradient at full force (2 W_ii times its range): relative to each actuator, so that a large
one does not blunt the checks of a small one."""

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
