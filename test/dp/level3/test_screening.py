"""The Level 3 screening estimate: the linearised closed loop's excursion against the Monte Carlo
of the Level 3 case runs (the horizontal standard deviation after settling, over seeds), within
20 % at three headings and three conditions, through the rows the report writes: with the setup
the Level 3 study prepares (the DP system: observer, noise, wave motion in the measurement, wind
feed-forward, thrust losses), and with the controller on the true state (``dp_system`` off, the
plain loop); the thrust losses' factor on the loop's gain against its mean."""

from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg.dp.level3.case import INTACT, Case, Criteria, run_case
from allocator_pkg.dp.level3.screening import SCREENING_TABLE, screening_table, thrust_factor
from allocator_pkg.dp.level3.study import Level3Inputs, prepare
from allocator_pkg.simulation.thrust_losses import LossCase, ThrustLosses

HEADINGS = (0.0, 45.0, 90.0)
NUMBERS = (3, 5, 6)
SEEDS = 2
INPUTS = Level3Inputs(ROOT / "config/dp_vessel.yaml", ROOT / "config/particulars/dp_vessel.yaml",
                      heading_step=45.0, criteria=Criteria(50.0, 30.0, settle=60.0, duration=400.0))


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=6), st.integers(0, 3))
def test_the_loss_factor_is_the_intact_cases_mean_over_the_actuators(factors, unnamed):
    names = tuple(f"a{i}" for i in range(len(factors) + unnamed))
    failed = LossCase(frozenset({"a0"}), {"a1": 0.1})
    losses = ThrustLosses((failed, LossCase(frozenset(), dict(zip(names, factors)))))
    assert thrust_factor(losses, names) == pytest.approx((sum(factors) + unnamed) / len(names))
    assert thrust_factor(None, names) == 1.0


@pytest.mark.slow
@pytest.mark.parametrize("dp_system", [True, False])
def test_the_screening_estimate_agrees_with_the_monte_carlo_within_20_percent(dp_system):
    setup = prepare(INPUTS).setup
    assert setup.dp_system
    setup = replace(setup, dp_system=dp_system)
    finished = {}
    for heading in HEADINGS:
        for number in NUMBERS:
            for seed in range(SEEDS):
                result = run_case(Case(heading, number, INTACT, seed), setup)
                finished[result.case.key] = result
    title, columns, table = screening_table(setup, finished)
    assert title == SCREENING_TABLE[dp_system]
    rows = [dict(zip(columns, row, strict=True)) for row in table]
    assert [(r["heading_deg"], r["capability_number"], r["seeds"]) for r in rows] == [
        (h, n, SEEDS) for h in HEADINGS for n in NUMBERS]
    for row in rows:
        estimate = np.hypot(row["fd_north_std_m"], row["fd_east_std_m"])
        measured = np.hypot(row["td_north_std_m"], row["td_east_std_m"])
        assert estimate == pytest.approx(measured, rel=0.20), row
