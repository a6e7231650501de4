"""Allocation methods, one module each: ``pseudoinverse`` (1.29)/(1.33), ``qp`` (1.35) on
OSQP, ``nonlinear`` (1.44) by sequential QPs (1.45). Each exposes ``solve(tau, limits)``."""
