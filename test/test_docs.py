"""The documentation against the code. The Python examples run as written: each ```python block
of the pages below is executed statement by statement, in a folder of its own where ``config/``
is the repository's, and a statement whose comment starts with a Python literal (``# 'DP
capability-L1(10, 8, 8, 6)'``, ``# True: ...``) must give that value. The message and service
tables of docs/interface.md list the fields of each type under that type."""

import ast
import re

import pytest
from conftest import ROOT

PAGES = {"docs/dp_capability.md": 0, "README.md": 0}
"""Page and the index of its ```python block to run (README's first: the library example)."""
SLOW = {"docs/dp_capability.md"}
"""Pages whose example runs minutes: DNV Level 1 three times and Level 2 twice."""


def python_blocks(text: str) -> list[str]:
    return re.findall(r"```python\n(.*?)```", text, flags=re.DOTALL)


def stated(line: str):
    """The literal a line's comment starts with (up to a colon), or None when it starts with none."""
    comment = line.partition("#")[2].strip()
    head = comment.split(":")[0].strip() if not comment.startswith(("'", '"')) else comment
    try:
        return ast.literal_eval(head)
    except (ValueError, SyntaxError):
        return None


def run(source: str) -> list[tuple[str, object, object]]:
    """Execute ``source`` in the working folder; (statement, value, stated value) of each checked one."""
    lines = source.splitlines()
    namespace: dict = {}
    checked = []
    for statement in ast.parse(source).body:
        code = ast.get_source_segment(source, statement)
        if isinstance(statement, ast.Expr):
            value = eval(compile(ast.Expression(statement.value), "<doc>", "eval"), namespace)
            expected = stated(lines[statement.end_lineno - 1])
            if expected is not None:
                checked.append((code, value, expected))
        else:
            exec(compile(ast.Module([statement], []), "<doc>", "exec"), namespace)
    return checked


@pytest.mark.parametrize("page", [pytest.param(page, marks=[pytest.mark.slow] if page in SLOW else [])
                                  for page in PAGES])
def test_the_python_example_runs_and_gives_the_values_it_states(page, tmp_path, monkeypatch):
    block = python_blocks((ROOT / page).read_text())[PAGES[page]]
    (tmp_path / "config").symlink_to(ROOT / "config")
    monkeypatch.chdir(tmp_path)
    checked = run(block)
    assert checked, f"{page}: no statement states its value"
    for code, value, expected in checked:
        assert value == expected, f"{page}: {code} gives {value!r}, the page says {expected!r}"


def test_a_stated_value_is_read_from_the_comment_and_a_wrong_one_fails():
    assert stated("x.summary_line()   # 'DP capability-L1(10, 8, 8, 6)'") == "DP capability-L1(10, 8, 8, 6)"
    assert stated("result.saturated   # True: the thrusts start at zero") is True
    assert stated("alloc.allocate(w)   # [X, Y, Z, K, M, N]") is None
    assert stated("analysis.loads(c, d)  # wind, current, waves apart") is None
    assert run("1 + 1   # 3\n") == [("1 + 1", 2, 3)]


def documented_fields(text: str) -> dict[str, set[str]]:
    """Per ``msg X`` or ``srv X`` row of the interface tables, the field names (in backticks) of
    its rows up to the next type."""
    fields: dict[str, set[str]] = {}
    current = None
    for line in text.splitlines():
        cells = [cell.strip() for cell in line.split("|")[1:-1]]
        if len(cells) < 2:
            continue
        kind = re.fullmatch(r"(msg|srv) `(\w+)`", cells[0])
        if kind:
            current = kind.group(2)
        elif cells[0]:
            current = None
        if current is not None:
            fields.setdefault(current, set()).update(re.findall(r"`(\w+)`", cells[1]))
    return fields


def test_the_interface_tables_list_each_field_under_its_own_type():
    import allocator_msgs.msg as messages
    import allocator_msgs.srv as services

    documented = documented_fields((ROOT / "docs" / "interface.md").read_text())
    assert {"AllocationStatus", "SetGroupFault", "HoldActuator", "ConsequenceAnalysis"} <= set(documented)
    for name, listed in documented.items():
        kind = getattr(messages, name, None)
        if kind is not None:
            actual = set(kind.get_fields_and_field_types())
        else:
            service = getattr(services, name)
            actual = set(service.Request.get_fields_and_field_types()) | set(
                service.Response.get_fields_and_field_types())
        assert listed <= actual, f"docs/interface.md lists {sorted(listed - actual)} under {name}"
    assert "consequence_alarm" in documented["AllocationStatus"]
