"""allocator_pkg.simulation.windows: the automatic windows of a run's faults."""

from types import SimpleNamespace

import pytest

from allocator_pkg.simulation.windows import Window, fault_intervals, fault_windows


def events(*items):
    return [SimpleNamespace(time=time, kind=kind) for time, kind in items]


def test_a_fault_cleared_gives_a_window_during_it_and_one_after_it():
    found = fault_windows(events((100.0, "fault"), (150.0, "fault"), (220.0, "clear_faults")), 300.0)
    assert found == [Window("fault", 100.0, 220.0), Window("after_fault", 220.0, 300.0)]


def test_a_fault_never_cleared_lasts_to_the_end():
    assert fault_windows(events((60.0, "fault"), (150.0, "parameter")), 300.0) == [Window("fault", 60.0, 300.0)]


def test_several_fault_intervals_are_numbered_and_after_ends_at_the_next_fault():
    found = fault_windows(events((10.0, "fault"), (20.0, "clear_faults"), (50.0, "fault"), (70.0, "clear_faults")),
                          100.0)
    assert [(w.name, w.start, w.end) for w in found] == [("fault_1", 10.0, 20.0), ("after_fault_1", 20.0, 50.0),
                                                          ("fault_2", 50.0, 70.0), ("after_fault_2", 70.0, 100.0)]


def test_no_fault_no_window_and_events_after_the_run_do_not_count():
    assert fault_windows(events((10.0, "clear_faults"), (5.0, "battery_ramp")), 100.0) == []
    assert fault_intervals(events((120.0, "fault")), 100.0) == []


def test_a_window_scales_with_the_run():
    assert Window("settled", 60.0, 100.0, {"energy": 1.0}).scaled(0.1) == Window("settled", 6.0, 10.0,
                                                                                  {"energy": 1.0})
    assert Window("w", 1.0, 2.0).scaled(0.5).end == pytest.approx(1.0)
