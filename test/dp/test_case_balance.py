"""The kept programmes of a Level 1 case: each balance answers as an independent solver of the
same programme (scipy's interior point method, from nothing), through every case, heading and
condition of dp_vessel and otter_usv in any order; a full heading search gives the numbers and
limiting wind speeds of the same search on that solver; the programmes are set up once per shape;
the tables' forces are those of every combination solved afresh; the search's balances."""

import itertools
import math
from collections import Counter

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog

from allocator_pkg import load_vehicle
from allocator_pkg.dp.case_balance import MARGIN
from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.standard.power_balance import power_rows
from allocator_pkg.dp.standard.weather import BISECTION_STEPS, TOP, condition_at

VESSELS = ("dp_vessel", "otter_usv")
AMBIGUOUS = 1e-7
"""A largest multiple this close (relative) to the one asked decides nothing between two solvers."""


def level1(vessel: str, kind: type[Level1] = Level1) -> Level1:
    return kind(load_vehicle(ROOT / "config" / f"{vessel}.yaml"),
                  load_particulars(ROOT / "config" / "particulars" / f"{vessel}.yaml"))


ANALYSES = {vessel: level1(vessel) for vessel in VESSELS}
"""One analysis per vessel for every example: its programmes start from whatever basis came last."""


class IndependentLevel1(Level1):
    """Level 1 whose balance is scipy's interior point solution of every combination's programme
    (:func:`largest_multiple`), nothing kept."""

    def balanced(self, level: float, direction: float, failed: tuple[str, ...] = ()) -> bool:
        multiple, asked = largest_multiple(self, level, direction, failed)
        return multiple >= asked


def largest_multiple(analysis: Level1, level: float, direction: float, failed: tuple[str, ...]) -> tuple[float, float]:
    """(the largest multiple of the balance's request over every combination of pieces by
    scipy's interior point method, the multiple the balance asks: 1 - MARGIN in the variant's
    authority) (:func:`combination_multiples`)."""
    multiples, asked = combination_multiples(analysis, level, direction, failed)
    return max(multiples), asked


def combination_multiples(analysis: Level1, level: float, direction: float,
                          failed: tuple[str, ...]) -> tuple[list[float], float]:
    """(per combination of pieces, the largest multiple of the balance's request by scipy's
    interior point method, the multiple the balance asks); ([inf], 0) for a calm condition,
    ([0], 1) for a case with no thruster working or a load in a DOF no actuator is asked to push."""
    condition = condition_at(level, analysis.conditions)
    tau = analysis.required(condition, direction)
    if not np.any(tau):
        return [math.inf], 0.0
    variant = analysis.variant(condition, direction, failed)
    if not variant.actuators or np.any(np.abs(tau[analysis.uncontrolled]) > 1e-9 * np.max(np.abs(tau))):
        return [0.0], 1.0
    capability = analysis.capability(variant, failed)
    model, limits = capability.model, analysis.power_limits(failed)
    scale = float(np.max(np.abs(tau[model.dof_index]) / np.maximum(model.authority, 1e-12)))
    request = (tau / scale)[model.dof_index]
    conditions = capability.in_force()
    low, high = conditions.low, conditions.high
    multiples = []
    for pieces in itertools.product(*(capability._pieces(i, conditions, low[i], high[i]) for i in model.rot)):
        cost, a_ub, b_ub, a_eq, bounds = capability._constraints(request, low, high, pieces, capability.sides)
        base = len(cost)
        rows = np.array(a_ub).reshape(-1, base)
        if limits is not None:
            power, right = power_rows(limits, model, variant.actuators, base, pieces)
            extra = power.shape[1] - base
            rows = np.vstack([np.hstack([rows, np.zeros((len(rows), extra))]), power])
            b_ub, cost = [*b_ub, *right], np.concatenate([cost, np.zeros(extra)])
            a_eq, bounds = np.hstack([a_eq, np.zeros((len(a_eq), extra))]), [*bounds, *[(0.0, None)] * extra]
        answer = linprog(cost, A_ub=rows if len(rows) else None, b_ub=b_ub if len(rows) else None, A_eq=a_eq,
                         b_eq=np.zeros(len(a_eq)), bounds=bounds, method="highs-ipm")
        multiples.append(float(answer.x[model.m]) if answer.status == 0 else 0.0)
    return multiples, scale * (1.0 - MARGIN)


@settings(max_examples=80, deadline=None)
@given(st.sampled_from(VESSELS), st.integers(0, 2), st.floats(0.0, 359.0), st.floats(0.05, 11.0))
@example("dp_vessel", 0, 340.0, 10.556640625)       # a fresh programme with presolve answered 0.99995 here
def test_a_balance_answers_as_an_independent_solver(vessel, case, heading, level):
    analysis = ANALYSES[vessel]
    failed = list(analysis.cases().values())[case % len(analysis.cases())]
    direction = math.radians(heading)
    multiple, asked = largest_multiple(analysis, level, direction, failed)
    if abs(multiple - asked) <= AMBIGUOUS * asked:
        return
    assert analysis.balanced(level, direction, failed) == (multiple >= asked), (multiple / asked, failed)


@pytest.mark.slow
@pytest.mark.parametrize(("vessel", "case", "headings"), [
    ("dp_vessel", "intact", (30.0, 340.0)),
    ("dp_vessel", "switchboard_a", (90.0, 250.0)),
    ("dp_vessel", "switchboard_b", (0.0, 120.0)),
    ("otter_usv", "intact", (60.0, 180.0)),
])
def test_a_heading_search_gives_the_independent_solvers_number_and_wind_speed(vessel, case, headings):
    analysis, independent = ANALYSES[vessel], level1(vessel, IndependentLevel1)
    failed = analysis.cases()[case]
    for heading in headings:
        number, wind = analysis.heading(math.radians(heading), failed)
        assert (number, wind) == independent.heading(math.radians(heading), failed), (case, heading)


def test_the_programmes_are_set_up_once_per_shape_of_a_combination():
    """Every balance of a case runs on the case's kept programmes: at most one without and one
    with the power rows per combination of pieces (their shapes do not change with the
    condition or heading here), however many balances."""
    analysis = level1("dp_vessel")
    for heading in range(0, 360, 30):
        for failed in analysis.cases().values():
            analysis.heading(math.radians(heading), failed)
    assert len(analysis._balances) == len(analysis.cases())
    for (failed, _), balance in analysis._balances.items():
        variant = analysis.variant(condition_at(5.0), 0.0, failed)
        capability = analysis.capability(variant, failed)
        conditions = capability.in_force()
        combinations = math.prod(len(capability._pieces(i, conditions, conditions.low[i], conditions.high[i]))
                                 for i in capability.model.rot)
        assert 1 <= len(balance._programmes) <= 2 * combinations


class UnkeptLevel1(Level1):
    """Level 1 without kept programmes: every balance and allocation on fresh ones."""

    def case_balance(self, variant, failed):
        return None


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2), st.integers(0, 35), st.integers(1, 10))
def test_the_allocation_of_the_tables_is_that_of_every_combination_solved(case, heading, number):
    """Tables A-8 to A-10: the forces of the combination the kept programmes find furthest,
    solved alone, are those of every combination solved afresh (the first that reaches furthest)."""
    analysis, unkept = ANALYSES["dp_vessel"], UNKEPT
    failed = list(analysis.cases().values())[case]
    direction = math.radians(10.0 * heading)
    assert analysis.thruster_use(number, direction, failed) == unkept.thruster_use(number, direction, failed)


def test_the_furthest_combination_is_the_independent_solvers():
    analysis = ANALYSES["dp_vessel"]
    for failed in analysis.cases().values():
        for heading, level in ((20.0, 9.0), (150.0, 6.0), (270.0, 8.0)):
            condition, direction = condition_at(level), math.radians(heading)
            variant, tau = analysis.variant(condition, direction, failed), analysis.required(condition, direction)
            best = analysis.case_balance(variant, failed).largest(variant, analysis.variant_profiles(variant), tau)
            multiples, _ = combination_multiples(analysis, level, direction, failed)
            assert best is not None and multiples[best] == max(multiples), (failed, heading)
            assert sorted(multiples)[-2] < (1.0 - 1e-6) * multiples[best]


UNKEPT = level1("dp_vessel", UnkeptLevel1)


class CountingLevel1(Level1):
    """Level 1 that counts its balances per heading and case."""

    def __init__(self, *args):
        self.counts: Counter = Counter()
        super().__init__(*args)

    def balanced(self, level: float, direction: float, failed: tuple[str, ...] = ()) -> bool:
        self.counts[(direction, failed)] += 1
        return super().balanced(level, direction, failed)


def test_a_heading_costs_the_rising_search_and_its_halvings():
    """The search stays exact ([2.2.2]: every lower number held; the balance need not be monotone
    in the number): per heading and case the numbers 1 ... n + 1 (11 at most), then
    BISECTION_STEPS halvings unless n is 11."""
    analysis = level1("dp_vessel", CountingLevel1)
    for failed in analysis.cases().values():
        for heading in (0.0, 90.0, 200.0, 330.0):
            direction = math.radians(heading)
            number, _ = analysis.heading(direction, failed)
            expected = min(number + 1, TOP) + (BISECTION_STEPS if number < TOP else 0)
            assert analysis.counts[(direction, failed)] == expected, (failed, heading, number)
