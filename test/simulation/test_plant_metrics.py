"""allocator_pkg.simulation.plant_metrics: the power plant's figures of metrics.json, counted by
hand on a made-up record."""

from __future__ import annotations

import pytest

from allocator_pkg.simulation.electric_plant import RELAY, PlantRecord
from allocator_pkg.simulation.plant_metrics import plant_report


def test_the_figures_of_a_record():
    record = PlantRecord(time=[0.1, 0.2, 0.3, 0.4, 0.5],
                         frequency=[[1.0, 1.0], [0.96, 1.0], [0.94, 0.99], [0.93, 0.949], [0.0, 1.0]],
                         trips=[(0.25, "g5", "lost (scenario event)"), (0.45, "g6", RELAY)])
    report = plant_report(record, ("a", "b"), 0.1)
    assert report["switchboards"] == {"a": {"lowest_frequency": 0.0, "time_under_frequency": pytest.approx(0.3)},
                                      "b": {"lowest_frequency": 0.949, "time_under_frequency": pytest.approx(0.1)}}
    assert report["metrics"] == {"frequency_dip": 1.0, "time_under_frequency": pytest.approx(0.3),
                                 "generator_sets_tripped": 1.0}
    assert [s["generator_set"] for s in report["generator_sets_off"]] == ["g5", "g6"]


def test_a_quiet_record():
    record = PlantRecord(time=[0.1, 0.2], frequency=[[1.001, 0.999], [0.98, 1.0]])
    report = plant_report(record, ("a", "b"), 0.1)
    assert report["metrics"] == {"frequency_dip": pytest.approx(0.02), "time_under_frequency": 0.0,
                                 "generator_sets_tripped": 0.0}
