"""allocator_pkg.capability.load_filter: the consequence analysis' load is the first-order lag of
the requests (time constant T), the request itself first, after a restart, when the clock went
back or without a filter (T <= 0)."""

import math

import numpy as np

from allocator_pkg.allocation.sample_rules import NS
from allocator_pkg.capability.load_filter import LoadFilter

AHEAD = np.array([500e3, 0.0, 0.0, 0.0, 0.0, 30e3])


def test_a_step_is_lagged_by_the_time_constant():
    load = LoadFilter()
    load.observe(np.zeros(6), 0, 10.0)
    for k in range(1, 51):                                      # 5 s of a step at 10 Hz
        load.observe(AHEAD, k * NS // 10, 10.0)
    np.testing.assert_allclose(load.load, AHEAD * (1.0 - math.exp(-0.5)), rtol=1e-12)


def test_the_request_itself_first_after_a_restart_a_clock_going_back_or_without_a_filter():
    load = LoadFilter()
    load.observe(AHEAD, 5 * NS, 10.0)
    np.testing.assert_array_equal(load.load, AHEAD)
    load.observe(-AHEAD, 4 * NS, 10.0)                          # the clock went back
    np.testing.assert_array_equal(load.load, -AHEAD)
    load.restart()
    load.observe(2.0 * AHEAD, 6 * NS, 10.0)
    np.testing.assert_array_equal(load.load, 2.0 * AHEAD)
    load.observe(AHEAD, 7 * NS, 0.0)                             # no filter
    np.testing.assert_array_equal(load.load, AHEAD)
