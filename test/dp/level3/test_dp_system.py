"""allocator_pkg.dp.level3.dp_system: every Level 3 case runs the vessel's DP system (the
observer tuned to the condition's peak period, noise, wind feed-forward), a failure is a trip,
the thrusters carry the static analysis' losses; the report's text states the tuning."""

import math
from dataclasses import replace

import pytest
from conftest import ROOT

from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.level3.case import INTACT, Case, CaseSetup, Criteria, case_scenario
from allocator_pkg.dp.level3.dp_system import NOISE, describe_dp_system
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS
from allocator_pkg.simulation.measurement import MeasurementNoise
from allocator_pkg.simulation.scenario import load_scenario

GROUPS = {"switchboard_a": ("azimuth_stbd", "tunnel_fwd"), "switchboard_b": ("azimuth_port", "tunnel_aft")}
PARTICULARS = load_particulars(ROOT / "config" / "particulars" / "dp_vessel.yaml")


@pytest.fixture(scope="module")
def setup() -> CaseSetup:
    scenario = load_scenario(ROOT / "config/scenarios/dp_station_keeping.yaml")
    return CaseSetup(scenario, WEATHER_CONDITIONS, GROUPS, frozenset(GROUPS), Criteria(5.0, 3.0, settle=20.0,
                                                                                      duration=20.0),
                     PARTICULARS.hull, PARTICULARS.frame, particulars=PARTICULARS)


@pytest.mark.parametrize("number", [1, 4, 7, 11])
@pytest.mark.parametrize("group", [INTACT, "switchboard_a"])
def test_every_case_runs_the_dp_system_with_a_trip_and_the_losses(setup, number, group):
    scenario = case_scenario(setup, Case(45.0, number, group, 0))
    control = scenario.control
    assert control.observer.wave_period == WEATHER_CONDITIONS[number].tp
    assert control.noise == NOISE and control.wind_feedforward and scenario.fault_trip
    assert scenario.parameters["flushing_zones"] == "dnv"
    dead = [case.dead for case in scenario.thrust_losses.cases]
    assert dead == ([frozenset()] if group == INTACT else [frozenset(), frozenset(GROUPS[group])])
    own = replace(setup, scenario=replace(setup.scenario, control=replace(
        setup.scenario.control, noise=MeasurementNoise(0.3, math.radians(0.2)))))
    assert case_scenario(own, Case(45.0, number, group, 0)).control.noise.position_sigma == 0.3
    plain = case_scenario(replace(setup, dp_system=False), Case(45.0, number, group, 0))
    assert plain.control.observer is None and not plain.fault_trip and plain.thrust_losses is None


def test_the_report_text_states_the_tuning(setup):
    text = describe_dp_system(setup.scenario, 8.5)
    for part in ("Fossen and Strand", "omega_o = 0.739 rad/s", "lambda 0.1", "zeta_n 1", "omega_c = 1.5 omega_o",
                 "bias time constant 1000 s", "K4 = diag(5, 5, 0.4)", "K3 = 0.02 K4", "sigma 0.1 m, 0.05 deg",
                 "wind feed-forward through a 10 s low-pass filter", "trip", "[3.9.4]", "[3.11.4]", "[3.11.3]"):
        assert part in text, part
