"""The figures of allocator-sim (allocator_pkg.simulation.report.figures, sim_timeline, sim_footprint, sim_power,
sim_style), read from their artists on made-up runs: panels and units, one line per actuator in
colours that tell apart, the thrust limits at the supply voltage of each sample, the events
marked, the nominal run overlaid; the footprint's heading, bound, start and end; the nominal
scenario and the comparison table."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from conftest import ROOT
from matplotlib.colors import to_rgba
from matplotlib.patches import Circle
from matplotlib.quiver import Quiver

from allocator_pkg.capability.report.plotting import pyplot
from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.effectiveness.faults import thrust_limits
from allocator_pkg.simulation.report import figures as sim_plots
from allocator_pkg.simulation.report.footprint import arrow_interval, footprint_figure
from allocator_pkg.simulation.report.power_figure import power_bounds
from allocator_pkg.simulation.report.style import (
    FAULT_COLOUR,
    LIMIT_COLOUR,
    NOMINAL_LABEL,
    OVERLAID,
    actuator_style,
    event_label,
    overlaid,
    scale,
)
from allocator_pkg.simulation.report.timeline import POWER_LABEL, thrust_limits_over_time, timeline_figure
from allocator_pkg.simulation.run_report import run_report
from allocator_pkg.simulation.run_setup import RunResult
from allocator_pkg.simulation.scenario import Event, load_scenario
from allocator_pkg.simulation.trace import Trace

SCENARIOS = ROOT / "config" / "scenarios"


def scenario(name: str, scale_: float = 0.1):
    return load_scenario(SCENARIOS / f"{name}.yaml").scaled(scale_)


def made_up_run(case, amplitude: float = 1.0, voltage=None) -> RunResult:
    """A run of ``case`` as the loop would record it, with smooth made-up motion and thrust;
    ``voltage(t)`` the supply voltage (NaN without)."""
    vehicle = load_vehicle(case.vehicle)
    period = 1.0 / vehicle.rate_hz
    trace = Trace(names=list(vehicle.names), period=period, horizontal=case.horizontal)
    faults = [(e.time, case.duration) for e in case.events if e.kind == "fault"][:1]
    high = thrust_limits(vehicle, None)[1]
    coefficients = np.array([a.power_coefficient for a in vehicle.actuators])
    for k in range(round(case.duration / period)):
        t = k * period
        wave = math.sin(0.3 * t)
        thrust = 0.3 * high * np.array([wave if i % 2 else math.cos(0.2 * t) for i in range(len(high))])
        trace.add(t, [amplitude * wave, 0.5 * amplitude * math.cos(0.3 * t), 5.0 + 0.01 * wave],
                  [0.01 * wave, -0.02 * wave, 0.005 * wave], list(case.setpoint_position), case.setpoint_heading,
                  thrust, [0.5 * i + 0.1 * wave if a.rotatable else 0.0 for i, a in enumerate(vehicle.actuators)],
                  k % 7 == 0, float(coefficients @ np.abs(thrust) ** 1.5), any(start <= t for start, _ in faults),
                  math.nan if voltage is None else voltage(t))
    report = run_report(case, trace, vehicle, realtime_factor=1.0)
    return RunResult(report["metrics"], trace, vehicle, faults, report)


@pytest.fixture(autouse=True)
def close_figures():
    yield
    pyplot().close("all")


def legend_texts(axes) -> list[str]:
    legend = axes.get_legend()
    return [] if legend is None else [text.get_text() for text in legend.get_texts()]


def labelled(axes) -> dict[str, object]:
    return {line.get_label(): line for line in axes.get_lines() if not line.get_label().startswith("_")}


def event_lines(axes) -> list[float]:
    """The times of the dotted vertical lines (events) of ``axes``."""
    return sorted(line.get_xdata()[0] for line in axes.get_lines()
                  if line.get_linestyle() == ":" and line.get_xdata()[0] == line.get_xdata()[1])


def test_the_dp_timeline_has_metres_and_degrees_apart_and_every_thruster_against_its_limits():
    case = scenario("dp_stuck_azimuth")
    figure = timeline_figure(made_up_run(case), case)
    _, heading, thrust, azimuth, power = figure.axes
    assert [a.get_ylabel() for a in figure.axes] == ["position error [m]", "heading error [deg]", "thrust [kN]",
                                                     "azimuth [deg]", "power [kW]"]
    assert figure.axes[-1].get_xlabel() == "time [s]"
    lines = labelled(thrust)
    names = ["azimuth_stbd", "azimuth_port", "tunnel_fwd", "tunnel_aft"]
    assert [name for name in lines if name in names] == names
    # The made-up thrusts reach 0.3 of each limit, azimuth_port's 196.5 kN: a limit is in view up to
    # twice that (the tunnels' 300 kN), farther ones are named beyond it.
    assert legend_texts(thrust) == [*names, "limits of azimuth_stbd, +420 kN beyond the view",
                                    "limits of azimuth_port, +655 kN beyond the view",
                                    "limits of tunnel_fwd, tunnel_aft"]
    assert lines["limits of azimuth_port, +655 kN beyond the view"].get_ydata() == pytest.approx(655.0)   # kN
    tunnels = [line for line in thrust.get_lines() if line.get_color() == LIMIT_COLOUR]
    assert sorted(line.get_ydata()[0] for line in tunnels) == [-300.0, 300.0]
    low, high = thrust.get_ylim()
    assert 300.0 < high < 0.5 * (300.0 + 420.0) and -0.5 * (300.0 + 420.0) < low < -300.0
    assert list(labelled(azimuth)) == ["azimuth_stbd", "azimuth_port"]
    assert legend_texts(power) == [POWER_LABEL, "saturated samples"]
    assert "(1.44)" in POWER_LABEL and "1.5" in POWER_LABEL
    assert list(labelled(heading)) == ["heading error"]


def test_events_are_lines_on_every_panel_and_labels_above_the_first():
    case = scenario("dp_stuck_azimuth")
    figure = timeline_figure(made_up_run(case), case)
    times = sorted(e.time for e in case.events)
    assert all(event_lines(a) == pytest.approx(times) for a in figure.axes)
    labels = [text.get_text() for text in figure.axes[0].texts]
    assert labels == ["azimuth_stbd STUCK", "azimuth_port.thrust_rate_max = 50000.0"]
    assert all(not a.texts for a in figure.axes[1:])
    assert "a fault in force" in legend_texts(figure.axes[0])


def test_the_rov_timeline_has_roll_and_pitch_and_limits_at_the_voltage_of_each_sample():
    case = scenario("rov_battery_sag")
    run = made_up_run(case, voltage=lambda t: 16.0 - 4.0 * min(1.0, t / case.duration))
    figure = timeline_figure(run, case)
    assert [a.get_ylabel() for a in figure.axes] == ["position error [m]", "heading error [deg]", "roll, pitch [deg]",
                                                     "thrust [N]", "voltage [V]", "power [W]"]
    assert list(labelled(figure.axes[2])) == ["roll", "pitch"]
    assert "depth error (down positive)" in labelled(figure.axes[0])
    thrust = figure.axes[3]
    limits = next(line for label, line in labelled(thrust).items()
                  if label.startswith("limits of every actuator at the supply voltage"))
    voltage = np.array(run.trace.voltage)
    for k in (0, len(voltage) // 2, len(voltage) - 1):
        assert limits.get_ydata()[k] == pytest.approx(thrust_limits(run.vehicle, voltage[k])[1][0])
    assert limits.get_ydata()[-1] < limits.get_ydata()[0]
    assert [line.get_label() for line in thrust.get_lines()].count("_") == 1      # the lower limit, unlabelled


def test_a_constant_voltage_is_named_in_the_limits_and_gets_no_panel():
    case = scenario("rov_thruster_failure")
    figure = timeline_figure(made_up_run(case, voltage=lambda t: 16.0), case)
    assert "voltage [V]" not in [a.get_ylabel() for a in figure.axes]
    assert any(text.startswith("limits of every actuator at 16 V") for text in legend_texts(figure.axes[3]))


def test_eight_thrusters_get_eight_colours_none_of_them_the_faults_or_the_limits():
    case = scenario("rov_thruster_failure")
    thrust = timeline_figure(made_up_run(case), case).axes[3]
    colours = [to_rgba(line.get_color()) for line in thrust.get_lines()[:8]]
    assert len(set(colours)) == 8
    assert to_rgba(FAULT_COLOUR) not in colours and to_rgba(LIMIT_COLOUR) not in colours
    styles = {(actuator_style(i)["color"], str(actuator_style(i)["linestyle"])) for i in range(24)}
    assert len(styles) == 24                                   # beyond eight: the colours with other styles


def test_a_trace_along_an_earlier_one_is_drawn_dashed():
    values = np.column_stack([np.linspace(0, 1, 50), np.linspace(0, 1, 50) + 1e-4, -np.linspace(0, 1, 50)])
    assert overlaid(values) == [False, True, False]
    case = scenario("dp_stuck_azimuth")
    run = made_up_run(case)
    for row in run.trace.thrust:
        row[3] = row[2]                                        # the tunnels alike
    thrust = timeline_figure(run, case).axes[2]
    assert thrust.get_lines()[3].get_label() == "tunnel_aft (dashed: along another)"
    assert thrust.get_lines()[3].get_linestyle() != thrust.get_lines()[2].get_linestyle()
    assert actuator_style(3)["linestyle"] != OVERLAID


def test_the_nominal_run_is_drawn_under_the_errors_and_the_power():
    case = scenario("dp_azimuth_failure")
    figure = timeline_figure(made_up_run(case), case, made_up_run(case, amplitude=0.5))
    for axes in (figure.axes[0], figure.axes[1], figure.axes[-1]):
        assert NOMINAL_LABEL in labelled(axes)
    assert NOMINAL_LABEL not in legend_texts(figure.axes[2])
    assert all(NOMINAL_LABEL not in labelled(a) for a in timeline_figure(made_up_run(case), case).axes)


def test_the_footprint_has_heading_arrows_the_bound_start_end_and_the_nominal_track():
    case = scenario("dp_azimuth_failure", 1.0)
    run = made_up_run(case, amplitude=2.0)
    figure = footprint_figure(run, case, made_up_run(case, amplitude=1.0))
    axes = figure.axes[0]
    assert (axes.get_xlabel(), axes.get_ylabel()) == ("east of the set-point [m]", "north of the set-point [m]")
    circles = [patch for patch in axes.patches if isinstance(patch, Circle)]
    assert [c.get_radius() for c in circles] == [case.bounds["position_error_max"]]
    assert axes.get_xlim()[1] >= case.bounds["position_error_max"]
    arrows = [c for c in axes.collections if isinstance(c, Quiver)]
    interval = arrow_interval(case.duration)
    assert [arrow.get_offsets().shape[0] for arrow in arrows] == [math.ceil(case.duration / interval)]
    lines = labelled(axes)
    offset = np.array(run.trace.position) - np.array(run.trace.setpoint)
    assert (lines["start"].get_xdata()[0], lines["start"].get_ydata()[0]) == (offset[0, 1], offset[0, 0])
    assert (lines["end"].get_xdata()[0], lines["end"].get_ydata()[0]) == (offset[-1, 1], offset[-1, 0])
    assert {"track", "samples under a fault", NOMINAL_LABEL, "set-point"} <= set(lines)
    texts = [text.get_text() for text in figure.legends[0].get_texts()]
    assert f"heading, every {interval:g} s" in texts and "bound 4 m" in texts
    assert "footprint" in figure.get_suptitle()


def test_a_bound_far_beyond_the_track_is_named_but_out_of_view():
    case = scenario("dp_azimuth_failure", 1.0)
    figure = footprint_figure(made_up_run(case, amplitude=0.2), case)
    assert figure.axes[0].get_xlim()[1] < case.bounds["position_error_max"]
    assert "bound 4 m (beyond the view)" in [text.get_text() for text in figure.legends[0].get_texts()]


@pytest.mark.parametrize(("duration", "interval"), [(300.0, 50.0), (30.0, 5.0), (100.0, 10.0), (15.0, 2.0)])
def test_arrows_come_at_one_two_or_five_times_a_power_of_ten(duration, interval):
    assert arrow_interval(duration) == interval


def test_the_nominal_scenario_leaves_out_what_goes_wrong_only():
    case = scenario("dp_stuck_azimuth")
    quiet = sim_plots.nominal(case)
    assert quiet.events == () and (quiet.seed, quiet.duration, quiet.method) == (case.seed, case.duration, case.method)
    assert sim_plots.nominal(scenario("dp_station_keeping")) is None
    other = Event(5.0, "setpoint")
    assert sim_plots.nominal(replace(case, events=(*case.events, other))).events == (other,)
    ran = []
    result = sim_plots.nominal_run(case, Path("out"), lambda s, o: ran.append((s, o)) or "result")
    assert result == "result" and ran == [(quiet, Path("out"))]
    assert sim_plots.nominal_run(scenario("dp_station_keeping"), Path("out"), lambda s, o: 1 / 0) is None


def test_event_labels():
    assert event_label(Event(1.0, "fault", actuator="a", mode="failed")) == "a FAILED"
    assert event_label(Event(1.0, "fault", actuator="a", mode="degraded", value=0.5)) == "a DEGRADED to 0.5"
    assert event_label(Event(1.0, "fault", actuator="a", mode="stuck", value=None)) == "a STUCK"
    assert event_label(Event(1.0, "fault", actuator="a", mode="stuck", value=math.pi / 2)) == "a STUCK at 90 deg"
    assert event_label(Event(1.0, "clear_faults")) == "faults cleared"
    assert event_label(Event(1.0, "battery_ramp", value=12.0, duration=60.0)) == "battery to 12 V in 60 s"
    assert event_label(Event(1.0, "parameter", name="actuators.x.gain", value=2)) == "x.gain = 2"
    assert event_label(Event(1.0, "setpoint_change")) == "setpoint change"


def test_units_scale_to_the_data():
    assert scale(np.array([0.0, 650e3]), "N") == (1e3, "kN")
    assert scale(np.array([-2e7]), "W") == (1e6, "MW")
    assert scale(np.array([51.5]), "N") == (1.0, "N")
    assert scale(np.array([]), "N") == (1.0, "N")


def test_limits_over_time_follow_the_voltage_and_the_nominal_one_without():
    vehicle = load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml")
    low, high = thrust_limits_over_time(vehicle, np.array([16.0, math.nan, 12.0]))
    assert high[:, 0] == pytest.approx([thrust_limits(vehicle, 16.0)[1][0], thrust_limits(vehicle, None)[1][0],
                                        thrust_limits(vehicle, 12.0)[1][0]])
    assert low.shape == high.shape == (3, 8)


def test_the_comparison_table_and_figure_show_the_nominal_runs():
    case = scenario("dp_azimuth_failure")
    results = {"qp": made_up_run(case), "lp": made_up_run(case, amplitude=1.5)}
    nominals = {"qp": made_up_run(case, amplitude=0.5)}
    table = sim_plots.compare_table(case, {m: r.metrics for m, r in results.items()},
                                    {m: r.metrics for m, r in nominals.items()})
    first, second = table.split("nominal runs):")
    assert "| metric | qp | lp |" in first and "| metric | qp |" in second and "| metric | qp | lp |" not in second
    assert "depth error" not in table and "alarm" not in table
    trip = scenario("dp_switchboard_trip", 1.0)
    power = sim_plots.compare_table(trip, {"qp": made_up_run(trip).metrics})
    assert "| time over available power [s] | 0.0 |" in power and "| consequence alarm at [s] | inf |" in power
    figure = sim_plots.compare_figure(case, results, nominals)
    timeline = figure.axes[0]
    assert legend_texts(timeline) == ["qp", "lp", f"dashed: {NOMINAL_LABEL}", "a fault in force"]
    dashed = labelled(timeline)[f"dashed: {NOMINAL_LABEL}"]
    assert dashed.get_linestyle() == "--" and dashed.get_color() == labelled(timeline)["qp"].get_color()
    assert event_lines(timeline) == pytest.approx(sorted(e.time for e in case.events))
    assert "bound 4 m" in legend_texts(figure.axes[1])


def test_methods_on_one_line_get_one_legend_entry_and_the_bounds_show_what_broke():
    """Six methods, five of them on one line, each with its nominal run: two lines and one
    dashed entry, not twelve; under them every bound of the verdict, the broken one red."""
    case = scenario("dp_azimuth_failure", 1.0)
    methods = ["qp", "lp", "pseudoinverse", "nonlinear", "dynamic", "svd_filter"]
    results = {m: made_up_run(case, amplitude=6.0 if m == "svd_filter" else 1.0) for m in methods}
    nominals = {m: made_up_run(case, amplitude=0.5) for m in methods}
    figure = sim_plots.compare_figure(case, results, nominals)
    timeline, _, checks = figure.axes
    assert legend_texts(timeline) == ["qp, lp, pseudoinverse, nonlinear, dynamic (one line)", "svd_filter",
                                      f"dashed: {NOMINAL_LABEL}", "a fault in force"]
    assert len(timeline.get_lines()) - len(event_lines(timeline)) == 3
    found = sim_plots.report_checks(case, results["svd_filter"].report)
    broken = [c for c in found if not c.passed]
    assert [c.metric for c in broken] == ["position_error_max"]            # about 6 m made up, bound 4 m
    labels = [label.get_text() for label in checks.get_xticklabels()]
    assert len(labels) == len(found) and labels[[c.metric for c in found].index("position_error_max")] == \
        f"position_error_max\n<= {case.bounds['position_error_max']:g} m"
    bars = [patch for patch in checks.patches if patch.get_width() > 0.0]
    assert len(bars) == len(methods) * len(found)
    red = [bar for bar in bars if bar.get_linewidth() > 0.0]
    assert len(red) == 1 and to_rgba(red[0].get_edgecolor()) == to_rgba(FAULT_COLOUR)
    check = broken[0]
    assert red[0].get_height() == pytest.approx(min(check.value / check.bound, sim_plots.SHARE_CAP))
    assert [text.get_text() for text in checks.texts] == [f"{check.value:.3g}"]


def test_a_vehicle_with_power_sources_gets_their_power_against_what_is_available_and_the_alarm():
    case = scenario("dp_switchboard_trip", 1.0)
    plain = made_up_run(case)
    trace = replace(plain.trace, sources=["swbd_a", "swbd_b"])
    for t in trace.time:
        tripped = t >= 100.0
        trace.add_power([300.0 + t, 0.0 if tripped else 200.0], [600.0 if t >= 160.0 else 5600.0,
                                                                 0.0 if tripped else 7800.0], tripped)
    figure = timeline_figure(replace(plain, trace=trace), case)
    sources = figure.axes[-1]
    assert sources.get_ylabel() == "power per source [kW]"
    # Drawn 300-460 kW: the view keeps to it, and 5600 and 7800 kW available are named above it.
    assert legend_texts(sources) == ["swbd_a drawn", "swbd_a available (up to 5600 kW, above the view)",
                                     "swbd_b drawn", "swbd_b available (up to 7800 kW, above the view)",
                                     "consequence alarm"]
    assert 460.0 < sources.get_ylim()[1] < 920.0 and sources.get_ylim()[0] == 0.0
    lines = labelled(sources)
    available = "swbd_a available (up to 5600 kW, above the view)"
    assert lines[available].get_color() == lines["swbd_a drawn"].get_color()
    assert lines[available].get_linestyle() == "--"
    assert lines["swbd_b available (up to 7800 kW, above the view)"].get_ydata()[-1] == 0.0
    assert lines["swbd_a drawn"].get_ydata()[0] == 300.0
    assert event_lines(sources) == [100.0, 160.0]
    assert [event_label(e) for e in case.events] == ["switchboard_b FAILED", "swbd_a 450 kW"]
    assert event_label(Event(10.0, "weather_ramp", value=1.5, duration=120.0)) == "weather x1.5 in 120 s"


def test_the_nominal_run_leaves_out_group_faults_and_power_but_keeps_the_weather():
    assert sim_plots.nominal(scenario("dp_switchboard_trip")).events == ()
    kept = sim_plots.nominal(scenario("dp_consequence_alarm")).events
    assert [e.kind for e in kept] == ["weather_ramp"]


def power_limited_run(case) -> RunResult:
    """A made-up run of ``case`` whose power plant gives 450 kW on each switchboard all along."""
    plain = made_up_run(case)
    trace = replace(plain.trace, sources=["swbd_a", "swbd_b"])
    for _ in trace.time:
        trace.add_power([440.0, 445.0], [450.0, 450.0], False)
    return replace(plain, trace=trace)


def test_the_thrust_panel_draws_each_thrusters_bound_from_the_available_power():
    """450 kW per switchboard: swbd_a feeds azimuth_stbd (P = 0.0074 W/N^1.5, 420 kN) and tunnel_fwd
    (0.0113, 300 kN), swbd_b azimuth_port (0.0074, 655 kN) and tunnel_aft (0.0113, 300 kN). With qp the
    power rows hold the power and no thrust range is narrowed: no bound. For a method without rows each
    source's power is shared in proportion to its consumers' largest draws D_j = sum P_i F_i^1.5, so
    that each thruster's bound is F_i (A_j / D_j)^(2/3)."""
    case = scenario("dp_power_limited", 1.0)
    run = power_limited_run(case)
    assert power_bounds(run, case) is None
    figure = timeline_figure(run, replace(case, method="pseudoinverse"))
    thrust = figure.axes[2]
    bounds: dict[str, list] = {}
    for line in thrust.get_lines():
        if line.get_linestyle() == "-.":
            bounds.setdefault(line.get_color(), []).append(line.get_ydata())
    feeds = {"swbd_a": [(0.0074, 420e3, 0), (0.0113, 300e3, 2)], "swbd_b": [(0.0074, 655e3, 1), (0.0113, 300e3, 3)]}
    expected = {}
    for consumers in feeds.values():
        demand = sum(p * f ** 1.5 for p, f, _ in consumers)
        for _, f, i in consumers:
            expected[actuator_style(i)["color"]] = f * (450e3 / demand) ** (2.0 / 3.0) / 1e3      # kN
    assert expected[actuator_style(0)["color"]] == pytest.approx(100.04, abs=0.01)
    assert set(bounds) == set(expected)
    for colour, drawn in bounds.items():                        # +bound, and -bound where the thrust goes negative
        assert [np.abs(values) for values in drawn] == [pytest.approx(expected[colour])] * len(drawn)
    assert "power bound: share of the available power" in legend_texts(thrust)
    assert thrust.get_ylim()[1] >= max(expected.values())            # in view: the thrusts reach 0.3 of 655 kN


def test_the_consequence_alarm_is_not_drawn_in_the_colour_of_a_fault():
    from allocator_pkg.simulation.report.power_figure import ALARM_COLOUR
    case = scenario("dp_consequence_alarm", 1.0)
    plain = made_up_run(case)
    trace = replace(plain.trace, sources=["swbd_a", "swbd_b"])
    for t in trace.time:
        trace.add_power([300.0, 200.0], [5600.0, 7800.0], t >= 100.0)
    sources = timeline_figure(replace(plain, trace=trace), case).axes[-1]
    alarm = next(c for c in sources.collections if c.get_label() == "consequence alarm")
    assert to_rgba(ALARM_COLOUR) != to_rgba(FAULT_COLOUR)
    assert to_rgba(alarm.get_edgecolor()[0])[:3] == to_rgba(ALARM_COLOUR)[:3] and alarm.get_hatch() == "///"


def test_event_labels_do_not_overlap():
    """Two events at 0 s and one at 30 s of a 300 s run: the label at 30 s starts within the
    width of those at 0 s, so it takes a row of its own."""
    case = scenario("dp_power_limited", 1.0)
    figure = timeline_figure(power_limited_run(case), case)
    figure.draw_without_rendering()
    renderer = figure.canvas.get_renderer()
    boxes = [text.get_window_extent(renderer) for text in figure.axes[0].texts]
    assert len(boxes) == 3
    assert not any(a.overlaps(b) for k, a in enumerate(boxes) for b in boxes[k + 1:])


def test_a_footprint_whose_set_point_moves_is_drawn_against_the_first_set_point():
    """The set-point steps 10 m north at 60 s and the vessel follows it: the track goes north."""
    case = scenario("dp_setpoint_change", 1.0)
    run = made_up_run(case, amplitude=0.0)
    for k, t in enumerate(run.trace.time):
        north = 0.0 if t < 60.0 else min(10.0, (t - 60.0) / 10.0)
        run.trace.position[k] = [north, 0.0, 0.0]
        run.trace.setpoint[k] = [0.0 if t < 60.0 else 10.0, 0.0, 0.0]
    figure = footprint_figure(run, case)
    axes = figure.axes[0]
    assert axes.get_ylabel() == "north of the first set-point [m]"
    track = labelled(axes)["track"]
    assert max(track.get_ydata()) == pytest.approx(10.0) and min(track.get_ydata()) == pytest.approx(0.0)
    assert [t.get_text() for t in axes.texts] == ["set-point from 0 s", "set-point from 60 s"]
    crosses = [line for line in axes.get_lines() if line.get_marker() == "+"]
    assert sorted(line.get_ydata()[0] for line in crosses) == [0.0, 10.0]
    circles = [patch.center for patch in axes.patches if isinstance(patch, Circle)]
    assert sorted(circles) == [(0.0, 0.0), (0.0, 10.0)]
    low, high = axes.get_ylim()
    assert low <= -case.bounds["position_error_max"] and high >= 10.0 + case.bounds["position_error_max"]
