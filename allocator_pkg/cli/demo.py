"""make demo: watch the allocator hold a DP vessel on station, in closed loop, while an azimuth
fails and recovers.

Runs a scenario of ``allocator-sim`` (by default ``config/scenarios/dp_azimuth_failure.yaml``):
the real ``allocator_node`` as its own process on sim time, in a namespace of the run's own
(``make run``'s node or another run in the same domain leave it alone), in lock-step with the
simulated vessel, its wind, current and waves, and a station-keeping controller. A compact live table
shows, every few simulated seconds, the position error and every thruster's thrust, command
and azimuth with the solver's figures; at the end the footprint and timeline PNGs are written
and their paths printed, with the real-time factor and the wall time the demo took here.

    python -m allocator_pkg.cli.demo [--scenario FILE] [--duration S] [--every S] [--out DIR]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from ..simulation.report import figures as sim_plots
from ..simulation.run_setup import SimulationError
from ..simulation.scenario import ScenarioError, load_scenario
from .allocator_sim import run

DEFAULT_SCENARIO = Path(__file__).resolve().parents[2] / "config" / "scenarios" / "dp_azimuth_failure.yaml"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="allocator-demo", description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenario", default=str(DEFAULT_SCENARIO), help="scenario file")
    parser.add_argument("--duration", type=float, default=None,
                        help="simulated seconds (the scenario's events scaled with it; default: the scenario's)")
    parser.add_argument("--every", type=float, default=5.0, help="simulated seconds between lines of the table")
    parser.add_argument("--out", default="build/demo", help="output folder")
    parser.add_argument("--no-baseline", action="store_true",
                        help="skip the nominal run (same seed, no failure) drawn dashed for comparison")
    arguments = parser.parse_args(argv)
    start = time.monotonic()
    try:
        scenario = load_scenario(arguments.scenario)
        if arguments.duration is not None:
            scenario = scenario.scaled(arguments.duration / scenario.duration)
        out = Path(arguments.out)
        print(f"demo: {scenario.description} ({scenario.duration:g} s simulated, {scenario.method})", flush=True)
        result = run(scenario, out, live=arguments.every, log=lambda text: print(text, flush=True))
        nominal = None if arguments.no_baseline else sim_plots.nominal_run(scenario, out / "nominal", run)
    except (ScenarioError, SimulationError, ValueError) as error:
        print(f"demo: {error}", file=sys.stderr)
        return 1
    sim_plots.plot_run(out, result, scenario, nominal)
    m = result.metrics
    print(f"demo: position error rms {m['position_error_rms']:.2f} m, max {m['position_error_max']:.2f} m; heading "
          f"error rms {m['heading_error_rms']:.2f} deg; energy {m['energy'] / 1e6:.1f} MJ; "
          f"{100 * m['saturated_fraction']:.0f} % saturated; {m['realtime_factor']:.0f} x real time")
    print(f"demo: footprint written to {(out / 'footprint.png').resolve()}")
    print(f"demo: timeline written to {(out / 'timeline.png').resolve()}")
    print(f"demo: took {time.monotonic() - start:.0f} s of wall time on this machine (runs, nominal run and "
          "figures); the times swing with the machine's load")
    return 0


if __name__ == "__main__":
    sys.exit(main())
