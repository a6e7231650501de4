"""allocator-sim's command line with the allocator in process: the help names both forms, and
the verdict tells a method that broke a bound (exit status 1) from a run that failed (3) and
from a scenario refused before anything ran (2); a method held to bounds of its own;
metrics.json is strict JSON."""

import json
import math

import pytest
from conftest import ROOT

from allocator_pkg.cli.allocator_sim import EXIT_BROKEN, EXIT_FAILED, EXIT_HELD, EXIT_REFUSED, main
from allocator_pkg.simulation.run_report import read_report


def station_keeping(tmp_path, bound: float, more: str = "", event: str = "") -> str:
    """dp_station_keeping with its position bound set to ``bound``, ``more`` appended and ``event``
    its only event."""
    text = (ROOT / "config" / "scenarios" / "dp_station_keeping.yaml").read_text().replace("../", f"{ROOT}/config/")
    text = text.replace("bounds: {position_error_max: 3.0", f"bounds: {{position_error_max: {bound}")
    path = tmp_path / f"keeping_{bound:g}_{len(more)}_{len(event)}.yaml"
    path.write_text(text + more + (f"events:\n  - {event}\n" if event else ""))
    return str(path)


def test_the_help_shows_compare_and_the_exit_statuses(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["--help"])
    assert exit_.value.code == 0
    text = capsys.readouterr().out
    assert "allocator-sim compare SCENARIO --methods" in text and "compare --help" in text
    assert "1 a method broke a bound" in text and "3 a run failed" in text


def test_a_broken_bound_and_a_failed_run_are_told_apart(tmp_path, capsys):
    """lp does not implement thrust bias: the node (here the library) refuses the parameter
    mid-run, and lp's run fails; qp runs and breaks its bound."""
    path = station_keeping(tmp_path, 1e-4, event="{time: 100.0, parameter: {name: bias.enabled, value: true}}")
    arguments = ["compare", path, "--methods", "qp", "lp", "--out", str(tmp_path / "cmp"), "--duration-scale", "0.02",
                 "--no-baseline", "--in-process"]
    assert main(arguments) == EXIT_FAILED
    text = capsys.readouterr().out
    assert "sim: qp: FAIL, broke run position_error_max" in text
    assert "sim: lp: RUN FAILED, SimulationError: parameter bias.enabled refused" in text
    assert "FAIL: 0 method(s) held every bound; bounds broken by qp; run failed (crashed, no verdict): lp" in text
    assert (tmp_path / "cmp" / "compare.md").exists()                  # the runs that ran are compared
    single = [path, "--out", str(tmp_path / "one"), "--duration-scale", "0.02", "--in-process", "--method", "lp"]
    assert main(single) == EXIT_FAILED
    assert "RUN FAILED" in capsys.readouterr().err
    assert main([*single[:-2], "--method", "qp"]) == EXIT_BROKEN


def test_a_refused_scenario_is_neither(tmp_path, capsys):
    path = station_keeping(tmp_path, 1e-4, event="{time: 400.0, clear_faults: true}")
    assert main(["compare", path, "--methods", "qp", "--out", str(tmp_path / "cmp"), "--in-process"]) == EXIT_REFUSED
    assert "events[0].time: 400 s is not within the run" in capsys.readouterr().err
    assert main([path, "--out", str(tmp_path / "one"), "--in-process"]) == EXIT_REFUSED


def test_a_method_is_held_to_the_bounds_the_scenario_gives_it(tmp_path, capsys):
    more = "methods:\n  lp:\n    bounds: {position_error_max: 3.0}\n    note: lp is judged on its own\n"
    path = station_keeping(tmp_path, 1e-4, more)
    arguments = ["compare", path, "--methods", "qp", "lp", "--out", str(tmp_path / "cmp"), "--duration-scale", "0.02",
                 "--no-baseline", "--in-process"]
    assert main(arguments) == EXIT_BROKEN
    text = capsys.readouterr().out
    assert "sim: qp: FAIL, broke run position_error_max" in text
    assert "sim: lp: PASS, 2 bounds held (its own bounds: position_error_max 3; lp is judged on its own)" in text
    assert "FAIL: 1 method(s) held every bound; bounds broken by qp" in text
    held = station_keeping(tmp_path, 3.0, more)
    assert main([arguments[0], held, *arguments[2:]]) == EXIT_HELD
    assert "PASS: 2 method(s) held every bound" in capsys.readouterr().out


def refuse(constant: str):
    raise ValueError(f"{constant} is not JSON")


def test_metrics_json_is_strict_json_and_reads_back(tmp_path):
    """No alarm and no loss of position: the alarm times are infinite, written as strings that
    JSON.parse takes, and read back as numbers."""
    out = tmp_path / "run"
    assert main([station_keeping(tmp_path, 3.0), "--out", str(out), "--duration-scale", "0.02", "--in-process"]) == 0
    text = (out / "metrics.json").read_text()
    data = json.loads(text, parse_constant=refuse)                     # bare Infinity or NaN would raise
    assert data["metrics"]["consequence_alarm_time"] == "Infinity"
    assert data["metrics"]["alarm_lead_time"] == "-Infinity" and data["metrics"]["position_lost_time"] == "Infinity"
    report = read_report(out / "metrics.json")
    assert report["metrics"]["alarm_lead_time"] == -math.inf and report["metrics"]["consequence_alarm_time"] == math.inf
    assert report["metrics"]["alarm_after_position_loss"] == 0.0 and report["scenario"] == "dp_station_keeping"
    assert report["windows"] == {} and isinstance(report["metrics"]["energy"], float)
