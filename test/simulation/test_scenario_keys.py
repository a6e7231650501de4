"""The scenario file's one key table: the docs, the reader's defaults and bounds."""

from conftest import ROOT

from allocator_pkg.configuration.file_keys import markdown_table
from allocator_pkg.simulation.scenario_keys import SCENARIO_KEYS, scenario_key


def test_closed_loop_doc_lists_the_scenario_keys():
    text = (ROOT / "docs" / "closed_loop.md").read_text()
    assert markdown_table(SCENARIO_KEYS) in text, "docs/closed_loop.md is out of date: run `make docs`"


def test_a_key_is_found_at_its_path_at_any_depth():
    assert scenario_key("environment.waves.peak_period").default == 8.0
    assert scenario_key("events[3].weather_ramp.duration").minimum == 0.0
    assert scenario_key("windows[0].bounds.position_error_max").minimum == 0.0
    assert scenario_key("events[0].setpoint.speed").exclusive_minimum
    assert scenario_key("environment.tide") is None
