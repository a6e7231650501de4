"""make demo in a short run: the node as a process, the scripted controller, the fault, the PNG."""

import subprocess
import sys

import pytest
from conftest import ROOT

pytestmark = pytest.mark.slow


def test_demo_short_run_writes_its_timeline(tmp_path):
    out = tmp_path / "timeline.png"
    command = [sys.executable, "-m", "allocator_pkg.cli.demo", "--config", str(ROOT / "config" / "dp_vessel.yaml"),
               "--duration", "6", "--out", str(out)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "azimuth_stbd: FAILED" in result.stdout
    assert "cleared faults of azimuth_stbd" in result.stdout
    assert f"timeline written to {out}" in result.stdout
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
