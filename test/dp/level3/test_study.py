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
from allocator_pkg.dp.level3 import engine as level3_engine
from allocator_pkg.dp.level3.study import JOURNAL

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
    assert "Headings every 90 deg: coarser than the standard's 10 deg." in text


def test_the_comparison_shows_level_1_as_published_whatever_the_heading_step(uninterrupted):
    """A study every 90 deg compares itself with Level 1 at the standard's 10 deg headings, the one
    ``--dnv-level1`` publishes (docs/dp_capability), not with a Level 1 of its own 4 headings."""
    published = (ROOT / "docs" / "dp_capability" / "dp_vessel_dp_l1.txt").read_text().splitlines()[0].split(": ")[1]
    text = (uninterrupted / "dp_vessel_dp_l3.txt").read_text()
    assert f"at the standard's 10 deg headings: {published}, DP capability-L2(" in text
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


def test_the_footprints_share_one_scale_about_the_limit_with_labelled_axes_and_no_legend_over_a_track(
        uninterrupted, tmp_path):
    """The study again from its journal (nothing runs): every panel 3 times the 0.05 m limit about
    the set-point, metres on the outer axes, the numbers in the titles, one legend under the
    panels, titles inside the figure, and how far a track that leaves the view went."""
    import shutil

    import numpy as np

    from allocator_pkg.capability.report.plotting import pyplot
    from allocator_pkg.dp.level3.case import Criteria
    from allocator_pkg.dp.level3.study import Level3Inputs, study
    from allocator_pkg.dp.report.level3_report import footprints_figure

    shutil.copy(uninterrupted / JOURNAL, tmp_path / JOURNAL)
    inputs = Level3Inputs(*map(ROOT.joinpath, ("config/dp_vessel.yaml", "config/particulars/dp_vessel.yaml")),
                          site=DATA / "sites" / "level3_site.yaml", heading_step=90.0,
                          criteria=Criteria(position_limit=0.05, settle=2.0, duration=6.0))
    prepared, result, finished = study(inputs, tmp_path, workers=1, resume=True, progress=False)
    figure = footprints_figure(prepared, result, finished, "dp_vessel")
    panels = [axes for axes in figure.axes if axes.get_title()]
    assert [axes.get_title().split("\n")[0] for axes in panels] == ["0 deg", "90 deg", "180 deg", "270 deg"]
    for axes, heading in zip(panels, (0.0, 90.0, 180.0, 270.0)):
        assert axes.get_xlim() == pytest.approx((-0.15, 0.15)) and axes.get_ylim() == pytest.approx((-0.15, 0.15))
        assert axes.get_legend() is None
        numbers = {case: prepared.search.outcome((heading, case), finished).number for case in prepared.search.cases}
        assert axes.get_title().replace("\n", " ").endswith(", ".join(f"{c} {n}" for c, n in numbers.items()))
        shown = [finished[key].track for case, n in numbers.items() for key in ((heading, n, case, 0),
                                                                                 (heading, n + 1, case, 0))
                 if key in finished]
        farthest = max(float(np.max(np.abs(np.array(track)))) for track in shown)
        off = [text.get_text() for text in axes.texts]
        assert off == ([f"off view: to {farthest:.0f} m"] if farthest > 0.15 else [])
    assert {axes.get_xlabel() for axes in panels} == {"east [m]"} and {a.get_ylabel() for a in panels[:1]} == \
        {"north [m]"}
    legend = [text.get_text() for text in figure.legends[0].get_texts()]
    assert legend[:len(prepared.search.cases)] == list(prepared.search.cases) and "position limit 0.05 m" in legend
    figure.draw_without_rendering()
    renderer = figure.canvas.get_renderer()
    frame = figure.bbox
    for text in [figure._suptitle, *(axes.title for axes in panels)]:
        box = text.get_window_extent(renderer)
        assert frame.x0 <= box.x0 and box.x1 <= frame.x1 and box.y1 <= frame.y1
    pyplot().close(figure)
