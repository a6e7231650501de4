"""allocator-capability --dnv-level3: the outputs, inputs refused before any case runs, and a run
killed midway that resumes to the same result as one never stopped."""

import os
import signal
import subprocess
import sys
import time

import pytest
from conftest import DATA, ROOT

from allocator_pkg.cli.capability import main
from allocator_pkg.cli.dp_level3 import JOURNAL, SCOPE_L3

FILES = [str(ROOT / "config/dp_vessel.yaml"), str(ROOT / "config/particulars/dp_vessel.yaml")]
SMALL = ["--site", str(DATA / "sites" / "level3_site.yaml"), "--headings", "90", "--position-limit", "0.05",
         "--settle", "2", "--duration", "6", "--no-progress"]
TEXT_OUTPUTS = ("dp_vessel_dp_l3.csv", "dp_vessel_dp_l3_table_a1.csv", "dp_vessel_dp_l3_limits.csv",
                "dp_vessel_dp_l3_cases.csv", "dp_vessel_dp_l3.txt")


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    out = tmp_path_factory.mktemp("whole")
    assert main(["--dnv-level3", *FILES, "--out", str(out), "--workers", "2", *SMALL]) == 0
    return out


@pytest.mark.slow
def test_the_report(uninterrupted, capsys):
    names = {path.name for path in uninterrupted.iterdir()}
    for suffix in ("_number.png", "_wind.png", "_groups_number.png", "_vs_l1_l2_number.png", "_vs_l1_l2_wind.png",
                   "_footprints.png", "_table_a2.csv", "_table_a3.csv", "_table_a5.csv"):
        assert f"dp_vessel_dp_l3{suffix}" in names
    assert set(TEXT_OUTPUTS) <= names and JOURNAL in names
    text = (uninterrupted / "dp_vessel_dp_l3.txt").read_text()
    assert text.startswith("dp_vessel (MSS osv hull, some inputs estimated): DP capability-L3(")
    assert "position limit 0.05 m, heading limit 3 deg, 2 s on station (a group fails then) + 6 s" in text
    assert SCOPE_L3 in text and "Not simulated, the static Level 2 balance already fails them" in text
    assert "gusts at its turbulence intensity); method qp." in text
    cases = (uninterrupted / "dp_vessel_dp_l3_cases.csv").read_text().splitlines()
    assert cases[1].startswith("# ") and "position limit 0.05 m" in cases[1]
    assert cases[2] == ("case,heading_deg,capability_number,seed,wind_speed,hs,tp,current,max_position_m,"
                        "mean_position_m,max_heading_deg,held")


def test_numbers_follow_the_cases_and_the_static_ceiling(uninterrupted):
    rows = [line.split(",") for line in (uninterrupted / "dp_vessel_dp_l3_cases.csv").read_text().splitlines()[3:]]
    held = {(r[0], float(r[1]), int(r[2])): r[-1] == "True" for r in rows}
    limits = [line.split(",") for line in (uninterrupted / "dp_vessel_dp_l3_limits.csv").read_text().splitlines()[3:]]
    assert len(limits) == 12                                   # 4 headings, intact and two groups
    for case, heading, number, reason in limits:
        heading, number = float(heading), int(number)
        assert all(held[(case, heading, n)] for n in range(1, number + 1))
        if reason == "failed":
            assert not held[(case, heading, number + 1)]
        else:
            assert (case, heading, number + 1) not in held     # not simulated: static Level 2 or the top
    table = [line.split(",") for line in (uninterrupted / "dp_vessel_dp_l3.csv").read_text().splitlines()[2:]]
    numbers = {(c, float(h)): int(n) for c, h, n, _ in table}
    for case, heading, number, _ in limits:
        assert numbers[(case, float(heading))] == int(number)
    for heading in (0.0, 90.0, 180.0, 270.0):
        assert numbers[("worst single failure", heading)] == min(numbers[("switchboard_a", heading)],
                                                                  numbers[("switchboard_b", heading)])


@pytest.mark.parametrize("bad, message", [
    (["--seeds", "0"], "--seeds"), (["--headings", "7"], "--headings"), (["--position-limit", "-1"], "position_limit"),
    (["--workers", "0"], "--workers"), (["--duration", "nan"], "duration")])
def test_bad_inputs_are_refused_before_the_first_case(bad, message, tmp_path, capsys):
    assert main(["--dnv-level3", *FILES, "--out", str(tmp_path), *SMALL, *bad]) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / JOURNAL).exists()


@pytest.mark.slow
def test_a_killed_run_resumes_to_the_same_result(uninterrupted, tmp_path):
    environment = {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
                   "ROS_DOMAIN_ID": os.environ.get("ROS_DOMAIN_ID", "42"), "PYTHONPATH": str(ROOT)}
    process = subprocess.Popen([sys.executable, "-m", "allocator_pkg.cli.capability", "--dnv-level3", *FILES, "--out",
                                str(tmp_path), "--workers", "1", *SMALL], env=environment, start_new_session=True,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
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
