"""allocator_pkg.simulation.power_plant_file: a scenario's power_plant section read into the
plant, and every mistake refused at load naming its key."""

from __future__ import annotations

import pytest
from conftest import ROOT

from allocator_pkg.simulation.scenario import ScenarioError, load_scenario

RIG = ROOT / "config" / "scenarios" / "drilling_rig_power.yaml"


def variant(tmp_path, old: str, new: str):
    text = RIG.read_text()
    assert old in text, old
    text = text.replace(old, new).replace("../drilling_rig.yaml", str(ROOT / "config" / "drilling_rig.yaml"))
    text = text.replace("../particulars/", str(ROOT / "config" / "particulars") + "/")
    path = tmp_path / "rig.yaml"
    path.write_text(text)
    return load_scenario(path)


def test_the_benchmark_reads_marpowsims_plant():
    plant = load_scenario(RIG).power_plant
    assert [s.name for s in plant.generator_sets] == ["g1", "g2", "g3", "g4", "g5", "g6"]
    g = plant.generator_sets[0]
    assert (g.rating, g.inertia, g.droop, g.under_frequency, g.over_frequency, g.trip_delay) == (
        9100.0, 2 * 1.2027, 0.02, 0.9, 1.1, 0.1)
    assert g.rated_power == pytest.approx(7735.0)
    assert (plant.management.reaction_time, plant.management.ramp_time) == (1.0, 45.0)
    assert (plant.load_reduction.reaction_time, plant.load_reduction.restore_time) == (0.2, 5.0)
    pulses = [c for c in plant.consumers if c.on > 0.0]
    assert [(c.switchboard, c.power, c.on, c.off, c.start) for c in pulses] == [
        ("swbd_1", 1600.0, 60.0, 120.0, 100.0), ("swbd_3", 1600.0, 60.0, 120.0, 100.0)]
    assert [pulses[0].at(t) for t in (99.0, 100.0, 159.0, 160.0, 279.0, 280.0)] == [0, 1600, 1600, 0, 0, 1600]
    off = load_scenario(RIG.with_name("drilling_rig_power_no_reduction.yaml")).power_plant
    assert not off.load_reduction.enabled and off.generator_sets == plant.generator_sets


@pytest.mark.parametrize(("old", "new", "message"), [
    ("{name: g1, switchboard: swbd_1, rating: 9100.0}", "{name: g1, switchboard: swbd_9, rating: 9100.0}",
     r"power_plant\.generator_sets\[0\]\.switchboard: 'swbd_9' is not a power source of the vehicle"),
    ("{name: g1, switchboard: swbd_1, rating: 9100.0}", "{name: g1, switchboard: swbd_1, rating: -1.0}",
     r"power_plant\.generator_sets\[0\]\.rating: a number > 0"),
    ("{name: g1, switchboard: swbd_1, rating: 9100.0}", "{name: g1, switchboard: swbd_1, rating: 9100.0, droop: 0}",
     r"power_plant\.generator_sets\[0\]\.droop: a number > 0"),
    ("{name: g1, switchboard: swbd_1, rating: 9100.0}", "{name: g1, switchboard: swbd_1, rating: 9100.0, inerta: 2}",
     r"power_plant\.generator_sets\[0\]\.inerta: unknown key; did you mean inertia\?"),
    ("{name: g1, switchboard: swbd_1, rating: 9100.0}", "{name: g2, switchboard: swbd_1, rating: 9100.0}",
     r"power_plant\.generator_sets: names given twice: g2"),
    ("{name: g1, switchboard: swbd_1, rating: 9100.0}",
     "{name: g1, switchboard: swbd_1, rating: 9100.0, under_frequency: 0.9, over_frequency: 1.0}",
     r"power_plant\.generator_sets\[0\]\.over_frequency: a number > 1"),
    ("{switchboard: swbd_2, power: 2000.0}", "{switchboard: swbd_2, power: lots}",
     r"power_plant\.consumers\[1\]\.power: a finite number"),
    ("generator_sets:\n", "management: {ramp_time: 0}\n  generator_sets:\n",
     r"power_plant\.management\.ramp_time: a number > 0"),
    ("generator_sets:\n", "load_reduction: {frequency_start: 0.9, frequency_zero: 0.95}\n  generator_sets:\n",
     r"power_plant\.load_reduction\.frequency_zero: below frequency_start"),
    ("generator_trip: {generator_set: g5}", "generator_trip: {generator_set: g7}",
     r"events\[2\]\.generator_trip\.generator_set: 'g7' is not one of g1, g2"),
    ("bus_tie: {name: tie_12, closed: false}", "bus_tie: {name: tie_13, closed: false}",
     r"events\[0\]\.bus_tie\.name: 'tie_13' is not a bus tie of the vehicle \(tie_12, tie_23\)"),
    ("{time: 252.0, fault: {actuator: thruster_6, mode: failed}}",
     "{time: 252.0, power: {source: swbd_1, available: 1}}",
     r"events\[3\]\.power: the power_plant gives each source's power"),
])
def test_a_bad_plant_is_refused_naming_its_key(tmp_path, old, new, message):
    with pytest.raises(ScenarioError, match=message):
        variant(tmp_path, old, new)


def test_every_switchboard_needs_a_connected_set_on_its_bus(tmp_path):
    off = ("{name: g5, switchboard: swbd_3, rating: 9100.0}\n    - {name: g6, switchboard: swbd_3, rating: 9100.0}",
           "{name: g5, switchboard: swbd_3, rating: 9100.0, connected: false}\n"
           "    - {name: g6, switchboard: swbd_3, rating: 9100.0, connected: false}")
    assert variant(tmp_path, *off).power_plant is not None           # swbd_3 fed through tie_23
    swbd_1 = ("{name: g1, switchboard: swbd_1, rating: 9100.0}\n    - {name: g2, switchboard: swbd_1, rating: 9100.0}",
              "{name: g1, switchboard: swbd_2, rating: 9100.0}\n    - {name: g2, switchboard: swbd_2, rating: 9100.0}")
    text = RIG.read_text().replace(*off).replace(*swbd_1).replace("../drilling_rig.yaml", "rig_open.yaml")
    text = text.replace("../particulars/", str(ROOT / "config" / "particulars") + "/")
    vehicle = (ROOT / "config" / "drilling_rig.yaml").read_text().replace(
        "tie_23: {sources: [swbd_2, swbd_3], closed: true}", "tie_23: {sources: [swbd_2, swbd_3], closed: false}")
    (tmp_path / "rig_open.yaml").write_text(vehicle)
    (tmp_path / "rig.yaml").write_text(text)
    with pytest.raises(ScenarioError, match=r"power_plant\.generator_sets: no connected set feeds swbd_3, nor"):
        load_scenario(tmp_path / "rig.yaml")


def test_plant_metrics_need_a_plant_and_are_bounded_over_the_run_only(tmp_path):
    with pytest.raises(ScenarioError, match=r"windows\[0\]\.bounds\.frequency_dip: a power plant's metric"):
        variant(tmp_path, "\nbounds: {", "\nwindows:\n  - {name: late, start: 260.0, bounds: {frequency_dip: 0.1}}\n"
                "bounds: {")
    dp = (ROOT / "config" / "scenarios" / "dp_station_keeping.yaml").read_text()
    path = tmp_path / "dp.yaml"
    path.write_text(dp.replace("../", str(ROOT / "config") + "/").replace(
        "bounds: {", "bounds: {generator_sets_tripped: 0, "))
    with pytest.raises(ScenarioError, match=r"bounds\.generator_sets_tripped: a power plant's metric; the scenario "
                                            "has no power_plant"):
        load_scenario(path)
