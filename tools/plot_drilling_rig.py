"""docs/power_drilling_rig.png: the drilling-rig benchmark (config/scenarios/drilling_rig_power.yaml
and drilling_rig_power_no_reduction.yaml), run with the allocator library in the loop
(``allocator-sim --in-process``), side by side: with the fast load reduction and without it. Per
switchboard the bus frequency, the power supplied against what the power management system
reports available to the thrusters, and the position error, from 190 s (the bus ties open at
200 s, g5 is lost at 250 s, thruster 6 at 252 s). Prints the benchmark's numbers.

    python tools/plot_drilling_rig.py          (make docs runs it)
"""

import tempfile
from pathlib import Path

from allocator_pkg.capability.report.plotting import pyplot
from allocator_pkg.simulation.closed_loop import ClosedLoop
from allocator_pkg.simulation.in_process import in_process_link
from allocator_pkg.simulation.report.plant_figure import plant_columns
from allocator_pkg.simulation.scenario import load_scenario

plt = pyplot()

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = ROOT / "config" / "scenarios"
RUNS = (("drilling_rig_power.yaml", "with the load reduction"),
        ("drilling_rig_power_no_reduction.yaml", "without the load reduction"))
OUT = ROOT / "docs" / "power_drilling_rig.png"


def main() -> None:
    runs = []
    for name, title in RUNS:
        scenario = load_scenario(SCENARIOS / name)
        with tempfile.TemporaryDirectory() as folder:
            result = ClosedLoop(scenario, Path(folder), in_process_link, log=lambda _: None).run()
        runs.append((result, scenario, title))
        plant = result.report["power_plant"]
        after = result.trace.metrics(result.vehicle, 250.0)["position_error_max"]
        print(f"{title}: " + ", ".join(f"{board} lowest {figures['lowest_frequency']:.4f} pu, "
                                       f"{figures['time_under_frequency']:.1f} s under 0.95"
                                       for board, figures in plant["switchboards"].items()))
        off = [(round(s["time"], 2), s["generator_set"], s["why"]) for s in plant["generator_sets_off"]]
        print(f"  sets off: {off}")
        print(f"  position error max {result.metrics['position_error_max']:.2f} m, after 250 s {after:.2f} m; "
              f"time over available {result.metrics['time_over_available']:.1f} s")
    figure = plant_columns(runs, start=190.0)
    figure.savefig(OUT, dpi=80)
    plt.close(figure)
    print(f"wrote {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
