"""What thrust bias buys and costs in closed loop: config/scenarios/dp_calm_bias.yaml run by
allocator-sim's loop (the real allocator_node, lock-step on sim time, the same seed) with the
bias off and on, at each bias thrust asked for. Per run: the azimuth travel (sum of |delta
alpha| over the run), the energy and mean power of the power model (1.44), and the position and
heading error; per bias thrust, the travel's ratio to the run without bias and the extra power.

    .venv/bin/python bench/thrust_bias.py [--thrust 30000 60000] [--duration-scale 1] [--out DIR]

Prints a Markdown table (docs/closed_loop.md, thrust bias, quotes it) and writes it with the
figures as thrust_bias.json into DIR (default build/thrust_bias).
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import replace
from pathlib import Path

from allocator_pkg.cli.allocator_sim import run
from allocator_pkg.simulation.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / "config" / "scenarios" / "dp_calm_bias.yaml"


def measure(thrusts: list[float | None], scale: float, out: Path) -> list[dict]:
    """One run per bias thrust (None: the vehicle file's), and one with the bias off first."""
    scenario = load_scenario(SCENARIO)
    if scale != 1.0:
        scenario = scenario.scaled(scale)
    rows = []
    for thrust in [0.0, *thrusts]:
        parameters = {**scenario.parameters, "bias.enabled": thrust != 0.0}
        if thrust:
            parameters["bias.thrust"] = thrust
        name = "off" if thrust == 0.0 else f"bias_{thrust or 'file'}"
        result = run(replace(scenario, parameters=parameters), out / name, log=lambda _: None)
        metrics = result.metrics
        rows.append({"bias_thrust": thrust if thrust is not None else result.vehicle.bias.thrust,
                     "azimuth_travel": metrics["azimuth_travel"], "energy": metrics["energy"],
                     "mean_power": metrics["energy"] / scenario.duration / 1e3,
                     "position_error_max": metrics["position_error_max"],
                     "heading_error_max": metrics["heading_error_max"]})
    off = rows[0]
    for row in rows:
        row["travel_ratio"] = row["azimuth_travel"] / off["azimuth_travel"]
        row["extra_power"] = row["mean_power"] - off["mean_power"]
    return rows


def table(rows: list[dict], duration: float) -> str:
    lines = [f"| bias.thrust [kN] | azimuth travel [rad] in {duration:g} s | travel / without bias | mean power [kW] | "
             "extra power [kW] | position error max [m] | heading error max [deg] |",
             "|---|---|---|---|---|---|---|"]
    for row in rows:
        thrust = "off" if row["bias_thrust"] == 0.0 else f"{row['bias_thrust'] / 1e3:g}"
        lines.append(f"| {thrust} | {row['azimuth_travel']:.3f} | {row['travel_ratio']:.2f} | {row['mean_power']:.1f} "
                     f"| {row['extra_power']:.1f} | {row['position_error_max']:.3f} | {row['heading_error_max']:.3f} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--thrust", type=float, nargs="*", default=[],
                        help="bias thrusts [N] to run (default: the vehicle file's)")
    parser.add_argument("--duration-scale", type=float, default=1.0)
    parser.add_argument("--out", type=Path, default=ROOT / "build" / "thrust_bias")
    arguments = parser.parse_args(argv)
    rows = measure(arguments.thrust or [None], arguments.duration_scale, arguments.out)
    duration = load_scenario(SCENARIO).duration * arguments.duration_scale
    text = table(rows, duration)
    arguments.out.mkdir(parents=True, exist_ok=True)
    (arguments.out / "thrust_bias.json").write_text(json.dumps({"duration": duration, "runs": rows}, indent=2) + "\n")
    print(text, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
