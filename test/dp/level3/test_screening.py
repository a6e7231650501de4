"""The Level 3 screening estimate: the linearised closed loop's excursion against the Monte Carlo
of the Level 3 case runs (the horizontal standard deviation after settling, over seeds), within
20 % at three headings and three conditions, through the rows the report writes."""

from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.level3.case import INTACT, Case, CaseSetup, Criteria, run_case
from allocator_pkg.dp.level3.screening import SCREENING_TABLE, screening_table
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS
from allocator_pkg.simulation.scenario import load_scenario

HEADINGS = (0.0, 45.0, 90.0)
NUMBERS = (3, 5, 6)
SEEDS = 2


@pytest.mark.slow
def test_the_screening_estimate_agrees_with_the_monte_carlo_within_20_percent():
    particulars = load_particulars(ROOT / "config/particulars/dp_vessel.yaml")
    scenario = replace(load_scenario(ROOT / "config/scenarios/dp_station_keeping.yaml"),
                       particulars=particulars.vessel)
    setup = CaseSetup(scenario, WEATHER_CONDITIONS, {}, frozenset(), Criteria(50.0, 30.0, settle=60.0, duration=400.0),
                      particulars.hull, particulars.frame)
    finished = {}
    for heading in HEADINGS:
        for number in NUMBERS:
            for seed in range(SEEDS):
                result = run_case(Case(heading, number, INTACT, seed), setup)
                finished[result.case.key] = result
    title, columns, table = screening_table(setup, finished)
    assert title == SCREENING_TABLE
    rows = [dict(zip(columns, row, strict=True)) for row in table]
    assert [(r["heading_deg"], r["capability_number"], r["seeds"]) for r in rows] == [
        (h, n, SEEDS) for h in HEADINGS for n in NUMBERS]
    for row in rows:
        estimate = np.hypot(row["fd_north_std_m"], row["fd_east_std_m"])
        measured = np.hypot(row["td_north_std_m"], row["td_east_std_m"])
        assert estimate == pytest.approx(measured, rel=0.20), row
