"""The OSQP problem wrapper: a SIGINT that OSQP swallows while it solves reaches the process."""

import os
import signal
import threading
import time

import numpy as np
import scipy.sparse as sp

from allocator_pkg.methods.sparse_rows import ScaledProblem, solver_settings


def test_sigint_during_a_solve_is_raised_again_for_the_process():
    """OSQP installs its own SIGINT handler while it iterates and just stops (status
    'interrupted'); without passing it on, Ctrl-C or a launch system's SIGINT would be lost
    and the node would keep running."""
    size = 300
    rng = np.random.default_rng(0)
    a = sp.random(size, size, density=0.2, random_state=1, format="csc")
    a.sort_indices()
    problem = ScaledProblem(np.ones(size), rng.normal(size=size), a, np.ones(size),
                            solver_settings(1e-15, 1e-15, 10**9, 20.0), np.arange(size))
    received = []
    previous = signal.signal(signal.SIGINT, lambda *_: received.append(time.monotonic()))
    try:
        threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT)).start()
        solution = problem.solve(-np.ones(size), np.ones(size))
    finally:
        signal.signal(signal.SIGINT, previous)
    assert solution.status == "interrupted" and not solution.usable
    assert len(received) == 1
