"""Independent reference solutions for tests: written from the survey's formulas with
plain numpy, quadprog and scipy, sharing no code with the allocator."""

import numpy as np
import quadprog
from scipy.optimize import linprog


def weighted_pseudo_inverse(t: np.ndarray, w: np.ndarray) -> np.ndarray:
    """(1.29): W^-1 T' (T W^-1 T')^-1."""
    w_inv = np.diag(1.0 / w)
    return w_inv @ t.T @ np.linalg.inv(t @ w_inv @ t.T)


def constrained_allocation(t, w, q, low, high, tau, beta=0.0):
    """(1.35) solved by quadprog's dual active-set method; returns f.

    Variables z = [f, s, fbar]; quadprog minimises 1/2 z'Gz - a'z s.t. C'z >= b (first
    ``meq`` rows equalities)."""
    r, n = t.shape[1], t.shape[0]
    size = r + n + 1
    g = np.zeros((size, size))
    g[:r, :r] = np.diag(2.0 * w)
    g[r:r + n, r:r + n] = np.diag(2.0 * q)
    g[-1, -1] = 1e-9 * max(np.max(w), 1.0)          # quadprog needs G positive definite
    a = np.zeros(size)
    a[-1] = -beta
    rows, rhs = [], []
    for k in range(n):                               # T f - s = tau
        row = np.zeros(size)
        row[:r], row[r + k] = t[k], -1.0
        rows.append(row)
        rhs.append(tau[k])
    for i in range(r):
        for sign, bound in ((1.0, low[i]), (-1.0, -high[i])):     # f >= low, -f >= -high
            row = np.zeros(size)
            row[i] = sign
            rows.append(row)
            rhs.append(bound)
        for sign in (1.0, -1.0):                                   # fbar - |f_i| >= 0
            row = np.zeros(size)
            row[i], row[-1] = -sign, 1.0
            rows.append(row)
            rhs.append(0.0)
    z = quadprog.solve_qp(g, a, np.array(rows).T, np.array(rhs), meq=n)[0]
    return z[:r]


def largest_attainable_scale(t, low, high, tau):
    """Durham's direct idea (4.3): max lambda in [0, 1] with lambda tau = T f, low <= f <= high."""
    r = t.shape[1]
    cost = np.zeros(r + 1)
    cost[-1] = -1.0
    a_eq = np.hstack([t, -tau.reshape(-1, 1)])
    result = linprog(cost, A_eq=a_eq, b_eq=np.zeros(len(tau)),
                     bounds=[(lo, hi) for lo, hi in zip(low, high)] + [(0.0, 1.0)], method="highs")
    return result.x[-1]
