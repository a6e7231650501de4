"""The suite itself: `make test` runs it on every core with pytest-xdist (pinned in the lock),
each test file on one worker; the slow marker (every test of 5 s or more carries it; `make test`
and CI run them all) is registered."""

import re

from conftest import ROOT


def test_the_slow_marker_is_registered(pytestconfig):
    markers = {line.split(":")[0]: line for line in pytestconfig.getini("markers")}
    assert markers["slow"] == "slow: takes 5 s or more (still run by make test and CI)"


def test_make_test_runs_the_suite_on_every_core_with_pytest_xdist():
    makefile = (ROOT / "Makefile").read_text()
    assert re.search(r"^TEST_WORKERS \?= auto$", makefile, re.M)
    assert re.search(r"^test: lint\n\t\$\(PY\) -m pytest -n \$\(TEST_WORKERS\) --dist loadfile \$\(PYTEST_ARGS\)$",
                     makefile, re.M)
    assert "pytest-xdist" in (ROOT / "requirements.in").read_text().split()
    pins = dict(line.split("==") for line in (ROOT / "requirements.lock").read_text().splitlines()
                if "==" in line)
    assert {"pytest-xdist", "execnet"} <= set(pins)
