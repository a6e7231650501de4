"""The weighted generalised inverse (1.29) of the extended configuration (1.32)-(1.34): gain
matrices G with f_e = G tau, computed from the geometry and the weights of the actuators
usable, once per set of them and cached (never per sample).

f_e = W^-1 T_e' (T_e W^-1 T_e')^-1 tau, computed as W^-1/2 pinv(T_e W^-1/2) so that it also
answers (in the least-squares sense) when some DOF cannot be produced. With DOF priorities,
:meth:`PseudoInverseGains.cascade` gives each level's gain in the weighted null space of the
levels above (the task-priority inverse). The ``pseudoinverse`` and ``svd_filter`` methods,
the allocator's fallback, its planning of rotatable thrusters (1.33) and the capability
analysis read these gains."""

from __future__ import annotations

import math

import numpy as np

from .model import Model

CACHE_SIZE = 64
"""Gain matrices a :class:`PseudoInverseGains` keeps; when full it starts again."""


class PseudoInverseGains:
    """Cached gain matrices of the weighted pseudo-inverse (1.29) of T_e, one per subset of
    usable actuators (a configuration's cache: never computed per sample)."""

    def __init__(self, model: Model):
        self.model = model
        self._cache: dict[tuple, np.ndarray] = {}

    def gain(self, excluded: np.ndarray, lines: dict[int, float]) -> np.ndarray:
        """G (m x n) with f_e = G tau for the actuators not ``excluded``; a rotatable
        thruster in ``lines`` may only push along its given angle."""
        return self._cached(("gain", excluded.tobytes(), tuple(sorted(lines.items()))),
                            lambda: self._compute(excluded, lines))

    def cascade(self, excluded: np.ndarray, lines: dict[int, float],
                levels: tuple[tuple[int, ...], ...]) -> list[tuple[np.ndarray, np.ndarray]]:
        """Per priority level, highest first, (its rows of tau, G_k): the force a level adds
        for a residual r_k of its rows is G_k r_k, in the weighted null space of every level
        above it."""
        return self._cached(("cascade", excluded.tobytes(), tuple(sorted(lines.items())), levels),
                            lambda: self._compute_cascade(excluded, lines, levels))

    def _cached(self, key: tuple, compute):
        value = self._cache.get(key)
        if value is None:
            if len(self._cache) >= CACHE_SIZE:
                self._cache.clear()
            value = compute()
            self._cache[key] = value
        return value

    def _compute(self, excluded: np.ndarray, lines: dict[int, float]) -> np.ndarray:
        basis = self._basis(excluded, lines)
        if basis is None:
            return np.zeros((self.model.m, self.model.n))
        return basis @ np.linalg.pinv(self.model.t_ec @ basis, rcond=1e-10)

    def _compute_cascade(self, excluded: np.ndarray, lines: dict[int, float],
                         levels: tuple[tuple[int, ...], ...]) -> list[tuple[np.ndarray, np.ndarray]]:
        basis = self._basis(excluded, lines)
        result = []
        projector = None if basis is None else np.eye(basis.shape[1])
        for level in levels:
            rows = np.array(level, dtype=int)
            if basis is None:
                result.append((rows, np.zeros((self.model.m, rows.size))))
                continue
            restricted = self.model.t_ec[rows] @ basis @ projector
            inverse = np.linalg.pinv(restricted, rcond=1e-10)
            result.append((rows, basis @ inverse))
            projector = projector - inverse @ restricted
        return result

    def _basis(self, excluded: np.ndarray, lines: dict[int, float]) -> np.ndarray | None:
        """The usable extended directions scaled by W^-1/2 (m x b), or None when none is."""
        model = self.model
        basis_columns: list[np.ndarray] = []
        weights: list[float] = []
        for i, start in enumerate(model.starts):
            if excluded[i]:
                continue
            if model.rotatable[i]:
                pairs = [(math.cos(lines[i]), math.sin(lines[i]))] if i in lines else [(1.0, 0.0), (0.0, 1.0)]
                for c1, c2 in pairs:
                    column = np.zeros(model.m)
                    column[start], column[start + 1] = c1, c2
                    basis_columns.append(column)
                    weights.append(model.weight[i])
            else:
                column = np.zeros(model.m)
                column[start] = 1.0
                basis_columns.append(column)
                weights.append(model.weight[i])
        if not basis_columns:
            return None
        return np.column_stack(basis_columns) / np.sqrt(np.asarray(weights))
