"""The benchmark and soak scripts' own logic (their runs are benchmarks, not tests)."""

import json
import sys

from conftest import ROOT

sys.path.insert(0, str(ROOT / "bench"))

import report
import soak

from allocator_pkg import load_vehicle


def test_the_report_is_rebuilt_from_the_committed_results(tmp_path):
    out = tmp_path / "performance.md"
    report.write(json.loads((ROOT / "bench" / "results" / "latest.json").read_text()), out)
    text = out.read_text()
    assert text == (ROOT / "docs" / "performance.md").read_text()


def test_the_soak_judges_each_command_by_the_state_at_its_stamp():
    vehicle = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
    start = soak.State(vehicle, {})
    degraded = soak.State(vehicle, {"azimuth_port": 0.5})
    history = soak.History(start)
    change = soak.Change(sent=10.0, state=degraded)
    history.changes.append(change)
    period = 0.002
    assert history.at(9.0, period) == (start, start, False)
    assert history.at(10.5, period) == (start, degraded, True)          # asked, not answered yet
    change.answered = 10.01
    assert history.at(10.011, period) == (start, degraded, True)        # within a period of the answer
    assert history.at(10.1, period) == (degraded, degraded, False)
    low, high = degraded.limits(vehicle.actuators.index(vehicle.actuator("azimuth_port")))
    assert (low, high) == (0.0, 0.5 * vehicle.actuator("azimuth_port").thrust_max)
    history.forget(change)
    assert history.at(10.1, period) == (start, start, False) and len(history.changes) == 1


def test_the_report_gives_the_explicit_rows_and_its_regions_when_measured():
    result = json.loads((ROOT / "bench" / "results" / "latest.json").read_text())
    run = result["solver"]["vehicles"]["bluerov2_heavy"]["sequences"]["smooth"]
    run["methods"]["explicit"] = {**run["methods"]["qp"], "time_us": {"median": 9.0, "p90": 9.5, "p99": 31.0,
                                                                      "max": 60.0},
                                  "regions": {"regions": 1, "hit_rate": 0.999, "neighbour_rate": 0.0,
                                              "osqp_rate": 0.001, "inexact": 0}}
    lines = report._targets(result) + report._solver_tables(result)
    assert "| explicit median <= 10 us, bluerov2_heavy, smooth | 9.0 us | yes |" in lines
    assert "| explicit p99 <= 30 us, bluerov2_heavy, smooth | 31.0 us | no |" in lines
    assert ("explicit: 1 region cached; of its solves in the timed samples 99.9 % answered by the previous "
            "region, 0.0 % by a neighbouring one, 0.1 % after OSQP (0 left inexact).") in lines
    assert any(line.startswith("| explicit | 9.0 | 9.5 | 31.0 | 60.0 |") for line in lines)
