"""allocator-capability --dnv-level3: the outputs, inputs refused before any case runs, a run
killed midway that resumes to the same result as one never stopped, an interrupted run and a
scheduler that does not answer."""

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import DATA, ROOT
from test_engine import alive

from allocator_pkg.cli.allocator_capability import main
from allocator_pkg.dp.capability_result import SCOPE_L3
from allocator_pkg.dp.inputs.site import SiteSea
from allocator_pkg.dp.level3 import engine as level3_engine
from allocator_pkg.dp.level3.case import CaseSetup, Criteria
from allocator_pkg.dp.level3.study import JOURNAL, environment_note, power_note
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS
from allocator_pkg.simulation.scenario import load_scenario

FILES = [str(ROOT / "config/dp_vessel.yaml"), str(ROOT / "config/particulars/dp_vessel.yaml")]
SMALL = ["--site", str(DATA / "sites" / "level3_site.yaml"), "--headings", "90", "--position-limit", "0.05",
         "--settle", "2", "--duration", "6", "--seeds", "2", "--no-progress"]
TEXT_OUTPUTS = ("dp_vessel_dp_l3.csv", "dp_vessel_dp_l3_table_a1.csv", "dp_vessel_dp_l3_limits.csv",
                "dp_vessel_dp_l3_cases.csv", "dp_vessel_dp_l3_quantiles.csv", "dp_vessel_dp_l3.txt",
                "dp_vessel_dp_l3_report.md")


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    out = tmp_path_factory.mktemp("whole")
    assert main(["--dnv-level3", *FILES, "--out", str(out), "--workers", "2", *SMALL]) == 0
    return out


@pytest.mark.slow
def test_the_report(uninterrupted, capsys):
    names = {path.name for path in uninterrupted.iterdir()}
    for suffix in ("_number.png", "_wind.png", "_groups_number.png", "_vs_l1_l2_number.png", "_vs_l1_l2_wind.png",
                   "_footprints.png", "_quantiles.png", "_transients.png", "_table_a2.csv", "_table_a3.csv",
                   "_table_a5.csv"):
        assert f"dp_vessel_dp_l3{suffix}" in names
    assert set(TEXT_OUTPUTS) <= names and JOURNAL in names
    text = (uninterrupted / "dp_vessel_dp_l3.txt").read_text()
    assert text.startswith("dp_vessel (MSS osv hull, some inputs estimated): DP capability-L3(")
    assert "position_limit 0.05 m; heading_limit_deg 3 deg; settle 2 s; duration 6 s; seeds 2; quantile 0.9;" in text
    assert "Criteria (criteria file keys):\n  position_limit: 0.05 m\n  heading_limit_deg: 3 deg\n" in text
    assert "Assumed where the standard's Level 3 text was not available:" in text
    assert "Seeds per condition: 2 (indices 0 ... 1, the same for every condition)" in text
    for name in TEXT_OUTPUTS:
        lines = (uninterrupted / name).read_text().splitlines()
        stated = "\n".join(lines[:2]) if name.endswith(".csv") else "\n".join(lines)
        assert "Not verified by DNV" in stated and "post_failure_window 60 s" in stated.replace(": ", " "), name
    assert SCOPE_L3 in text and "Not simulated, the static Level 2 balance already fails them" in text
    assert "the current's slow variation); method qp." in text
    assert "Environment: NPD gusts on the mean wind, a long-crested JONSWAP sea" in text
    assert "DP system: " in text
    assert "Headings every 90 deg: coarser than the standard's 10 deg." in text


def test_the_comparison_shows_level_1_as_published_whatever_the_heading_step(uninterrupted):
    """A study every 90 deg compares itself with Level 1 at the standard's 10 deg headings, the one
    ``--dnv-level1`` publishes (docs/dp_capability), not with a Level 1 of its own 4 headings."""
    published = (ROOT / "docs" / "dp_capability" / "dp_vessel_dp_l1.txt").read_text().splitlines()[0].split(": ")[1]
    text = (uninterrupted / "dp_vessel_dp_l3.txt").read_text()
    assert f"at the standard's 10 deg headings: {published}, DP capability-L2(" in text
    cases = (uninterrupted / "dp_vessel_dp_l3_cases.csv").read_text().splitlines()
    assert cases[1].startswith("# ") and "position_limit 0.05 m" in cases[1]
    assert cases[2] == ("case,heading_deg,capability_number,seed,wind_speed,hs,tp,current,max_position_m,"
                        "mean_position_m,max_heading_deg,steady_position_m,steady_heading_deg,transient_position_m,"
                        "transient_heading_deg,held")


def test_numbers_follow_the_conditions_and_the_static_ceiling(uninterrupted):
    """The numbers against the conditions' verdicts in _quantiles.csv, which follow from its
    quantiles and the limits; every condition has both seeds in _cases.csv."""
    rows = [line.split(",") for line in (uninterrupted / "dp_vessel_dp_l3_quantiles.csv").read_text().splitlines()[3:]]
    held = {(r[0], float(r[1]), int(r[2])): r[-1] == "True" for r in rows}
    for row in rows:
        quantiles = [float(row[k]) for k in (4, 10, 16, 22) if row[k]]
        assert row[3] == "2"
        assert held[(row[0], float(row[1]), int(row[2]))] == (quantiles[0] <= 0.05 and quantiles[1] <= 3.0 and
                                                             all(q <= lim for q, lim in zip(quantiles[2:], (5.0, 3.0))))
    runs = [line.split(",") for line in (uninterrupted / "dp_vessel_dp_l3_cases.csv").read_text().splitlines()[3:]]
    assert sorted((r[0], float(r[1]), int(r[2]), int(r[3])) for r in runs) == sorted(
        (c, h, n, s) for c, h, n in held for s in (0, 1))
    limits = [line.split(",") for line in (uninterrupted / "dp_vessel_dp_l3_limits.csv").read_text().splitlines()[3:]]
    assert len(limits) == 12                                   # 4 headings, intact and two groups
    for case, heading, number, reason in limits:
        heading, number = float(heading), int(number)
        assert all(held[(case, heading, n)] for n in range(1, number + 1))
        if reason == "failed":
            assert not held[(case, heading, number + 1)]
        else:
            assert (case, heading, number + 1) not in held     # not simulated: static Level 2 or the top
    table = [line.split(",") for line in (uninterrupted / "dp_vessel_dp_l3.csv").read_text().splitlines()[3:]]
    numbers = {(c, float(h)): int(n) for c, h, n, _ in table}
    for case, heading, number, _ in limits:
        assert numbers[(case, float(heading))] == int(number)
    for heading in (0.0, 90.0, 180.0, 270.0):
        assert numbers[("worst single failure", heading)] == min(numbers[("switchboard_a", heading)],
                                                                  numbers[("switchboard_b", heading)])


@pytest.mark.parametrize("bad, message", [
    (["--seeds", "0"], "seeds: an integer >= 1"), (["--headings", "7"], "--headings"),
    (["--position-limit", "-1"], "position_limit"), (["--workers", "0"], "--workers"),
    (["--duration", "nan"], "duration"), (["--level3-criteria", str(DATA / "missing.yaml")], "missing.yaml"),
    (["--level3-criteria", str(ROOT / "config/dp_vessel.yaml")], "unknown key(s)"),
    (["--scenario", str(ROOT / "config/scenarios/drilling_rig_power.yaml")],
     "its power_plant feeds swbd_1, swbd_2, swbd_3, not a power source of dp_vessel.yaml (swbd_a, swbd_b)")])
def test_bad_inputs_are_refused_before_the_first_case(bad, message, tmp_path, capsys):
    assert main(["--dnv-level3", *FILES, "--out", str(tmp_path), *SMALL, *bad]) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / JOURNAL).exists()


@pytest.mark.slow
def test_a_killed_run_resumes_to_the_same_result(uninterrupted, tmp_path):
    environment = {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
                   "ROS_DOMAIN_ID": os.environ.get("ROS_DOMAIN_ID", "42"), "PYTHONPATH": str(ROOT)}
    process = subprocess.Popen([sys.executable, "-m", "allocator_pkg.cli.allocator_capability", "--dnv-level3", *FILES,
                                "--out", str(tmp_path), "--workers", "1", *SMALL], env=environment,
                               start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    journal = tmp_path / JOURNAL
    deadline = time.monotonic() + 60.0
    while time.monotonic() < deadline and process.poll() is None:
        if journal.exists() and len(journal.read_text().splitlines()) >= 6:
            break
        time.sleep(0.02)
    os.killpg(process.pid, signal.SIGKILL)
    process.wait()
    done = len(journal.read_text().splitlines()) - 1
    whole = len((uninterrupted / JOURNAL).read_text().splitlines()) - 1
    assert 5 <= done < whole                                  # killed midway
    assert main(["--dnv-level3", *FILES, "--out", str(tmp_path), "--workers", "2", "--resume", *SMALL]) == 0
    assert len(journal.read_text().splitlines()) - 1 == whole     # nothing finished ran again
    for name in TEXT_OUTPUTS:
        assert (tmp_path / name).read_text() == (uninterrupted / name).read_text()


def children(pid: int) -> set[int]:
    """The pool workers ``pid`` started (Linux /proc), not multiprocessing's resource tracker."""
    found = {int(child) for task in Path(f"/proc/{pid}/task").iterdir()
             for child in (task / "children").read_text().split()}
    return {child for child in found if b"resource_tracker" not in _command_line(child)}


def _command_line(pid: int) -> bytes:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes()
    except (FileNotFoundError, ProcessLookupError):
        return b""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_sigint_ends_in_one_line_and_status_130(tmp_path):
    environment = {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
                   "ROS_DOMAIN_ID": os.environ.get("ROS_DOMAIN_ID", "42"), "PYTHONPATH": str(ROOT)}
    process = subprocess.Popen([sys.executable, "-m", "allocator_pkg.cli.allocator_capability", "--dnv-level3", *FILES,
                                "--out", str(tmp_path), "--workers", "2", *SMALL], env=environment,
                               start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    journal = tmp_path / JOURNAL
    workers: set[int] = set()
    try:
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline and process.poll() is None:
            if journal.exists() and len(journal.read_text().splitlines()) >= 3:
                break
            time.sleep(0.02)
        workers = children(process.pid)
        process.send_signal(signal.SIGINT)             # the parent only
        _, err = process.communicate(timeout=60)
        assert process.returncode == 130
        done = len(journal.read_text().splitlines()) - 1
        assert done >= 2
        lines = err.strip().splitlines()
        assert len(lines) == 1
        assert re.fullmatch(rf"allocator-capability: interrupted after {done} of \d+ cases; rerun with --resume",
                            lines[0])
        assert len(workers) == 2 and not any(map(alive, workers))
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        for pid in filter(alive, workers):
            os.kill(pid, signal.SIGKILL)


def test_an_unreachable_scheduler_is_refused_before_the_analysis_and_the_journal(tmp_path, capsys, monkeypatch):
    pytest.importorskip("dask.distributed")
    monkeypatch.setattr(level3_engine, "CONNECT_TIMEOUT", 1.0)
    earlier = '{"level3": "1"}\n{"an earlier": "case"}\n'
    (tmp_path / JOURNAL).write_text(earlier)
    missing = str(tmp_path / "missing.yaml")             # the scheduler is checked before the files
    assert main(["--dnv-level3", missing, FILES[1], "--out", str(tmp_path), *SMALL,
                 "--scheduler", "tcp://127.0.0.1:9"]) == 2
    assert "--scheduler tcp://127.0.0.1:9: no Dask scheduler answers there within 1 s" in capsys.readouterr().err
    assert (tmp_path / JOURNAL).read_text() == earlier


def test_the_criteria_file_gives_the_criteria_and_an_option_overrides_its_key(tmp_path):
    import argparse

    from allocator_pkg.cli.allocator_capability import add_level3_arguments, level3_criteria
    from allocator_pkg.dp.level3.case import Criteria

    parser = argparse.ArgumentParser()
    add_level3_arguments(parser)
    path = tmp_path / "criteria.yaml"
    path.write_text("seeds: 4\nquantile: 0.8\nposition_limit: 2\n")
    assert level3_criteria(parser.parse_args([])) == Criteria()
    assert level3_criteria(parser.parse_args(["--level3-criteria", str(path)])) == Criteria(2.0, seeds=4,
                                                                                           quantile=0.8)
    overridden = parser.parse_args(["--level3-criteria", str(path), "--seeds", "6", "--position-limit", "3",
                                    "--heading-limit", "4", "--settle", "5", "--duration", "7"])
    assert level3_criteria(overridden) == Criteria(3.0, 4.0, 5.0, 7.0, seeds=6, quantile=0.8)


@pytest.mark.parametrize(("sea", "spectra", "says", "not_said"), [
    (SiteSea(), True, ["a long-crested JONSWAP sea", "DNV-RP-C205's peak factor", "Level 1's collinear"],
     ["site directions", "spreading"]),
    (SiteSea((0.0, 2.0), 3.0, 20.0, None), True,
     ["cos^3 spreading", "the site's peak factor", "averaged over the spreading's directions",
      "site directions: waves from 20 deg and current from 0 deg relative to the wind"], ["collinear"]),
    (SiteSea(current_direction=-30.0), False, ["current from -30 deg relative to the wind"], ["collinear"]),
])
def test_the_environment_note_says_which_sea_and_directions(sea, spectra, says, not_said):
    setup = CaseSetup(load_scenario(ROOT / "config/scenarios/dp_station_keeping.yaml"), WEATHER_CONDITIONS, {},
                      frozenset(), Criteria(), spectra=spectra, sea=sea)
    note = environment_note(setup)
    assert all(text in note for text in says) and not any(text in note for text in not_said)


def test_the_power_note_says_whether_a_plant_is_simulated(tmp_path):
    base = load_scenario(ROOT / "config/scenarios/dp_station_keeping.yaml")
    assert power_note(CaseSetup(base, WEATHER_CONDITIONS, {}, frozenset(), Criteria())).startswith(
        "Power: no power plant simulated")
    plant = load_scenario(ROOT / "config/scenarios/drilling_rig_power.yaml")
    note = power_note(CaseSetup(plant, WEATHER_CONDITIONS, {}, frozenset(), Criteria()))
    assert "simulated power plant (6 generator sets" in note and "fast load reduction" in note


@pytest.mark.slow
def test_a_sites_sea_reaches_the_level_3_outputs(tmp_path):
    """A site file with the sea's keys: the Level 3 notes say the spread sea, its peak factor and
    the site's directions; Level 2's part says it stays collinear."""
    site = tmp_path / "sea.yaml"
    site.write_text((DATA / "sites" / "level3_site.yaml").read_text()
                    + "peak_factor: [1.5, 2.5, 3.3]\nspreading: 2\nwave_direction: 30\ncurrent_direction: -60\n")
    small = [*SMALL[2:], "--site", str(site)]
    assert main(["--dnv-level3", *FILES, "--out", str(tmp_path), "--workers", "1", *small]) == 0
    text = (tmp_path / "dp_vessel_dp_l3.txt").read_text()
    for said in ("a short-crested JONSWAP sea (cos^2 spreading", "(the site's peak factor)",
                 "site directions: waves from 30 deg and current from -60 deg relative to the wind",
                 "JONSWAP sea with peak factor 1.5, 2.5, 3.3 (numbers 1 to 3)", "Level 2 collinear."):
        assert said in text
