"""The input files of a Level 1 or 2 analysis read once: the vehicle and particulars files, the
site file if given, and the particulars file's statement of each commented top-level value."""

import pytest
from conftest import ROOT

from allocator_pkg.dp.vessel_files import read_vessel_files, stated_values

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
DP_PARTICULARS = ROOT / "config" / "particulars" / "dp_vessel.yaml"


def test_a_commented_top_level_key_is_stated_and_nothing_else():
    text = "# a header\nlpp: 83.0   # m, osv.m\nbeam: 18.0\nthrusters:\n  a: 1  # nested\nlos: 85 #m\n"
    assert stated_values(text) == (("lpp", "83.0", "m, osv.m"), ("los", "85", "m"))


def test_the_files_of_dp_vessel():
    files = read_vessel_files(str(DP_VESSEL), str(DP_PARTICULARS))
    assert files.vehicle_path == DP_VESSEL and files.particulars_path == DP_PARTICULARS
    assert files.site is None and files.particulars.hull.lpp == 83.0
    assert set(files.particulars.thrusters) == set(files.vehicle.names)
    assert files.stated[0] == ("lpp", "83.0", "m, osv.m")


def test_a_missing_particulars_file_is_refused_naming_it(tmp_path):
    with pytest.raises(ValueError, match=r"missing\.yaml"):
        read_vessel_files(DP_VESSEL, tmp_path / "missing.yaml")


def test_the_particulars_file_is_read_once(monkeypatch):
    """Its keys and its comments come from one read of the file."""
    from pathlib import Path

    reads: list[Path] = []
    read_text = Path.read_text

    def counted(path, *args, **kwargs):
        reads.append(Path(path))
        return read_text(path, *args, **kwargs)

    monkeypatch.setattr(Path, "read_text", counted)
    read_vessel_files(DP_VESSEL, DP_PARTICULARS)
    assert reads.count(DP_PARTICULARS) == 1
