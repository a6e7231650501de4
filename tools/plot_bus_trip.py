"""docs/power_bus_trip.png: the bus trip of config/scenarios/dp_switchboard_trip.yaml, run with
the allocator library in the loop (``allocator-sim --in-process``; the node in the loop gives
the same trace).

Switchboard B trips at 100 s (its redundancy group fails: the port azimuth and the aft tunnel,
swbd_b at 0 kW); at 160 s switchboard A is down to 450 kW. The figure is the run's timeline:
position and heading error, thrust, azimuth angles, the power estimate, and the power drawn
from each switchboard against what it can give, with the consequence alarm shaded.

    python tools/plot_bus_trip.py          (make docs runs it)
"""

import tempfile
from pathlib import Path

from allocator_pkg.capability.report.plotting import pyplot
from allocator_pkg.simulation.closed_loop import ClosedLoop
from allocator_pkg.simulation.in_process import in_process_link
from allocator_pkg.simulation.report.timeline import timeline_figure
from allocator_pkg.simulation.scenario import load_scenario

plt = pyplot()

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / "config" / "scenarios" / "dp_switchboard_trip.yaml"
OUT = ROOT / "docs" / "power_bus_trip.png"


def main() -> None:
    scenario = load_scenario(SCENARIO)
    with tempfile.TemporaryDirectory() as folder:
        result = ClosedLoop(scenario, Path(folder), in_process_link, log=lambda _: None).run()
    figure = timeline_figure(result, scenario)
    figure.savefig(OUT, dpi=80)
    plt.close(figure)
    print(f"wrote {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
