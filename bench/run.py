"""make bench: run the solver, node, DP capability and closed-loop benchmarks, write
bench/results/latest.json and regenerate docs/performance.md from it. Every figure a section
compares comes from that section's one run, on this machine; ``--only`` re-measures the sections
named and keeps the others, and the report says which and when."""

from __future__ import annotations

import os

from allocator_pkg.ros.process import dds_environment

os.environ.update(dds_environment())

import argparse
import datetime
import json
import platform
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import report
import solver

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "bench" / "results"


def machine() -> dict[str, str]:
    """CPU, Python and library versions of this run."""
    cpu = "unknown"
    cpuinfo = Path("/proc/cpuinfo")
    if cpuinfo.exists():
        for line in cpuinfo.read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    versions = {}
    for name in ("numpy", "osqp", "daqp", "scipy", "quadprog", "ros-jazzy-rclpy"):
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = "not installed"
    return {"cpu": cpu, "cores": str(os.cpu_count()), "python": platform.python_version(),
            "platform": platform.platform(), "date": datetime.date.today().isoformat(), **versions}


SECTIONS: dict[str, tuple[str, list[str], list[str]]] = {
    "solver": ("solver.py", ["--samples", str(solver.SAMPLES)], ["--samples", "300"]),
    "settling": ("settling.py", ["--full"], []),
    "node": ("node.py", [], ["--quick"]),
    "overhead": ("overhead.py", ["--seconds", "8", "--rounds", "3"], ["--seconds", "3", "--rounds", "1"]),
    "idle_core": ("idle_core.py", [], ["--rounds", "1", "--samples", "100"]),
    "dp_capability": ("dp_capability.py", [], ["--repeats", "1", "--heading-step", "30"]),
    "power_cost": ("power_cost.py", [], ["--samples", "600"]),
    "consequence": ("consequence.py", [], ["--seconds", "3", "--rounds", "1"]),
    "inprocess_sim": ("inprocess_sim.py", [], ["--repeats", "1"]),
    "dp_level3": ("dp_level3.py", [], ["--settle", "10", "--duration", "30"]),
    "dp_level3_study": ("dp_level3.py", ["--study", "--seeds", "2", "--settle", "30", "--duration", "120"],
                        ["--study", "--seeds", "2", "--settle", "30", "--duration", "30"]),
    "environment_cost": ("environment_cost.py", [], ["--duration", "30"]),
    "dp_step_costs": ("dp_step_costs.py", [], ["--settle", "20", "--duration", "60"]),
    "load": ("load.py", [], ["--seconds", "10"]),
}
"""Each section of the results: its script, its arguments, and those of a quick run."""
WRITES_OUT = ("node", "overhead", "consequence", "load")
"""The sections whose script writes its result to ``--out`` (the others print it)."""


def measure(name: str, quick: bool) -> dict:
    """One section's result, its script run in a process of its own."""
    script, full, short = SECTIONS[name]
    command = [sys.executable, str(ROOT / "bench" / script), *(short if quick else full)]
    if name not in WRITES_OUT:
        return json.loads(_capture(command))
    out = RESULTS / f"{name}.json"
    subprocess.run([*command, "--out", str(out)], check=name != "load")
    return json.loads(out.read_text())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="short sequences and node runs (a smoke test)")
    parser.add_argument("--only", type=lambda text: text.split(","), metavar="SECTION[,SECTION]",
                        help="re-measure these sections alone, the others kept from bench/results/latest.json "
                             f"(the report says which and when): {', '.join(SECTIONS)}")
    arguments = parser.parse_args(argv)
    RESULTS.mkdir(parents=True, exist_ok=True)
    latest = RESULTS / "latest.json"
    if arguments.only:
        unknown = [name for name in arguments.only if name not in SECTIONS]
        if unknown or not latest.exists():
            parser.error(f"--only: unknown section {', '.join(unknown)}" if unknown else
                         f"--only: no {latest} to keep the other sections from")
        result = json.loads(latest.read_text())
        for name in arguments.only:
            result[name] = measure(name, result.get("quick", False))
        result["remeasured"] = {"date": datetime.date.today().isoformat(), "sections": arguments.only}
    else:
        result = {"machine": machine(), "quick": arguments.quick}
        for name in SECTIONS:
            result[name] = measure(name, arguments.quick)
    latest.write_text(json.dumps(result, indent=1))
    report.write(result, ROOT / "docs" / "performance.md")
    print(f"bench: wrote {latest} and docs/performance.md")
    return 0


def _capture(command: list[str]) -> str:
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout


if __name__ == "__main__":
    sys.exit(main())
