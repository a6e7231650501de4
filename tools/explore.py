"""Fresh generated vehicles by the thousand, judged as test/allocation/test_generated.py judges them.

Every case of test_generated.CASES runs for each of its methods with hypothesis, not
derandomised, with --examples draws; the seed is printed so that a run can be repeated
(--seed); --minutes stops starting new cases. A counter-example (shrunk) is printed as a ROS 2
params file of the vehicle, with its faults, requests and the failed judgement as comments, to
keep in test/data/. Not part of CI: ``make explore``.
"""

from __future__ import annotations

import argparse
import random
import sys
import time
import traceback
from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

from allocator_pkg.configuration.params_file import params_text

ROOT = Path(__file__).resolve().parents[1]
GENERATED = ROOT / "test" / "allocation" / "test_generated.py"
"""The suite's module of generated cases; pytest collects it (the suite's own imports, its
conftest's environment), and the cases are taken from the module it imported."""


def explore(case, method: str, examples: int, run_seed: int) -> str | None:
    """The counter-example of one case and method as a params file with its faults and requests
    as comments, or None. Hypothesis replays the shrunk counter-example last, so the draws
    recorded last are its."""
    last: dict = {}

    @seed(run_seed)
    @settings(max_examples=examples, deadline=None, database=None, derandomize=False,
              suppress_health_check=list(HealthCheck), phases=[Phase.generate, Phase.shrink])
    @given(data=st.data())
    def check(data):
        draw = data.draw

        def recording(strategy, label=None):
            value = draw(strategy, label)
            if isinstance(value, tuple) and len(value) >= 2 and isinstance(value[1], dict):
                last.clear()
                last["parameters"] = value[1]
            elif isinstance(value, dict):
                last["faults"] = value
            elif isinstance(value, tuple) and len(value) == 2 and isinstance(value[0], str):
                last["requests"] = value
            return value

        data.draw = recording
        case(data, method)

    try:
        check()
    except Exception:               # a judge's assertion or an error, with the shrunk draws
        comments = [f"# {line}" for line in traceback.format_exc().splitlines()[-12:]]
        comments.append(f"# faults: {last.get('faults', {})}")
        kind, requests = last.get("requests", ("none", []))
        comments.append(f"# requests ({kind}): {[list(map(float, tau)) for tau in requests[:3]]}")
        return "\n".join(comments) + "\n" + params_text(last.get("parameters", {}))
    return None


class Cases:
    """A pytest plugin that keeps the collected module's ``CASES`` and runs no test."""

    def __init__(self) -> None:
        self.cases: dict = {}

    def pytest_collection_modifyitems(self, items: list, config) -> None:
        if items:
            self.cases = items[0].module.CASES
        items.clear()


def generated_cases() -> dict:
    """``CASES`` of the suite's generated-vehicle module, as pytest imports it."""
    plugin = Cases()
    pytest.main([str(GENERATED), "-q", "-p", "no:cacheprovider", "--collect-only"], plugins=[plugin])
    if not plugin.cases:
        raise RuntimeError(f"no cases collected from {GENERATED}")
    return plugin.cases


def main(argv: list[str] | None = None) -> int:
    cases = generated_cases()
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--examples", type=int, default=300, help="draws per case and method (default %(default)s)")
    parser.add_argument("--seed", type=int, default=None, help="default: a fresh one, printed")
    parser.add_argument("--minutes", type=float, default=None, help="stop starting new cases after this")
    parser.add_argument("--case", choices=list(cases), action="append", help="default: every case")
    arguments = parser.parse_args(argv)
    run_seed = arguments.seed if arguments.seed is not None else random.SystemRandom().randrange(2 ** 32)
    print(f"explore: seed {run_seed}, {arguments.examples} draws per case and method", flush=True)
    start = time.monotonic()
    found = 0
    for name in arguments.case or list(cases):
        case, methods = cases[name]
        for method in methods:
            if arguments.minutes is not None and time.monotonic() - start > 60.0 * arguments.minutes:
                print("explore: time is up", flush=True)
                return 1 if found else 0
            began = time.monotonic()
            failure = explore(case, method, arguments.examples, run_seed)
            print(f"{name} {method}: {'COUNTER-EXAMPLE' if failure else 'ok'} ({time.monotonic() - began:.0f} s)",
                  flush=True)
            if failure:
                found += 1
                print(failure)
    print(f"explore: {found} counter-examples (each printed above as a params file for test/data/)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
