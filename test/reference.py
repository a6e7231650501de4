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


def weighted_l1_allocation(t, w, q, low, high, tau):
    """The survey's LP criterion (5.3) for non-rotating actuators, by scipy's HiGHS:
    min sum w_i |f_i| + sum q_k |s_k| s.t. T f - s = tau, low <= f <= high. Variables
    [f+, f-, s+, s-] >= 0; returns (f, the optimal cost)."""
    n, r = t.shape
    cost = np.concatenate([w, w, q, q])
    a_eq = np.hstack([t, -t, -np.eye(n), np.eye(n)])
    bounds = ([(max(lo, 0.0), max(hi, 0.0)) for lo, hi in zip(low, high)]
              + [(max(-hi, 0.0), max(-lo, 0.0)) for lo, hi in zip(low, high)] + [(0.0, None)] * (2 * n))
    result = linprog(cost, A_eq=a_eq, b_eq=tau, bounds=bounds, method="highs")
    return result.x[:r] - result.x[r:2 * r], result.fun


def circle_allocation(t_e, w_ext, q, columns, boxes, circles, tau):
    """min 1/2 f'Wf + 1/2 s'Qs, s = T_e f - tau, with box limits on the columns of non-rotating
    actuators and |(f_2j, f_2j+1)| <= B_j for rotatable ones, by SLSQP from the unconstrained
    optimum (a convex problem). ``columns``: per actuator, its column or its pair; ``boxes``
    and ``circles``: {actuator: (low, high)} and {actuator: B}. Returns the extended forces."""
    from scipy.optimize import minimize

    scale = np.ones(t_e.shape[1])
    for i, (low, high) in boxes.items():
        scale[columns[i]] = max(high, -low, 1e-9)
    for i, radius in circles.items():
        scale[list(columns[i])] = radius
    weight = w_ext * scale * scale
    matrix = t_e * scale
    reference = float(np.max(weight))

    def cost(x):
        miss = matrix @ x - tau
        return 0.5 * float(x @ (weight * x) + miss @ (q * miss)) / reference

    def gradient(x):
        return (weight * x + matrix.T @ (q * (matrix @ x - tau))) / reference

    bounds = [(None, None)] * t_e.shape[1]
    for i, (low, high) in boxes.items():
        bounds[columns[i]] = (low / scale[columns[i]], high / scale[columns[i]])
    constraints = [{"type": "ineq", "fun": lambda x, a=a, b=b: 1.0 - x[a] ** 2 - x[b] ** 2,
                    "jac": lambda x, a=a, b=b: -2.0 * np.eye(len(x))[a] * x[a] - 2.0 * np.eye(len(x))[b] * x[b]}
                   for a, b in (columns[i] for i in circles)]
    start = np.zeros(t_e.shape[1])
    result = minimize(cost, start, jac=gradient, method="SLSQP", bounds=bounds, constraints=constraints,
                      options={"maxiter": 1000, "ftol": 1e-16})
    return result.x * scale


def bounded_least_squares(t, w, q, low, high, tau):
    """(1.35) with beta = 0 and the slack eliminated, min f'Wf + (Tf - tau)'Q(Tf - tau) with
    low <= f <= high, as the bounded least-squares problem it is: scipy's BVLS on
    [sqrt(Q) T; sqrt(W)] f ~ [sqrt(Q) tau; 0] (QR based, so a Q a million times W costs no
    accuracy, as it can in a dual active-set QP)."""
    from scipy.optimize import lsq_linear

    a = np.vstack([np.sqrt(q)[:, None] * t, np.diag(np.sqrt(w))])
    b = np.concatenate([np.sqrt(q) * tau, np.zeros(t.shape[1])])
    return lsq_linear(a, b, bounds=(low, high), method="bvls", tol=1e-14).x


def lexicographic_allocation(t, low, high, tau, levels, weights):
    """DOF priorities solved independently: level by level (rows of ``t`` in ``levels``,
    highest first), scipy's SLSQP minimises that level's weighted squared wrench error
    sum_j weights_j (t_j f - tau_j)^2 within the force bounds, with every higher level's
    achieved wrench held as an equality constraint. Returns the achieved wrench t f."""
    from scipy.optimize import minimize

    scale = np.maximum(np.abs(low), np.abs(high))
    ts = t * scale                                  # variables x = f / scale, of order one
    bounds = list(zip(low / scale, high / scale))
    x = np.zeros(t.shape[1])
    held: list[tuple[np.ndarray, np.ndarray]] = []
    for level in levels:
        rows = np.array(level)
        a, b, w = ts[rows], tau[rows], weights[rows]

        def cost(x, a=a, b=b, w=w):
            r = a @ x - b
            return float(np.sum(w * r * r))

        def gradient(x, a=a, b=b, w=w):
            return 2.0 * a.T @ (w * (a @ x - b))

        constraints = [{"type": "eq", "fun": (lambda x, a=ha, v=hv: a @ x - v), "jac": (lambda x, a=ha: a)}
                       for ha, hv in held]
        starts = [x, np.zeros_like(x), *np.random.default_rng(0).uniform(-0.5, 0.5, (4, x.size))]
        for start in starts:                         # SLSQP may stall at a degenerate start: try others
            result = minimize(cost, start, jac=gradient, bounds=bounds, constraints=constraints, method="SLSQP",
                              options={"ftol": 1e-12, "maxiter": 1000})
            if result.success:
                break
        assert result.success, result.message
        x = result.x
        held.append((a, a @ x))
    return ts @ x
