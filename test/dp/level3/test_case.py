"""The Level 3 case runner: a seeded in-process closed-loop run per (heading, condition, case, seed)."""

import contextlib
import itertools
from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT
from scipy import integrate, signal

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.inputs.site import SiteSea
from allocator_pkg.dp.level3.case import (
    INTACT,
    NO_ONLINE_CONSEQUENCE,
    Case,
    CaseResult,
    CaseSetup,
    Criteria,
    GroupFaultLink,
    case_environment,
    case_scenario,
    excursions,
    run_case,
)
from allocator_pkg.dp.standard import loads as standard_loads
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS
from allocator_pkg.hull.environment_loads import VesselParticulars
from allocator_pkg.simulation.closed_loop import ClosedLoop
from allocator_pkg.simulation.environment import Environment, SlowVariation
from allocator_pkg.simulation.environment_record import build_record
from allocator_pkg.simulation.run_setup import build_plant
from allocator_pkg.simulation.scenario import load_scenario
from allocator_pkg.simulation.spectra import peak_factor
from allocator_pkg.simulation.spreading import normalisation

GROUPS = {"switchboard_a": ("azimuth_stbd", "tunnel_fwd"), "switchboard_b": ("azimuth_port", "tunnel_aft")}


@pytest.fixture(scope="module")
def setup() -> CaseSetup:
    scenario = load_scenario(ROOT / "config/scenarios/dp_station_keeping.yaml")
    return CaseSetup(scenario, WEATHER_CONDITIONS, GROUPS, frozenset(GROUPS),
                     Criteria(1.0, 3.0, settle=5.0, duration=15.0))


def test_environment_comes_from_the_heading(setup):
    scenario = case_scenario(setup, Case(90.0, 6, INTACT, 2))
    spec = scenario.environment
    assert (spec.wind_direction, spec.current_direction, spec.wave_direction) == (90.0, 90.0, 90.0)
    assert (spec.wind_speed, spec.wave_height, spec.wave_period, spec.current_speed) == (13.8, 3.1, 8.5, 0.75)
    assert (spec.wind_spectrum, spec.wave_spectrum) == ("npd", "jonswap")
    base = case_scenario(replace(setup, spectra=False), Case(90.0, 6, INTACT, 2)).environment
    first_order = setup.scenario.environment                  # the base's turbulence intensity
    assert base.gusts.sigma == pytest.approx(13.8 * first_order.gusts.sigma / first_order.wind_speed)
    assert (base.wind_spectrum, base.wave_spectrum) == ("first_order", "none")
    assert scenario.seed == setup.scenario.seed + 2 and scenario.duration == 20.0 and not scenario.events


def test_a_group_fails_every_actuator_after_settling(setup):
    events = case_scenario(setup, Case(0.0, 3, "switchboard_b", 0)).events
    assert [(e.time, e.kind, e.actuator, e.mode) for e in events] == [
        (5.0, "fault", "azimuth_port", "failed"), (5.0, "fault", "tunnel_aft", "failed")]


def test_beam_weather_from_starboard_pushes_the_vessel_to_port(setup):
    vehicle = load_vehicle(setup.scenario.vehicle)
    for heading, side in ((90.0, -1.0), (270.0, 1.0)):
        plant = build_plant(case_scenario(setup, Case(heading, 5, INTACT, 0)), vehicle)
        force = plant.environment_force()                      # body frame: Y to starboard
        assert np.sign(force[1]) == side and abs(force[1]) > 10.0 * abs(force[0])
    ahead = build_plant(case_scenario(setup, Case(0.0, 5, INTACT, 0)), vehicle).environment_force()
    assert ahead[0] < 0.0 and abs(ahead[0]) > 10.0 * abs(ahead[1])


def test_a_case_is_a_pure_function_of_its_inputs(setup):
    case = Case(30.0, 6, "switchboard_a", 0)
    first, second = run_case(case, setup), run_case(case, setup)
    assert first == second
    assert CaseResult.from_json(first.to_json()) == first
    other = run_case(replace(case, seed=1), setup)
    assert other.track != first.track                          # another seed, other gusts


def test_criteria_decide_held(setup):
    result = run_case(Case(90.0, 7, "switchboard_a", 0), setup)     # a 60 s window: all after the failure
    assert result.transient_position == pytest.approx(max(p for p in positions(result)[5:]), abs=0.05)
    assert result.held == (result.steady_position <= 1.0 and result.steady_heading_deg <= 3.0
                           and result.transient_position <= 5.0 and result.transient_heading_deg <= 3.0)
    loose = replace(setup, criteria=Criteria(result.steady_position + 0.01, result.steady_heading_deg + 0.01, 5.0,
                                             15.0, post_failure_position_limit=result.transient_position + 0.01,
                                             post_failure_heading_limit_deg=result.transient_heading_deg + 0.01))
    tight = replace(setup, criteria=Criteria(90.0, 90.0, 5.0, 15.0,
                                             post_failure_position_limit=0.5 * result.transient_position))
    assert run_case(result.case, loose).held and not run_case(result.case, tight).held


def positions(result):
    return [float(np.hypot(*point)) for point in result.track]


WINDOWS = [(INTACT, 4.0, 10.0, 20.0, None), ("g", 4.0, 10.0, 8.0, 20.0), ("g", 4.0, 3.0, 20.0, 8.0),
           ("g", 0.0, 10.0, 20.0, None), ("g", 30.0, 10.0, 8.0, 20.0), ("g", 4.0, 20.0, 20.0, 1.0)]


@pytest.mark.parametrize("group, window, settle, steady, transient", WINDOWS)
def test_the_post_failure_window_splits_a_run_by_the_time_of_the_failure(group, window, settle, steady, transient):
    """A run 8 m off at 4 s to 6 s and 20 m off at 10 s to 12 s, 1 m elsewhere, 30 s long: with a
    group failing at ``settle`` the window [settle, settle + window) takes what falls in it."""
    time = np.arange(0.0, 30.0, 0.5)
    position = np.where((time >= 4.0) & (time < 6.0), 8.0, np.where((time >= 10.0) & (time < 12.0), 20.0, 1.0))
    heading = 0.1 * position
    criteria = Criteria(9.0, 1.0, settle=settle, duration=30.0 - settle, post_failure_window=window,
                        post_failure_position_limit=21.0, post_failure_heading_limit_deg=2.5)
    result = excursions(Case(0.0, 1, group, 0), criteria, time, position, heading, ())
    assert (result.steady_position, result.transient_position) == (steady, transient)
    assert result.max_position == 20.0 and result.mean_position == pytest.approx(np.mean(position))
    assert result.steady_heading_deg == pytest.approx(0.1 * steady)
    assert result.held == (steady <= 9.0 and 0.1 * steady <= 1.0 and (transient is None or transient <= 21.0))


def test_the_group_link_fails_the_group_and_the_simulated_thrusters(setup, tmp_path):
    scenario = case_scenario(setup, Case(60.0, 4, "switchboard_a", 0))
    links = []

    def connect(run, out):
        import contextlib

        @contextlib.contextmanager
        def opened():
            links.append(GroupFaultLink(run, "switchboard_a"))
            yield links[-1]
        return opened()

    trace = ClosedLoop(scenario, tmp_path, connect, log=lambda _: None).run().trace
    assert links[0].allocator.group_faults == ("switchboard_a",)
    thrust, time = np.array(trace.thrust), np.array(trace.time)
    failed = [trace.names.index(name) for name in GROUPS["switchboard_a"]]
    assert np.all(thrust[time > 5.0 + 1e-9][:, failed] == 0.0)
    assert np.any(thrust[time < 5.0][:, failed] != 0.0)


def test_the_online_consequence_analysis_is_off_and_would_change_no_run(setup, tmp_path):
    """A case runs without the node's online consequence analysis; with it on at the vehicle's
    rate (1 Hz) the run is the same, bit for bit, but for the alarm the statuses carry."""
    import contextlib

    off = case_scenario(setup, Case(90.0, 7, "switchboard_a", 0))
    assert NO_ONLINE_CONSEQUENCE == {"consequence.rate": 0.0}
    assert off.parameters["consequence.rate"] == 0.0
    on = replace(off, parameters={k: v for k, v in off.parameters.items() if k != "consequence.rate"})
    traces = []
    for scenario in (off, on):
        def connect(run, out):
            return contextlib.nullcontext(GroupFaultLink(run, "switchboard_a"))
        traces.append(ClosedLoop(scenario, tmp_path / str(len(traces)), connect, log=lambda _: None).run().trace)
    for name in ("time", "position", "attitude", "thrust", "azimuth", "power", "source_power"):
        assert getattr(traces[0], name) == getattr(traces[1], name), name
    assert not any(traces[0].consequence_alarm)
    assert any(traces[1].consequence_alarm)                  # number 7 after a switchboard's loss: the alarm


PLANT = """
power_plant:
  generator_sets:
    - {name: ga1, switchboard: swbd_a, rating: 3500.0}
    - {name: ga2, switchboard: swbd_a, rating: 3500.0}
    - {name: gb1, switchboard: swbd_b, rating: 4500.0}
    - {name: gb2, switchboard: swbd_b, rating: 4500.0}
  consumers:
    - {switchboard: swbd_a, power: 500.0}
    - {switchboard: swbd_b, power: 500.0}
events:
  - {time: 1.0, generator_trip: {generator_set: gb1}}
"""


def test_with_the_base_scenarios_power_plant_a_group_loses_its_switchboards_generator_sets(setup, tmp_path):
    """A base scenario with a power plant: the cases run it, its own events left out, and a named
    group's loss takes the generator sets of the group's switchboards with its thrusters."""
    text = (ROOT / "config/scenarios/dp_station_keeping.yaml").read_text().replace("../", f"{ROOT / 'config'}/")
    (tmp_path / "plant.yaml").write_text(text + PLANT)
    base = load_scenario(tmp_path / "plant.yaml")
    assert [e.kind for e in base.events] == ["generator_trip"]
    sources = {"switchboard_a": ("swbd_a",), "switchboard_b": ("swbd_b",)}
    with_plant = replace(setup, scenario=base, group_sources=sources)
    assert not case_scenario(with_plant, Case(0.0, 3, INTACT, 0)).events
    scenario = case_scenario(with_plant, Case(0.0, 3, "switchboard_a", 0))
    assert [(e.time, e.kind, e.actuator or e.name) for e in scenario.events] == [
        (5.0, "fault", "azimuth_stbd"), (5.0, "fault", "tunnel_fwd"), (5.0, "generator_trip", "ga1"),
        (5.0, "generator_trip", "ga2")]
    assert [e.kind for e in case_scenario(setup, Case(0.0, 3, "switchboard_a", 0)).events] == ["fault", "fault"]
    loop = ClosedLoop(scenario, tmp_path / "run", lambda run, out: contextlib.nullcontext(
        GroupFaultLink(run, "switchboard_a")), log=lambda _: None)
    trace = loop.run().trace
    assert [(round(t, 6), name) for t, name, _ in loop.electric.record.trips] == [(5.0, "ga1"), (5.0, "ga2")]
    generation = np.array(loop.electric.record.generation)
    time = np.array(loop.electric.record.time)
    assert np.all(generation[time > 5.0 + 1e-9, 0] == 0.0) and np.all(generation[time < 5.0, 0] > 0.0)
    assert np.all(generation[:, 1] > 0.0)
    assert np.all(np.array(trace.source_available)[np.array(trace.time) > 6.0, 0] == 0.0)


@pytest.mark.parametrize("group", [INTACT, "switchboard_b"])
def test_in_steady_weather_a_held_case_settles_on_its_set_point(setup, group):
    """Beam weather at number 6 (426 kN of sway: 214 kN wave drift, 68 kN wind, the rest current)
    without the slow variations and gusts, the controller on the true state (no DP system): the
    controller's integral starts at the mean load
    (Plant.environment_force), which is then the load, so the intact vessel stays on its set-point,
    and after the loss of switchboard B (at 5 s) it comes back to it. A seeded case's excursions
    both ways are the variations' (the wave drift's sigma, 30 % of 214 kN, against Kp 51 kN/m)."""
    none = SlowVariation()
    environment = replace(setup.scenario.environment, current_speed_variation=none,
                          current_direction_variation=none, gusts=none, drift_variation=none)
    steady = replace(setup, scenario=replace(setup.scenario, environment=environment),
                     criteria=Criteria(0.1, 0.5, settle=5.0, duration=175.0), spectra=False, dp_system=False)
    result = run_case(Case(90.0, 6, group, 0), steady)
    north, east = result.track[-1]
    assert result.held and np.hypot(north, east) < 0.01
    if group == INTACT:
        assert result.max_position < 1e-4
    varied = run_case(Case(90.0, 6, group, 0), replace(setup, criteria=steady.criteria, spectra=False,
                                                      dp_system=False))
    assert varied.max_position > 0.2


@pytest.fixture(scope="module")
def standard_setup(setup) -> CaseSetup:
    """The set-up with the standard's hull (config/particulars/dp_vessel.yaml), an hour per case."""
    particulars = load_particulars(ROOT / "config/particulars/dp_vessel.yaml")
    return replace(setup, hull=particulars.hull, frame=particulars.frame,
                   criteria=Criteria(5.0, 3.0, settle=60.0, duration=3600.0))


def record_drift(scenario) -> np.ndarray:
    """The drift load [X, Y, N] at heading 0 at every sample of the environment's record."""
    environment = build_plant(scenario, load_vehicle(scenario.vehicle)).environment
    loads = []
    for _ in range(environment.record.samples):
        environment.step(environment.record.step)
        loads.append(environment.drift_load(0.0))
    return np.array(loads)


@pytest.mark.parametrize("number", [3, 6, 9])
@pytest.mark.parametrize("heading", [0.0, 45.0, 90.0, 150.0, 225.0])
def test_the_mean_drift_is_the_standards_and_its_deviation_newmans(standard_setup, heading, number):
    """[3.7] in the body frame (dp/standard/loads.py) for the condition, within 1 % over the record;
    the slowly varying drift's deviation equal to its mean (Newman, one drift coefficient) within 10 %."""
    scenario = case_scenario(standard_setup, Case(heading, number, INTACT, 0))
    condition = WEATHER_CONDITIONS[number]
    expected = standard_setup.frame.load(standard_loads.wave_drift_load(standard_setup.hull, condition.hs,
                                                                        condition.tp, np.radians(heading)))
    drift = record_drift(scenario)
    assert np.mean(drift, axis=0) == pytest.approx(expected, rel=0.01, abs=1e-6 * np.abs(expected).max())
    assert np.std(drift, axis=0) == pytest.approx(np.abs(expected), rel=0.10, abs=1e-6 * np.abs(expected).max())
    wind = standard_setup.frame.load(standard_loads.wind_load(standard_setup.hull, condition.wind,
                                                              np.radians(heading)))
    assert np.array(scenario.environment.mean_wind_load) == pytest.approx(wind)


SEA = SiteSea(peak_factors=(0.0,) + (6.0,) * 11, spreading=4.0, wave_direction=30.0, current_direction=-45.0)
"""A site's sea: gamma 6, cos^4 spreading, waves from 30 deg and current from -45 deg off the wind."""


@pytest.mark.parametrize("number", [3, 6, 9])
@pytest.mark.parametrize("heading", [0.0, 45.0, 90.0, 150.0, 225.0, 300.0])
@pytest.mark.parametrize("sea", [replace(SEA, spreading=0.0), SEA])
def test_site_directions_reach_the_mean_loads(standard_setup, heading, number, sea):
    """The mean wind load [3.5] at the wind's heading, the mean drift [3.7] at the waves' (averaged
    over the cos^4 spreading by scipy's quadrature), the current from its own direction and the
    site's gamma in the spectrum's spec, all against dp/standard/loads.py."""
    setup, condition = replace(standard_setup, sea=sea), WEATHER_CONDITIONS[number]
    spec = case_environment(setup, Case(heading, number, INTACT, 0))
    hull, frame = setup.hull, setup.frame
    wind = frame.load(standard_loads.wind_load(hull, condition.wind, np.radians(heading)))
    assert np.array(spec.mean_wind_load) == pytest.approx(wind)
    waves = np.radians(heading + 30.0)

    def drift(theta: float) -> np.ndarray:
        return frame.load(standard_loads.wave_drift_load(hull, condition.hs, condition.tp, waves + theta))

    if sea.spreading:
        weight = normalisation(4.0)
        expected = [integrate.quad(lambda t, k=k: drift(t)[k] * weight * np.cos(t) ** 4, -np.pi / 2, np.pi / 2,
                                   limit=200)[0] for k in range(3)]
    else:
        expected = drift(0.0)
    scale = np.abs(expected).max()
    assert np.array(spec.mean_drift_load) == pytest.approx(expected, rel=5e-3, abs=1e-3 * scale)
    assert (spec.wind_direction, spec.wave_direction, spec.current_direction) == (heading, heading + 30.0,
                                                                                   heading - 45.0)
    assert (spec.peak_factor, spec.wave_spreading) == (6.0, sea.spreading)
    current = Environment(spec, 0).mean_current()           # flowing away from where it comes from
    assert np.degrees(np.arctan2(-current[1], -current[0])) % 360.0 == pytest.approx((heading - 45.0) % 360.0)
    push = frame.load(standard_loads.current_load(hull, condition.current, np.radians(heading - 45.0)))
    assert np.dot(push[:2], current[:2]) > 0.0                # the standard's current load downstream, as the water


def test_a_collinear_site_is_level_1s_environment(standard_setup):
    plain = case_environment(standard_setup, Case(60.0, 5, INTACT, 0))
    assert case_environment(replace(standard_setup, sea=SiteSea()), Case(60.0, 5, INTACT, 0)) == plain
    assert (plain.wave_direction, plain.current_direction, plain.peak_factor, plain.wave_spreading) == \
        (60.0, 60.0, 0.0, 0.0)


@pytest.mark.parametrize("number", [4, 6, 8])
def test_the_sites_peak_factor_reaches_the_sea(standard_setup, number):
    """The wave motion of a point hull in head seas is the surface's horizontal displacement, whose
    spectrum is the elevation's: Welch's estimate of it per band of the JONSWAP spectrum with the
    site's gamma 6 (spectra.py, against scipy's quadrature of [3.5.5] written out here) within 10 %
    of the band's energy; DNV-RP-C205's own gamma for the condition is further off."""
    setup = replace(standard_setup, sea=replace(SEA, spreading=0.0, wave_direction=None, current_direction=None))
    spec = case_environment(setup, Case(0.0, number, INTACT, 0))
    hull = VesselParticulars(lpp=0.01, beam=0.01, draught=0.01, wind_area_frontal=1.0, wind_area_lateral=1.0,
                             wind_centre_x=0.0, underwater_centre_x=0.0)
    record = build_record(spec, 11, hull, 4 * 3600.0, 0.0)
    north = record.data[:-1, record.index["north"]]
    f, psd = signal.welch(north, fs=1.0 / record.step, nperseg=8192)
    hs, tp = WEATHER_CONDITIONS[number].hs, WEATHER_CONDITIONS[number].tp
    wp = 2.0 * np.pi / tp

    def jonswap(omega: float, gamma: float) -> float:
        width = 0.07 if omega <= wp else 0.09
        pm = 5.0 / 16.0 * hs ** 2 * wp ** 4 * omega ** -5 * np.exp(-1.25 * (omega / wp) ** -4)
        return (1.0 - 0.287 * np.log(gamma)) * pm * gamma ** np.exp(-0.5 * ((omega - wp) / (width * wp)) ** 2)

    edges = np.array([0.7, 0.85, 0.95, 1.05, 1.2, 1.5]) * wp
    dnv_gamma, off = peak_factor(hs, tp), 0.0
    for low, high in itertools.pairwise(edges):
        band = (2.0 * np.pi * f >= low) & (2.0 * np.pi * f < high)
        measured = np.sum(psd[band]) * (f[1] - f[0])
        expected = integrate.quad(jonswap, low, high, args=(6.0,), points=[wp])[0]
        assert measured == pytest.approx(expected, rel=0.10)
        off = max(off, abs(integrate.quad(jonswap, low, high, args=(dnv_gamma,), points=[wp])[0] / expected - 1.0))
    assert off > 0.2


@pytest.mark.parametrize("heading", [0.0, 90.0, 225.0])
def test_a_spread_seas_slowly_varying_drift_keeps_newmans_statistics(standard_setup, heading):
    """With one drift coefficient the spread sea's drift has the spread mean and, the point spectrum
    being the same, a standard deviation equal to it (within 10 %) in every DOF."""
    scenario = case_scenario(replace(standard_setup, sea=SEA), Case(heading, 6, INTACT, 0))
    drift, mean = record_drift(scenario), np.array(scenario.environment.mean_drift_load)
    scale = 1e-6 * np.abs(mean).max()
    assert np.mean(drift, axis=0) == pytest.approx(mean, rel=0.01, abs=scale)
    assert np.std(drift, axis=0) == pytest.approx(np.abs(mean), rel=0.10, abs=scale)
