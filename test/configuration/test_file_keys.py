"""The key tables of the input files: one checker, one docs table, the bounds of each key."""

import pytest

from allocator_pkg.configuration.file_keys import (
    EACH,
    MAPPING,
    NUMBER,
    TEXT,
    FileKey,
    check_keys,
    defaults,
    finite_number,
    markdown_table,
)

KEYS = (
    FileKey("b", NUMBER, "a length", required=True, unit="m", minimum=0.0, exclusive_minimum=True),
    FileKey("a", TEXT, "a name", default="x", choices=("x", "y")),
    FileKey("rows", MAPPING, "per row", keys=(FileKey("c", NUMBER, "c", default=1.0),), item="<row>"),
    FileKey("items", MAPPING, "a list", keys=(FileKey("d", NUMBER, "d", required=True),), item=EACH),
)


@pytest.mark.parametrize(("data", "where", "sort", "message"), [
    ({"b": 1, "z": 2, "e": 3}, "", False, "unknown key(s): e, z; known: b, a, rows, items"),
    ({"b": 1, "z": 2}, "", True, "unknown key(s): z; known: a, b, items, rows"),
    ({"b": 1, "z": 2}, "thrusters.t", False, "thrusters.t: unknown key(s) z; known: b, a, rows, items"),
    ({"a": "x"}, "", False, "missing key(s): b"),
    ({"a": "x"}, "rudders.r", False, "rudders.r: missing key(s) b"),
])
def test_unknown_and_missing_keys_are_refused_naming_where(data, where, sort, message):
    with pytest.raises(ValueError) as error:
        check_keys(data, KEYS, where, sort_known=sort)
    assert str(error.value) == message


def test_a_finite_number():
    assert finite_number(3, "x") == 3.0
    for bad in (True, "1", float("nan"), float("inf")):
        with pytest.raises(ValueError, match=r"^x: a finite number, not "):
            finite_number(bad, "x")


def test_bounds_and_their_interval():
    key = FileKey("wind", NUMBER, "", minimum=0.0, maximum=70.0, exclusive_minimum=True)
    assert not key.holds(0.0) and key.holds(70.0) and not key.holds(70.1) and key.interval() == "(0, 70]"
    assert FileKey("hs", NUMBER, "", minimum=0.0, maximum=25.0).interval() == "[0, 25]"
    assert FileKey("f", NUMBER, "", minimum=0.0, maximum=90.0, exclusive_minimum=True,
                   exclusive_maximum=True).documented_range() == "(0, 90)"


def test_the_docs_table_has_a_row_per_key_at_any_depth():
    rows = markdown_table(KEYS).splitlines()
    assert rows[0] == "| key | unit | default | range | meaning |"
    assert [row.split(" | ")[0] for row in rows[2:]] == [
        "| `b`", "| `a`", "| `rows`", "| `rows.<row>.c`", "| `items`", "| `items[].d`"]
    assert rows[2] == "| `b` | m | required | > 0 | a length |"
    assert defaults(KEYS) == {"a": "x"}
