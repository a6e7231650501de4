"""The Level 1 and 2 report writer writes a complete result: it solves no linear programme and
reads no input file, and gives the paths in the order the command prints them."""

from pathlib import Path

import pytest
from conftest import ROOT

from allocator_pkg.capability import envelope
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.level2 import Level2
from allocator_pkg.dp.report.files import write_report
from allocator_pkg.dp.vessel_files import read_vessel_files

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"


@pytest.fixture(scope="module")
def computed():
    """dp_vessel's files, its Level 1 and Level 2 analyses and results at 90 deg (Level 2's with
    Level 1's)."""
    files = read_vessel_files(DP_VESSEL, DP_PARTICULARS)
    level1 = Level1(files.vehicle, files.particulars)
    level2 = Level2(files.vehicle, files.particulars)
    first = level1.run(90.0)
    return files, (level1, first), (level2, level2.run(90.0, (first,)))


def test_the_report_solves_nothing_and_reads_no_file(computed, tmp_path, monkeypatch):
    files, *levels = computed

    def refused(*_, **__):
        raise AssertionError("the report writer solved a linear programme or read a file")

    monkeypatch.setattr(envelope, "solve_linear_programme", refused)
    monkeypatch.setattr(Path, "read_text", refused)
    for analysis, result in levels:
        paths = write_report(tmp_path, files, analysis, result)
        stem = f"dp_vessel_dp_l{result.level}"
        assert [p.name for p in paths[-3:]] == [f"{stem}_loads.csv", f"{stem}.txt", f"{stem}_report.md"]
        assert all(path.exists() for path in paths)
    assert (tmp_path / "dp_vessel_dp_l2_vs_l1_number.png").exists()
    assert not (tmp_path / "dp_vessel_dp_l1_vs_l1_number.png").exists()


def test_the_allocations_are_every_case_and_heading_at_its_number(computed):
    _, (analysis, result), _ = computed
    keys = [(a.case, a.heading_deg, a.number) for a in result.allocations]
    assert keys == [(case, float(heading), int(result.numbers[case][k])) for case in analysis.cases()
                    for k, heading in enumerate(result.headings_deg)]
