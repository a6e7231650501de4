"""Capability analysis against hand-computed values, and the allocator-capability CLI."""

import csv
import math
import os
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg import METHODS, Allocator, FaultMode, load_vehicle, read_parameters, vehicle_from_parameters
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.effectiveness.faults import Fault

# A symmetric vessel: surge thrusters at y = -+1 m, sway thrusters at x = -+1 m, +-100 N each.
SYMMETRIC = {
    "dofs": ["surge", "sway", "yaw"],
    "actuators.names": ["surge_port", "surge_stbd", "sway_aft", "sway_fwd"],
    "actuators.surge_port.type": "fixed", "actuators.surge_port.position": [0.0, -1.0, 0.0],
    "actuators.surge_port.direction": [1.0, 0.0, 0.0], "actuators.surge_port.thrust_max": 100.0,
    "actuators.surge_stbd.type": "fixed", "actuators.surge_stbd.position": [0.0, 1.0, 0.0],
    "actuators.surge_stbd.direction": [1.0, 0.0, 0.0], "actuators.surge_stbd.thrust_max": 100.0,
    "actuators.sway_aft.type": "fixed", "actuators.sway_aft.position": [-1.0, 0.0, 0.0],
    "actuators.sway_aft.direction": [0.0, 1.0, 0.0], "actuators.sway_aft.thrust_max": 100.0,
    "actuators.sway_fwd.type": "fixed", "actuators.sway_fwd.position": [1.0, 0.0, 0.0],
    "actuators.sway_fwd.direction": [0.0, 1.0, 0.0], "actuators.sway_fwd.thrust_max": 100.0,
}


@pytest.mark.parametrize("method", [name for name, method in METHODS.items()      # those serving fixed thrusters
                                    if not method.problems(replace(vehicle_from_parameters(SYMMETRIC), method=name))])
@pytest.mark.parametrize("degrees", [0, 30, 45, 90, 135, 200, 270])
def test_symmetric_vessel_nominal(method, degrees):
    # Surge and sway are independent, each 2 x 100 N with the yaw moments cancelling:
    # F(theta) = 200 / max(|cos|, |sin|).
    capability = Capability(vehicle_from_parameters(SYMMETRIC), method=method)
    theta = math.radians(degrees)
    expected = 200.0 / max(abs(math.cos(theta)), abs(math.sin(theta)))
    assert capability.max_force(theta) == pytest.approx(expected, rel=1e-6)


def test_symmetric_vessel_with_a_failure_and_a_yaw_moment():
    capability = Capability(vehicle_from_parameters(SYMMETRIC))
    # Pure surge with surge_stbd failed: surge_port (y = -1) at F makes N = +F, cancelled by the
    # sway pair pushing -+F/2 (N = 1 * F_fwd - 1 * F_aft): F <= 100 from either side.
    assert capability.max_force(0.0, faults={"surge_stbd": FaultMode.FAILED}) == pytest.approx(100.0, rel=1e-6)
    # Pure sway while holding N = 300 N m: the surge pair gives at most 200 N m (+-100 N at
    # +-1 m), the sway pair the rest: F_fwd - F_aft = 100, F_fwd + F_aft = F, F_fwd <= 100.
    assert capability.max_force(math.pi / 2, yaw_moment=300.0) == pytest.approx(100.0, rel=1e-6)
    assert capability.max_force(math.pi / 2, yaw_moment=200.0) == pytest.approx(200.0, rel=1e-6)


@pytest.mark.parametrize("method", ["qp", "nonlinear"])
def test_an_azimuth_gives_its_whole_thrust_circle_at_rest(method):
    """The qp method's octagon has a face along the thruster's direction at its exact limit:
    held, a request beyond the limit settles at the full 100 N in every direction, between the
    octagon's corners too (a fixed inscribed octagon gave 100 cos(pi/8) = 92.4 N there), and
    the capability analysis says the same."""
    parameters = {"dofs": ["surge", "sway"], "actuators.names": ["a"], "actuators.a.type": "azimuth",
                  "actuators.a.position": [0.0, 0.0, 0.0], "actuators.a.thrust_max": 100.0,
                  "azimuth_polygon_sides": 8}
    vehicle = vehicle_from_parameters(parameters)
    for direction in (0.0, math.pi / 8, 1.0, 2.5):        # middle of an octagon's side, a corner, others
        assert Capability(vehicle, method).max_force(direction) == pytest.approx(100.0, rel=1e-4)
        allocator = Allocator(vehicle, method=method)
        for _ in range(50):
            result = allocator.allocate([150.0 * math.cos(direction), 150.0 * math.sin(direction), 0, 0, 0, 0])
        assert math.hypot(*result.achieved[:2]) == pytest.approx(100.0, rel=1e-6)
    stuck = Capability(vehicle, method).max_force(math.pi / 2, faults={"a": FaultMode.STUCK})   # stuck at 0 rad
    assert stuck == pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("method", ["qp", "lp"])
def test_a_stuck_azimuth_gives_its_signed_thrust_along_its_line_as_the_allocator_does(method):
    """Stuck at 0.3 rad (between the octagon's corners and the circle's), the azimuth gives its
    whole signed thrust [-60, 100] N along its line, as the allocator gives it held there (a
    stuck thruster's one convex piece, survey 4.2; no polygon cuts the line)."""
    parameters = {"dofs": ["surge", "sway"], "actuators.names": ["a"], "actuators.a.type": "azimuth",
                  "actuators.a.position": [0.0, 0.0, 0.0], "actuators.a.thrust_max": 100.0,
                  "actuators.a.thrust_min": -60.0, "actuators.a.reversible": True, "azimuth_polygon_sides": 8}
    vehicle = vehicle_from_parameters(parameters)
    capability = Capability(vehicle, method)
    for direction, expected in ((0.3, 100.0), (0.3 + math.pi, 60.0)):
        stuck = {"a": Fault(FaultMode.STUCK, angle=0.3)}
        assert capability.max_force(direction, faults=stuck) == pytest.approx(expected, rel=1e-9)
        allocator = Allocator(vehicle, method=method)
        allocator.set_fault("a", FaultMode.STUCK, angle=0.3)
        for _ in range(80):
            result = allocator.allocate([150.0 * math.cos(direction), 150.0 * math.sin(direction), 0, 0, 0, 0])
        assert math.hypot(*result.achieved[:2]) == pytest.approx(expected, rel=1e-9)
    assert capability.max_force(1.0, faults=stuck) == pytest.approx(0.0, abs=1e-6)      # off the line


def test_forbidden_sector_removes_directions():
    parameters = {"dofs": ["surge", "sway"], "actuators.names": ["a"], "actuators.a.type": "azimuth",
                  "actuators.a.position": [0.0, 0.0, 0.0], "actuators.a.thrust_max": 100.0,
                  "actuators.a.forbidden_sectors": [1.0, 2.0], "azimuth_polygon_sides": 64}
    capability = Capability(vehicle_from_parameters(parameters), "qp")
    assert capability.max_force(1.5) == pytest.approx(0.0, abs=1e-6)
    assert capability.max_force(0.5) == pytest.approx(100.0, rel=2e-3)


def test_cli_writes_png_and_csv(tmp_path):
    binary = os.path.join(os.path.dirname(sys.executable), "allocator-capability")
    result = subprocess.run([binary, str(ROOT / "config" / "example1_rov.yaml"), "--out", str(tmp_path),
                             "--step", "30"], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    png = tmp_path / "example1_rov_capability.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    rows = list(csv.reader((tmp_path / "example1_rov_capability.csv").open()))
    assert rows[0][:4] == ["direction_deg", "nominal.surge", "nominal.sway", "nominal.magnitude"]
    assert len(rows) == 1 + 12
    assert "main_port failed.magnitude" in rows[0]
    assert float(rows[1][3]) == pytest.approx(900.0, rel=1e-4)      # surge: 2 x 300 + 2 x 150, whole circles


def test_scale_of_a_request():
    capability = Capability(vehicle_from_parameters(SYMMETRIC))
    assert capability.scale([100.0, 50.0, 0.0, 0.0, 0.0, 0.0]) == pytest.approx(2.0, rel=1e-6)
    assert capability.scale([100.0, 50.0, 999.0, 0.0, 0.0, 0.0]) == pytest.approx(2.0, rel=1e-6)   # heave ignored
    assert capability.scale([400.0, 0.0, 0.0, 0.0, 0.0, 0.0], faults={"surge_port": FaultMode.FAILED}) == \
        pytest.approx(0.25, rel=1e-6)


def test_lp_capability_is_the_survey_polygon_cut_by_the_circle():
    """One free azimuth of 100 N under lp: along a face normal of its octagon the polygon's
    96.04 N (2 cos(pi/8) / (1 + cos(pi/8))), at a corner the circle's 100 N (the polygon
    reaches 103.96 N there, but every thrust is clipped to the circle)."""
    parameters = {"dofs": ["surge", "sway"], "actuators.names": ["a"], "actuators.a.type": "azimuth",
                  "actuators.a.position": [0.0, 0.0, 0.0], "actuators.a.thrust_max": 100.0,
                  "azimuth_polygon_sides": 8}
    capability = Capability(vehicle_from_parameters(parameters), method="lp")
    c = math.cos(math.pi / 8)
    assert capability.max_force(0.0) == pytest.approx(100.0 * 2.0 * c / (1.0 + c), rel=1e-6)
    assert capability.max_force(math.pi / 8) == pytest.approx(100.0, rel=1e-4)
    assert capability.max_force(math.pi / 2) == pytest.approx(100.0 * 2.0 * c / (1.0 + c), rel=1e-6)


def test_with_saturation_direct_the_pseudo_inverse_reaches_the_attainable_set():
    weighted = Capability(vehicle_from_parameters({**SYMMETRIC, "actuators.surge_port.thrust_max": 50.0}),
                          method="pseudoinverse")
    direct = Capability(vehicle_from_parameters({**SYMMETRIC, "actuators.surge_port.thrust_max": 50.0,
                                                 "saturation": "direct"}), method="pseudoinverse")
    lp = Capability(vehicle_from_parameters({**SYMMETRIC, "actuators.surge_port.thrust_max": 50.0}), method="qp")
    for degrees in (0, 30, 90, 200):
        theta = math.radians(degrees)
        assert direct.max_force(theta) == pytest.approx(lp.max_force(theta), rel=1e-6)
        assert weighted.max_force(theta) <= direct.max_force(theta) + 1e-6
    assert weighted.max_force(0.0) < 0.9 * direct.max_force(0.0)


def test_all_methods_writes_a_plot_per_group_of_methods_with_another_capability(tmp_path):
    from allocator_pkg.capability.envelope import differing_methods
    from allocator_pkg.cli.allocator_capability import main
    from allocator_pkg.configuration.parameters import load_vehicle

    vehicle = load_vehicle(ROOT / "config" / "example1_rov.yaml")
    assert differing_methods(vehicle, "qp") == [["pseudoinverse", "svd_filter"], ["lp"]]
    assert differing_methods(load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml"), "qp") == [["pseudoinverse"]]
    assert main([str(ROOT / "config" / "example1_rov.yaml"), "--out", str(tmp_path), "--step", "45",
                 "--all-methods"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        f"example1_rov{suffix}_capability.{ext}" for suffix in ("", "_lp", "_pseudoinverse") for ext in ("csv", "png")]


def test_the_thrust_bias_changes_no_capability_and_is_no_reason_to_refuse_a_method(tmp_path):
    from allocator_pkg.cli.allocator_capability import main

    parameters = read_parameters(ROOT / "config" / "dp_vessel.yaml")
    biased = vehicle_from_parameters({**parameters, "bias.enabled": True})
    plain = Capability(vehicle_from_parameters(parameters), "lp", speed=0.0)
    with_bias = Capability(biased, "lp", speed=0.0)
    for direction in ([1.0, 0, 0, 0, 0, 0], [0, 1.0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 1.0]):
        assert with_bias.reach(direction)[0] == plain.reach(direction)[0]
    text = (ROOT / "config" / "dp_vessel.yaml").read_text().replace("enabled: false", "enabled: true")
    (tmp_path / "biased.yaml").write_text(text)
    assert main([str(tmp_path / "biased.yaml"), "--method", "lp", "--out", str(tmp_path), "--step", "90"]) == 0


def test_reach_gives_the_wrench_there_and_follows_speed_and_voltage():
    capability = Capability(vehicle_from_parameters(SYMMETRIC))
    scale, wrench = capability.reach([100.0, 50.0, 0.0, 0.0, 0.0, 0.0])
    assert scale == pytest.approx(2.0, rel=1e-6)
    assert wrench[[0, 1, 5]] == pytest.approx([200.0, 100.0, 0.0], abs=1e-6)
    assert capability.reach([0.0, 0.0, 5.0, 0.0, 0.0, 0.0]) == (math.inf, pytest.approx([0.0] * 6))
    bluerov = Capability(load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml"))
    heave = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]
    for volts, forward_end in ((16.0, 51.5), (12.0, 36.4), (13.0, (36.4 + 44.3) / 2.0), (20.0, 65.9)):
        scale, wrench = bluerov.reach(heave, voltage=volts)
        assert scale == pytest.approx(4 * forward_end, rel=1e-6)            # four verticals at the curve's end
        assert wrench == pytest.approx(np.array(heave) * 4 * forward_end, abs=1e-6)
    assert bluerov.reach(heave)[0] == pytest.approx(4 * 51.5, rel=1e-6)     # the nominal 16 V
    assert bluerov.reach(heave, faults={"thruster_5": FaultMode.FAILED}, voltage=12.0)[0] == \
        pytest.approx(2 * 36.4, rel=1e-6)                                   # a diagonal pair: no roll or pitch


@pytest.mark.parametrize("method", ["qp", "lp", "pseudoinverse"])
def test_attains_answers_as_reach_whichever_pieces_it_tries_first(method):
    """dp_vessel's azimuths have forbidden sectors: two convex pieces each, four combinations."""
    capability = Capability(load_vehicle(ROOT / "config" / "dp_vessel.yaml"), method, speed=0.0)
    for tau in ([3e5, -2e5, 0, 0, 0, 4e6], [-1e5, 4e5, 0, 0, 0, -9e6], [0, 6e5, 0, 0, 0, 0]):
        reach = capability.reach(tau)[0]
        for multiple in (0.5 * reach, reach * (1 - 1e-9), reach * (1 + 1e-6), 2.0 * reach):
            for first in (0, 3, 7):
                held, winner = capability.attains(tau, multiple, first)
                assert held == (reach >= multiple), (tau, multiple, first)
                assert (winner >= 0) == (held and method != "pseudoinverse")


def test_under_the_power_in_force_the_capability_is_the_exact_optimums():
    """dp_vessel, switchboard B failed, switchboard A at 1000 kW: with the allocator's power rows
    in the linear programme the surge is within 1 % of the exact optimum under the power
    constraint (scipy SLSQP, bench/power_use.py), never beyond it, far above what the
    proportional bounds of a method without rows allow (170.4 kN of azimuth_stbd, less its share
    of holding the yaw moment); the answer draws at most 1000 kW."""
    from conftest import bench_module
    vessel = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
    allocator = Allocator(vessel)
    allocator.set_group_fault("switchboard_b")
    allocator.set_available_power({"swbd_a": 1000.0})
    capability = Capability(vessel, speed=0.0)
    surge = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    faults = allocator.faults
    without = capability.reach(surge, faults)[0]
    budget, limit = allocator.power, allocator.power_limit
    proportional = Allocator(vessel, method="pseudoinverse")
    proportional.set_group_fault("switchboard_b")
    proportional.set_available_power({"swbd_a": 1000.0})
    bounded = capability.reach_forces(surge, faults, power=(budget, proportional.power_limit))[0]
    scale, force = capability.reach_forces(surge, faults, power=(budget, limit))
    best = bench_module("power_use").reference_scale(allocator, np.array([1.0, 0.0, 0.0])) * 1e6
    assert bounded < 0.7 * best and without > 1.5 * best
    assert 0.99 * best <= scale <= best * (1 + 1e-6)
    thrust = np.sqrt(np.bincount(capability.model.extended_owner, force ** 2, capability.model.r))
    assert budget.draw(thrust, limit)[0] <= 1000.0 * 1.01


DP_CASES = [("fault", name) for name in ("azimuth_stbd", "azimuth_port", "tunnel_fwd", "tunnel_aft")] + [
    ("group", name) for name in ("switchboard_a", "switchboard_b")]


def _settled(allocator, tau, steps):
    """The allocator's last answer after ``steps`` samples of ``tau``."""
    for _ in range(steps):
        result = allocator.allocate(tau)
    return result


@pytest.mark.parametrize("kind, name", DP_CASES)
def test_dp_vessel_capability_after_a_fault_is_the_allocators_attainable_set(kind, name):
    """dp_vessel after every single actuator fault and every redundancy group's loss: the
    ~/get_capability answer (the service's own query, with the zones, power and faults in force)
    is the allocator's attainable set in eight directions of surge and sway (yaw held at 0): the
    allocator with the same faults meets 0.99 times the answer unsaturated, settled, and saturates
    at 1.01 times it. The sector an azimuth keeps off the other lifts when that one fails."""
    import threading

    from allocator_pkg.ros.capability_query import CapabilityQuery

    vessel = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
    allocator = Allocator(vessel)
    if kind == "fault":
        allocator.set_fault(name, FaultMode.FAILED)
    else:
        allocator.set_group_fault(name)
    query, lock = CapabilityQuery(), threading.Lock()
    for degrees in range(0, 360, 45):
        direction = np.array([math.cos(math.radians(degrees)), math.sin(math.radians(degrees)), 0.0, 0.0, 0.0, 0.0])
        success, message, scale, _ = query.answer(allocator, lock, "body", 1e5 * direction)
        assert success, message
        tau = 1e5 * scale * direction
        assert scale > 0.0, (name, degrees)
        met = _settled(allocator, 0.99 * tau, 300)
        controlled = [0, 1, 5]                                  # surge, sway, yaw
        assert not met.saturated and np.allclose(met.achieved[controlled], 0.99 * tau[controlled], atol=2e3), (
            name, degrees, scale, met.short)
        assert _settled(allocator, 1.01 * tau, 60).saturated, (name, degrees, scale)


def test_dp_vessel_sway_abeam_once_the_other_azimuth_fails():
    """The sector an azimuth keeps off the other (about +-90 deg) lifts when that one fails, so
    pure sway (X = 0, N = 0; x = -41.5 m for the azimuths, 37 m and 35 m for the tunnels) comes
    from the azimuth abeam and the tunnels balancing its yaw moment, 41.5 F_a = 37 F_fwd + 35 F_aft:
    - azimuth_port failed, to starboard: F_a = 420 kN, F_aft = 300 kN, F_fwd = (41.5 420 - 35 300)
      / 37 = 187.3 kN: 907.3 kN;
    - azimuth_stbd failed, to port: both tunnels at 300 kN, F_a = 72 300 / 41.5 = 520.5 kN
      (of 655): 1120.5 kN;
    - switchboard B lost (azimuth_port, tunnel_aft), to starboard: F_fwd = 300 kN, F_a = 37 300 /
      41.5 = 267.5 kN: 567.5 kN; switchboard A lost, to port: 300 (1 + 35 / 41.5) = 553.0 kN."""
    vessel = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
    capability = Capability(vessel, speed=0.0)
    failed = FaultMode.FAILED
    cases = [({"azimuth_port": failed}, 90, 420e3 + 300e3 + (41.5 * 420e3 - 35.0 * 300e3) / 37.0),
             ({"azimuth_stbd": failed}, 270, 600e3 + 72.0 * 300e3 / 41.5),
             ({"azimuth_port": failed, "tunnel_aft": failed}, 90, 300e3 * (1.0 + 37.0 / 41.5)),
             ({"azimuth_stbd": failed, "tunnel_fwd": failed}, 270, 300e3 * (1.0 + 35.0 / 41.5))]
    for faults, degrees, expected in cases:
        assert capability.max_force(math.radians(degrees), faults=faults) == pytest.approx(expected, rel=1e-3)
    envelope = capability.envelope(90.0, faults={"azimuth_port": failed})
    assert envelope.magnitude[1] == pytest.approx(cases[0][2], rel=1e-3)


def test_with_dnv_zones_a_dead_thruster_lifts_its_zone_and_pushing_onto_it_costs_its_loss():
    """Two azimuths of 1000 N and 2 m diameter 10 m apart athwartships, ``flushing_zones: dnv``
    (surge and sway). Intact, az0 (y = +5 m) may not push its race onto az1 (toward starboard,
    +pi/2) within arctan(0.1 + 2 / 10) = 0.291 rad: along +pi/2 az0 pushes at the zone's edge and
    az1 mirrors it, 2000 cos(0.291) N. With az1 failed that zone lifts and pushing onto the dead
    az1 costs the [3.11.4] loss, beta = 1 - 1 / (0.02 x 5^2 + 0.25 x 5 + 1.2) straight at it,
    within arctan(0.6 x 2 / 10) = 0.119 rad: 1000 beta along +pi/2, 1000 N at pi/2 + 0.2
    (outside the loss sector, inside the lifted zone); the allocator meets 0.99 times each and
    not 1.01 times."""
    parameters = {"actuators.names": ["az0", "az1"], "dofs": ["surge", "sway"], "flushing_zones": "dnv"}
    for name, y in (("az0", 5.0), ("az1", -5.0)):
        parameters.update({f"actuators.{name}.type": "azimuth", f"actuators.{name}.position": [0.0, y, 0.0],
                           f"actuators.{name}.thrust_max": 1000.0, f"actuators.{name}.diameter": 2.0})
    vehicle = vehicle_from_parameters(parameters)
    capability = Capability(vehicle, "qp")
    beta = 1.0 - 1.0 / (0.02 * 25.0 + 0.25 * 5.0 + 1.2)
    assert capability.max_force(math.pi / 2) == pytest.approx(2000.0 * math.cos(math.atan(0.3)), rel=1e-3)
    dead = {"az1": FaultMode.FAILED}
    for angle, expected in ((math.pi / 2, 1000.0 * beta), (math.pi / 2 + 0.2, 1000.0)):
        reach = capability.max_force(angle, faults=dead)
        assert reach == pytest.approx(expected, rel=1e-3)
        allocator = Allocator(vehicle, method="qp")
        allocator.set_fault("az1", FaultMode.FAILED)
        direction = np.array([math.cos(angle), math.sin(angle), 0.0, 0.0, 0.0, 0.0])
        assert not _settled(allocator, 0.99 * reach * direction, 300).saturated
        assert _settled(allocator, 1.01 * reach * direction, 100).saturated
