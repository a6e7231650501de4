"""allocator_pkg.simulation.verdict: bounds over the run and over windows, what breaks one,
and the table."""

import math

from allocator_pkg.simulation.verdict import RUN, Check, broken, checks, verdict_lines


def test_each_bound_is_checked_over_its_scope():
    found = checks({"position_error_max": 2.0, "energy": 10.0}, {"position_error_max": 3.0},
                   {"settled": {"position_error_max": 1.5, "energy": 4.0}},
                   {"settled": {"position_error_max": 1.0, "energy": 4.0}})
    assert found == [Check(RUN, "position_error_max", 2.0, 3.0), Check("settled", "position_error_max", 1.5, 1.0),
                     Check("settled", "energy", 4.0, 4.0)]
    assert [c.passed for c in found] == [True, False, True]                 # a value at its bound holds it
    assert broken(found) == [found[1]]


def test_a_metric_that_is_not_a_number_breaks_its_bound():
    assert not Check(RUN, "position_error_max", math.nan, 3.0).passed
    assert not Check(RUN, "position_error_max", math.inf, 3.0).passed


def test_the_table_names_units_and_ends_with_the_verdict():
    lines = verdict_lines([Check(RUN, "heading_error_max", 2.5, 3.0), Check("fault", "position_error_max", 4.2, 4.0)])
    assert lines[1].startswith("PASS") and "heading_error_max [deg]" in lines[1]
    assert lines[2].startswith("FAIL") and "fault" in lines[2] and "position_error_max [m]" in lines[2]
    assert lines[-1] == "verdict: FAIL, 1 of 2 bounds broken"
    assert verdict_lines([Check(RUN, "energy", 1.0, 2.0)])[-1] == "verdict: PASS, 1 bound held"
    assert verdict_lines([])[-1] == "verdict: PASS, no bounds"
