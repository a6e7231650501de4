"""Repeatable means repeatable: every method that serves a shipped scenario's vehicle gives
the same metrics.json, bit for bit (all but the real-time factor, which is wall time, and the
consequence alarm times, which the node's analysis thread sets within an analysis period), on
two runs of the same short scenario with the same seed. A vessel scenario with a fault and its
clearing (services between steps, azimuths) and an ROV scenario with a battery ramp (the
voltage on its own topic every step, and the BlueROV2's tied optima under lp)."""


import pytest
from conftest import ALARM_METRICS, ALARM_TOLERANCE, ROOT

from allocator_pkg.cli.allocator_sim import run
from allocator_pkg.methods import METHODS
from allocator_pkg.simulation.run_report import read_report
from allocator_pkg.simulation.scenario import ScenarioError, load_scenario

pytestmark = pytest.mark.slow

SCENARIOS = {"dp_azimuth_failure": 0.05, "rov_battery_sag": 0.05}
"""One scenario per shipped vehicle, with the scale of its duration (15 s and 5 s)."""


def cases():
    for name, scale in SCENARIOS.items():
        scenario = load_scenario(ROOT / "config" / "scenarios" / f"{name}.yaml").scaled(scale)
        for method in METHODS:
            try:
                yield pytest.param(scenario.with_method(method), id=f"{name}-{method}")
            except ScenarioError:
                continue


def report(scenario, out):
    run(scenario, out, log=lambda _: None)
    data = read_report(out / "metrics.json")
    assert data["metrics"].pop("realtime_factor") > 0.0
    return data


def alarm_times(data) -> dict[str, float]:
    """The alarm times (ALARM_METRICS) of the run and each window, taken out of ``data``."""
    scopes = {"run": data["metrics"]} | {name: window["metrics"] for name, window in data["windows"].items()}
    return {f"{scope}.{key}": metrics.pop(key) for scope, metrics in scopes.items() for key in ALARM_METRICS}


@pytest.mark.parametrize("scenario", list(cases()))
def test_the_same_seed_gives_the_same_metrics_bit_for_bit(scenario, tmp_path):
    first, second = report(scenario, tmp_path / "first"), report(scenario, tmp_path / "second")
    times = alarm_times(first)
    assert alarm_times(second) == pytest.approx(times, rel=0.0, abs=ALARM_TOLERANCE)
    assert first == second
    assert len(first["metrics"]) == 11 and all(isinstance(v, (int, float)) for v in first["metrics"].values())
