"""The benchmark and soak scripts' own logic (their runs are benchmarks, not tests)."""

import itertools
import json
from types import SimpleNamespace

import numpy as np
import pytest
from conftest import ROOT, bench_module

from allocator_pkg import load_vehicle
from allocator_pkg.solvers import BACKENDS

dp_capability = bench_module("dp_capability")
idle_core = bench_module("idle_core")
overhead = bench_module("overhead")
power_cost = bench_module("power_cost")
report = bench_module("report")
soak = bench_module("soak")
solver = bench_module("solver")
ticker = bench_module("ticker")


def test_the_report_is_rebuilt_from_the_committed_results(tmp_path):
    out = tmp_path / "performance.md"
    report.write(json.loads((ROOT / "bench" / "results" / "latest.json").read_text()), out)
    text = out.read_text()
    assert text == (ROOT / "docs" / "performance.md").read_text()


def test_only_re_measures_the_named_sections_and_keeps_the_others(tmp_path, monkeypatch):
    run = bench_module("run")
    results, kept = tmp_path / "results", json.loads((ROOT / "bench" / "results" / "latest.json").read_text())
    results.mkdir()
    (tmp_path / "docs").mkdir()
    (results / "latest.json").write_text(json.dumps(kept))
    fresh = {**kept["dp_step_costs"], "allocate_us": 1.0}
    measured = []
    monkeypatch.setattr(run, "RESULTS", results)
    monkeypatch.setattr(run, "ROOT", tmp_path)
    monkeypatch.setattr(run, "measure", lambda name, quick: measured.append(name) or fresh)
    assert run.main(["--only", "dp_step_costs"]) == 0
    result = json.loads((results / "latest.json").read_text())
    assert measured == ["dp_step_costs"] and result["dp_step_costs"] == fresh and result["solver"] == kept["solver"]
    assert result["remeasured"]["sections"] == ["dp_step_costs"]
    text = (tmp_path / "docs" / "performance.md").read_text()
    assert (f"Re-measured alone on {result['remeasured']['date']}: dp_step_costs; the other "
            f"sections are from the run of {kept['machine']['date']}.") in text
    with pytest.raises(SystemExit):
        run.main(["--only", "dp_step_cost"])
    assert measured == ["dp_step_costs"]


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


def test_the_soak_puts_each_late_tick_down_to_what_came_right_before_it():
    period = 1.0 / soak.RATE_HZ
    # ticks every period from t = 100 s, with three late ones: 3, 2 and 4 periods after the
    # tick before (2, 1 and 3 missed periods)
    offsets = [*range(10), 12, *range(13, 30), 31, *range(32, 50), 53, 54]
    stamps = [100.0 + k * period for k in offsets]
    late_after = [100.0 + 12 * period, 100.0 + 31 * period, 100.0 + 53 * period]
    disturbances = [late_after[0] - 0.03, late_after[2] - 0.2]         # within 50 ms of the first only
    solve_at = dict.fromkeys(stamps, 2e-4)
    solve_at[100.0 + 29 * period] = 1.5e-3                              # the sample before the second
    assert soak.late_ticks(stamps, solve_at, disturbances) == {
        "after a disturbance": 2, "next to a slow sample": 1, "elsewhere": 3}


def test_the_bare_ticker_counts_missed_periods_as_the_node_benchmark_does():
    period = 1.0 / 500.0
    woke = [k * period for k in (0, 1, 2, 4, 5, 9, 10)]    # 2 then 4 periods apart: 1 + 3 missed
    result = ticker.missed(woke, 500.0)
    assert (result["missed"], result["missed_percent"], result["longest_interval_ms"]) == (4, 40.0, 8.0)
    woke = ticker.tick(0.02, 500.0)            # ten deadlines: at most ten wake-ups, in order
    assert 1 <= len(woke) <= 10 and all(b > a for a, b in itertools.pairwise(woke))


def test_every_solver_pattern_of_the_bench_allocates_and_records_its_solver_calls():
    """The bench's plumbing on a few samples: every method and backend pattern answers, and
    each QP pattern's solver calls are recorded through the backend seam."""
    for config in ("bluerov2_heavy", "dp_vessel"):
        vehicle = load_vehicle(ROOT / "config" / f"{config}.yaml")
        methods = solver.allocators(vehicle)
        assert {name for name, backend in solver.PATTERNS.items() if backend in BACKENDS} <= set(methods)
        tau = solver.sequences(vehicle, 5)["smooth"][2]
        for name, (allocator, timed) in methods.items():
            result = allocator.allocate(tau)
            assert np.isfinite(result.thrust).all(), (config, name)
            if name.startswith("qp"):
                assert timed.times, (config, name)


def test_the_report_renders_the_convergence_rows_when_a_run_has_them(tmp_path):
    result = json.loads((ROOT / "bench" / "results" / "latest.json").read_text())
    vehicle = next(iter(result["solver"]["vehicles"].values()))
    smooth = vehicle["sequences"]["smooth"]["methods"]
    smooth["qp"]["distance_to_qp"] = {"median": 0.0, "p90": 0.0, "p99": 0.0, "max": 0.0}
    smooth["lp"].pop("distance_to_qp", None)                        # a method the run did not compare
    vehicle["convergence"] = {"qp": {"samples": [3, 9], "never": 0, "median": 6.0, "max": 9},
                              "lp": {"samples": [None, None], "never": 2, "median": None, "max": None}}
    out = tmp_path / "performance.md"
    report.write(result, out)
    text = out.read_text()
    assert "| qp | 6 | 9 | 0 | 0.00 | 0.00 |" in text
    assert "| lp | - | - | 2 | - | - |" in text


def test_the_report_gives_the_explicit_rows_and_its_regions_when_measured():
    result = json.loads((ROOT / "bench" / "results" / "latest.json").read_text())
    run = result["solver"]["vehicles"]["bluerov2_heavy"]["sequences"]["smooth"]
    run["methods"]["explicit"] = {**run["methods"]["qp"], "time_us": {"median": 9.0, "p90": 9.5, "p99": 31.0,
                                                                      "max": 60.0},
                                  "regions": {"regions": 1, "hit_rate": 0.999, "neighbour_rate": 0.0,
                                              "osqp_rate": 0.001, "inexact": 0}}
    lines = report._targets(result) + report._solver_tables(result)
    assert "| explicit median <= 10 us, bluerov2_heavy, smooth, Python included | 9.0 us | yes |" in lines
    assert "| explicit p99 <= 30 us, bluerov2_heavy, smooth, Python included | 31.0 us | no |" in lines
    assert ("explicit: 1 region cached; of its solves in the timed samples 99.9 % answered by the previous "
            "region, 0.0 % by a neighbouring one, 0.1 % after OSQP (0 left inexact).") in lines
    assert any(line.startswith("| explicit | 9.0 | 9.5 | 31.0 | 60.0 |") for line in lines)


def test_the_overhead_bench_takes_medians_over_rounds_and_ratios_to_the_bare_node_of_the_same_rate():
    def case(cpu, p50, allocate=None):
        return {"cpu_ms_per_sample": cpu, "cpu_percent": 10.0 * cpu, "latency_ms_p50": p50, "latency_ms_p99": 2 * p50,
                "allocate_ms_p50": allocate, "beyond_allocate_ms": None if allocate is None else cpu - 1.5 * allocate}

    rounds = [{"input|bare echo|100.0": case(0.5, 1.0), "input|dp_vessel|100.0": case(0.6, 1.5, 0.1),
               "input|bare echo|500.0": case(0.2, 0.5), "input|dp_vessel|500.0": case(0.3, 0.5, 0.1)},
              {"input|bare echo|100.0": case(0.7, 1.0), "input|dp_vessel|100.0": case(0.8, 1.1, 0.3),
               "input|bare echo|500.0": case(0.4, 0.5), "input|dp_vessel|500.0": case(0.5, 0.6, 0.2)}]
    rows = {(row["node"], row["rate_hz"]): row for row in overhead.summarise(rounds)}
    assert rows[("dp_vessel", 100.0)]["cpu_ms_per_sample"] == 0.7 and rows[("bare echo", 100.0)]["cpu_ratio"] == 1.0
    assert rows[("dp_vessel", 100.0)]["cpu_ratio"] == pytest.approx(0.7 / 0.6)
    assert rows[("dp_vessel", 500.0)]["cpu_ratio"] == pytest.approx(0.4 / 0.3)
    assert rows[("dp_vessel", 500.0)]["latency_ratio"] == pytest.approx(1.1)
    assert rows[("dp_vessel", 100.0)]["latency_ratio"] == pytest.approx(1.3)
    assert rows[("dp_vessel", 100.0)]["allocate_share"] == pytest.approx(0.2 / 0.7)
    assert rows[("dp_vessel", 500.0)]["allocate_share"] == pytest.approx(0.15 / 0.4)
    assert "allocate_share" not in rows[("bare echo", 500.0)]
    assert rows[("dp_vessel", 100.0)]["beyond_allocate_ratio"] == pytest.approx(((0.6 - 0.15) + (0.8 - 0.45)) / 2 / 0.6)
    assert rows[("dp_vessel", 500.0)]["beyond_allocate_ratio"] == pytest.approx(((0.3 - 0.15) + (0.5 - 0.3)) / 2 / 0.3)
    assert "beyond_allocate_ratio" not in rows[("bare echo", 100.0)]


def test_a_window_of_the_overhead_bench_gives_cpu_per_sample_and_what_is_spent_beyond_allocate():
    # 0.5 s of CPU over 10 s of wall time and 1000 samples; allocate took 0.1 ms in 3 samples of 4 and 0.5 ms in 1.
    figures = overhead.window_figures(0.5, 10.0, 1000, 1000, [1e-3, 2e-3, 3e-3], [1e-4, 1e-4, 1e-4, 5e-4])
    assert figures["cpu_ms_per_sample"] == pytest.approx(0.5) and figures["cpu_percent"] == pytest.approx(5.0)
    assert figures["allocate_ms_p50"] == pytest.approx(0.1)
    assert figures["beyond_allocate_ms"] == pytest.approx(0.5 - 0.2)
    assert figures["latency_ms_p50"] == pytest.approx(2.0)
    bare = overhead.window_figures(0.5, 10.0, 1000, 1000, [1e-3], [])
    assert bare["allocate_ms_p50"] is None and bare["beyond_allocate_ms"] is None


def test_the_idle_core_bench_asks_the_node_cost_probes_request_and_times_every_sample():
    turn = idle_core.requests(overhead.AMPLITUDE["dp_vessel"], round(idle_core.RATE_HZ * overhead.PERIOD) + 1)
    assert np.allclose(turn[0], [2.0e5, 0, 0, 0, 0, 0]) and np.allclose(turn[-1], [2.0e5, 0, 0, 0, 0, 0], atol=1e-6)
    quarter = turn[round(idle_core.RATE_HZ * overhead.PERIOD / 4)]
    assert np.allclose(quarter, [0, 2.0e5, 0, 0, 0, 0], atol=1e-6)
    result = idle_core.measure(rounds=1, samples=3)
    for rows in result["vehicles"].values():
        assert [row["gap_ms"] for row in rows] == list(idle_core.GAPS_MS)
        assert rows[0]["p50_multiple"] == rows[0]["mean_multiple"] == 1.0
        assert all(row["cpu_us_p50"] > 0.0 and np.isfinite(row["mean_multiple"]) for row in rows)


def test_the_report_gives_allocates_cpu_after_each_idle_gap():
    idle = {"rounds": 3, "samples": 400, "rate_hz": 100.0, "vehicles": {"dp_vessel": [
        {"gap_ms": 0.0, "cpu_us_p50": 110.0, "cpu_us_mean": 120.0, "p50_multiple": 1.0, "mean_multiple": 1.0},
        {"gap_ms": 10.0, "cpu_us_p50": 330.0, "cpu_us_mean": 300.0, "p50_multiple": 3.0, "mean_multiple": 2.5}]}}
    lines = report._idle_core_section(idle)
    assert "| dp_vessel | 0 | 110.0 | 120.0 | 1.00 | 1.00 |" in lines
    assert "| dp_vessel | 10 | 330.0 | 300.0 | 3.00 | 2.50 |" in lines


def test_the_dp_capability_bench_times_every_run_and_counts_its_balances():
    result = dp_capability.measure(repeats=2, step_deg=90.0)
    assert (result["headings"], result["cases"], result["repeats"]) == (4, 3, 2) and len(result["wall_s"]) == 2
    assert result["wall_s_median"] == pytest.approx(sum(result["wall_s"]) / 2)
    assert result["user_cpu_s_median"] > 0.0 and result["ms_per_balance"] == pytest.approx(
        1e3 * result["wall_s_median"] / result["balances"])
    assert result["summary"].startswith("DP capability-L1(")
    # every heading and case balances its number's conditions and then halves 14 times at least
    assert result["balances"] >= 4 * 3 * 14


def test_the_power_cost_bench_gives_the_ratios_of_one_run_and_the_report_says_them():
    """The cases fed in turn, each sample timed: the ratios are those of the means; the limited
    cases solve with the rows (one set-up more than without sources, none after), the one at
    capacity never power-limited."""
    run = power_cost.run(40)
    mean = run["mean_ms"]
    assert run["limited_over_unlimited"] == pytest.approx(0.5 * (mean["limited"] + mean["limited_split"])
                                                          / mean["at_capacity"])
    assert run["rows_over_without"] == pytest.approx(mean["at_capacity"] / mean["without"])
    assert run["setups"]["limited"] == run["setups"]["at_capacity"] == run["setups"]["without"] + 1
    assert run["power_limited_share"]["without"] == run["power_limited_share"]["at_capacity"] == 0.0
    lines = power_cost.section(run)
    assert lines[0] == "## Power rows" and f"{run['limited_over_unlimited']:.2f}x one at capacity" in lines[-1]


def test_the_report_gives_the_dp_capability_run_against_its_target():
    run = {"vessel": "dp_vessel", "heading_step_deg": 10.0, "headings": 36, "cases": 3, "repeats": 3,
           "wall_s": [4.0, 5.5, 4.5], "wall_s_median": 4.5, "user_cpu_s_median": 4.25, "balances": 2500,
           "summary": "DP capability-L1(10, 8, 8, 6)", "target_s": 5.0}
    lines = report._dp_capability_section(run)
    assert lines[0] == "## DP capability Level 1"
    assert "| dp_vessel | DP capability-L1(10, 8, 8, 6) | 2500 | 4.50 | 4.25 | 1.80 | < 5 | yes |" in lines
    assert report._dp_capability_section({**run, "wall_s_median": 12.0})[-1].endswith("| no |")


def test_the_report_gives_the_in_process_factors_and_the_ratio_to_the_node():
    run = {"scenario": "dp_station_keeping", "duration_s": 300.0, "method": "qp", "repeats": 5,
           "in_process": {"loop": 400.0, "run": 350.0, "run_cpu": 360.0}, "target": 300.0, "meets_target": True,
           "node": {"loop": 50.0, "run": 35.0, "run_cpu": 36.0}, "ratio": {"loop": 8.0, "run": 10.0, "run_cpu": 10.0}}
    lines = report._inprocess_section(run)
    assert "| in process | 400x | 350x | 360x |" in lines and "| ratio | 8.0 | 10.0 | 10.0 |" in lines
    assert lines[-1].endswith(": met.")
    assert report._inprocess_section({**run, "meets_target": False})[-1].endswith("not met.")


def test_the_report_gives_the_level3_case_cost_and_speed_up():
    run = {"vessel": "dp_vessel", "cases": 16, "simulated_s_per_case": 660.0,
           "in_process": {"wall_s_per_case": 1.8, "cases_per_minute": 60.0 / 1.8, "realtime_factor_wall": 660.0 / 1.8,
                          "realtime_factor_cpu": 400.0},
           "pool_1_worker": {"wall_s": 30.0}, "pool_2_workers": {"wall_s": 15.0}, "speedup_2_over_1": 2.0,
           "target_speedup": 1.8, "identical": True}
    assert report._level3_section(run)[-1] == "| 1.80 | 33.3 | 367x / 400x | 30.0 | 15.0 | 2.00 | >= 1.8 | yes |"
    study = {"runs": 64, "seeds": 2, "simulated_s_per_run": 150.0,
             "pool_1_worker": {"wall_s": 67.2, "load_average": 1.65},
             "pool_2_workers": {"wall_s": 33.6, "load_average": 1.22}, "speedup_2_over_1": 2.0,
             "target_speedup": 1.8, "identical_journals": True}
    assert report._level3_section(run, study)[-1] == "| 64 | 67.2 (1.6) | 33.6 (1.2) | 2.00 | >= 1.8 | yes |"


def test_a_sequence_of_the_solver_bench_runs_every_method_through_the_allocator():
    """The bench's per-sequence loop on a few samples (it reads the method in use from the
    allocator, which no other test exercises)."""
    vehicle = load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml")
    requests = np.tile([10.0, 5.0, -3.0, 0.0, 0.0, 1.0], (solver.WARM_UP + 3, 1))
    results = solver.run_sequence(vehicle, requests)
    assert set(results["methods"]) == set(solver.allocators(vehicle))
    assert results["samples"] == 3 and all(method["saturated_flags"] == 0 and method["fallbacks"] == 0
                                            for method in results["methods"].values())


def test_the_node_probe_counts_missed_and_lost_periods_from_the_stamps():
    """Stamps 10 ms apart with one interval of 2 periods and one of 3: 1 + 2 missed periods, and
    3 periods of the span without a message."""
    probe = bench_module("probe")
    stamps = [0.01 * k for k in (0, 1, 2, 3, 5, 6, 7, 8, 9, 12)]
    recorded = SimpleNamespace(commands=[(stamp + 0.001, stamp) for stamp in stamps], latencies=[], solves=[],
                               published=[])
    figures = probe.summarise(recorded, 100.0, (0.0, 0.2), 12.0)
    assert (figures["missed"], figures["lost"], figures["missed_percent"]) == (3, 3, 25.0)
    assert figures["achieved_hz"] == 50.0 and figures["tick_to_receipt_ms"]["p50"] == pytest.approx(1.0)
    assert figures["publish_to_commands_ms"] == {"p50": None, "p99": None, "matched": 0, "published": 0}
