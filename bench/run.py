"""make bench: run the solver and node benchmarks, write bench/results/latest.json and
regenerate docs/performance.md from it. Every figure compared in the report comes from
this one run, on this machine."""

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


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="short sequences and node runs (a smoke test)")
    arguments = parser.parse_args(argv)
    RESULTS.mkdir(parents=True, exist_ok=True)
    samples = 300 if arguments.quick else solver.SAMPLES
    result = {"machine": machine(), "quick": arguments.quick}
    result["solver"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "solver.py"), "--samples",
                                            str(samples)]))
    result["settling"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "settling.py")]
                                             + ([] if arguments.quick else ["--full"])))
    node_out = RESULTS / "node.json"
    subprocess.run([sys.executable, str(ROOT / "bench" / "node.py"), "--out", str(node_out)]
                   + (["--quick"] if arguments.quick else []), check=True)
    result["node"] = json.loads(node_out.read_text())
    overhead_out = RESULTS / "overhead.json"
    subprocess.run([sys.executable, str(ROOT / "bench" / "overhead.py"), "--out", str(overhead_out)]
                   + (["--seconds", "3", "--rounds", "1"] if arguments.quick else ["--seconds", "8", "--rounds", "3"]),
                   check=True)
    result["overhead"] = json.loads(overhead_out.read_text())
    result["idle_core"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "idle_core.py")]
                                              + (["--rounds", "1", "--samples", "100"] if arguments.quick else [])))
    result["dp_capability"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "dp_capability.py")]
                                                  + (["--repeats", "1", "--heading-step", "30"] if arguments.quick
                                                     else [])))
    result["power_cost"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "power_cost.py")]
                                               + (["--samples", "600"] if arguments.quick else [])))
    consequence_out = RESULTS / "consequence.json"
    subprocess.run([sys.executable, str(ROOT / "bench" / "consequence.py"), "--out", str(consequence_out)]
                   + (["--seconds", "3", "--rounds", "1"] if arguments.quick else []), check=True)
    result["consequence"] = json.loads(consequence_out.read_text())
    result["inprocess_sim"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "inprocess_sim.py")]
                                                  + (["--repeats", "1"] if arguments.quick else [])))
    result["dp_level3"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "dp_level3.py")]
                                              + (["--settle", "10", "--duration", "30"] if arguments.quick else [])))
    result["dp_level3_study"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "dp_level3.py"), "--study",
                                                    "--seeds", "2", "--settle", "30", "--duration",
                                                    "30" if arguments.quick else "120"]))
    result["environment_cost"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "environment_cost.py")]
                                                     + (["--duration", "30"] if arguments.quick else [])))
    result["dp_step_costs"] = json.loads(_capture([sys.executable, str(ROOT / "bench" / "dp_step_costs.py")]
                                                  + (["--settle", "20", "--duration", "60"] if arguments.quick
                                                     else [])))
    load_out = RESULTS / "load.json"
    subprocess.run([sys.executable, str(ROOT / "bench" / "load.py"), "--out", str(load_out)]
                   + (["--seconds", "10"] if arguments.quick else []), check=False)
    result["load"] = json.loads(load_out.read_text())
    latest = RESULTS / "latest.json"
    latest.write_text(json.dumps(result, indent=1))
    report.write(result, ROOT / "docs" / "performance.md")
    print(f"bench: wrote {latest} and docs/performance.md")
    return 0


def _capture(command: list[str]) -> str:
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout


if __name__ == "__main__":
    sys.exit(main())
