"""A vessel's load coefficients over heading: interpolation by hand, refusals naming the key."""

import math

import pytest

from allocator_pkg.dp.inputs.coefficients import coefficient_table

SQUARE = {"heading_deg": [0, 90, 180, 270], "cx": [-1.0, 0.0, 1.0, 0.0], "cy": [0.0, 1.0, 0.0, -1.0],
          "cn": [0.0, 0.2, 0.0, -0.2]}


@pytest.mark.parametrize(("heading", "expected"), [
    (0.0, [-1.0, 0.0, 0.0]), (45.0, [-0.5, 0.5, 0.1]), (90.0, [0.0, 1.0, 0.2]), (315.0, [-0.5, -0.5, -0.1]),
    (360.0, [-1.0, 0.0, 0.0]), (-45.0, [-0.5, -0.5, -0.1]), (300.0, [-1 / 3, -2 / 3, -0.4 / 3]),
])
def test_coefficients_are_linear_between_rows_and_around_360(heading, expected):
    assert coefficient_table(SQUARE, "t").at(math.radians(heading)) == pytest.approx(expected, abs=1e-12)


def test_a_table_not_starting_at_zero_wraps_too():
    table = coefficient_table({**SQUARE, "heading_deg": [10, 100, 190, 280]}, "t")
    assert table.at(math.radians(5.0)) == pytest.approx([-1.0 + 5 / 90, -1.0 + 85 / 90, -0.2 + 0.2 * 85 / 90])


@pytest.mark.parametrize(("data", "message"), [
    ({**SQUARE, "cz": [0, 0, 0, 0]}, r"level2\.wind_coefficients: a mapping of heading_deg, cx, cy, cn"),
    ({**SQUARE, "cx": [0, 1]}, r"level2\.wind_coefficients: heading_deg, cx, cy, cn need one value per heading"),
    ({**SQUARE, "cy": [0, "a", 0, 0]}, r"level2\.wind_coefficients\.cy: a list of at least two finite numbers"),
    ({**SQUARE, "heading_deg": [0, 90, 90, 270]}, r"level2\.wind_coefficients\.heading_deg: strictly increasing"),
    ({**SQUARE, "heading_deg": [0, 90, 180, 360]}, r"level2\.wind_coefficients\.heading_deg: strictly increasing"),
])
def test_a_bad_table_is_refused_naming_the_key(data, message):
    with pytest.raises(ValueError, match=message):
        coefficient_table(data, "level2.wind_coefficients")
