"""allocator_pkg.simulation.report.plant_figure: plant.png of a short drilling-rig run without
load reduction: a frequency, a power and a position panel, a line per switchboard, the set the
relay tripped named, the events marked; and allocator-sim's files include it."""

from __future__ import annotations

import pytest
from conftest import ROOT

from allocator_pkg.capability.report.plotting import pyplot
from allocator_pkg.simulation.closed_loop import ClosedLoop
from allocator_pkg.simulation.in_process import in_process_link
from allocator_pkg.simulation.report.figures import plot_run
from allocator_pkg.simulation.report.plant_figure import plant_figure
from allocator_pkg.simulation.scenario import load_scenario


@pytest.mark.slow
def test_the_plant_figure_of_a_trip(tmp_path):
    text = (ROOT / "config" / "scenarios" / "drilling_rig_power_no_reduction.yaml").read_text()
    for old, new in (("../", str(ROOT / "config") + "/"), ("duration: 320.0", "duration: 40.0"),
                     ("time: 200.0", "time: 5.0"), ("time: 250.0", "time: 20.0"), ("time: 252.0", "time: 22.0"),
                     ("start: 100.0", "start: 0.0")):
        text = text.replace(old, new)
    path = tmp_path / "rig.yaml"
    path.write_text(text)
    scenario = load_scenario(path)
    result = ClosedLoop(scenario, tmp_path / "out", in_process_link, log=lambda line: None).run()
    figure = plant_figure(result, scenario)
    frequency, power, position = figure.axes
    assert len(frequency.lines) >= 3 and len(power.lines) >= 6 and len(position.lines) >= 1
    assert [line.get_label() for line in frequency.lines[:3]] == ["swbd_1", "swbd_2", "swbd_3"]
    assert "g6 tripped" in [text.get_text() for text in frequency.texts]
    assert {"generator trip", "thruster_6 FAILED"} <= {text.get_text() for text in frequency.texts}
    pyplot().close(figure)
    plot_run(tmp_path, result, scenario)
    assert (tmp_path / "plant.png").is_file()
