"""make demo in a short run: the closed loop with the node as a process, started loaded, the
azimuth failing and recovering, the live table, the PNGs."""

import subprocess
import sys

import pytest
from conftest import ROOT

pytestmark = pytest.mark.slow


def test_demo_short_run_writes_its_figures(tmp_path):
    out = tmp_path / "demo"
    command = [sys.executable, "-m", "allocator_pkg.cli.demo", "--scenario",
               str(ROOT / "config" / "scenarios" / "dp_azimuth_failure.yaml"), "--duration", "20", "--every", "2",
               "--out", str(out)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "sim: warm-up: 200 steps of the equilibrium request; thrusters start at azimuth_stbd" in result.stdout
    assert "azimuth_port: FAILED" in result.stdout
    assert "cleared faults of azimuth_port" in result.stdout
    table = [line for line in result.stdout.splitlines() if " err " in line and "azimuth_stbd" in line]
    assert len(table) >= 9                                     # a line every 2 s of 20 s
    took = [line for line in result.stdout.splitlines() if line.startswith("demo: took ")]
    assert len(took) == 1 and float(took[0].split()[2]) > 0.0 and "on this machine" in took[0]
    for name in ("footprint", "timeline"):
        path = out / f"{name}.png"
        assert f"{name} written to {path}" in result.stdout
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
