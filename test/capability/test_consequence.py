"""The consequence analysis (allocator_pkg.capability.consequence) against a linear programme
written from the definition (test/power_reference.py): forces in units of each thruster's
rating, the configuration matrix of surge, sway and yaw from the positions, each azimuth's
allowed arc cut into pieces at most 2 pi / 3 wide (the analysis cuts at pi), the 256-gon of
method qp, scipy's linprog; the derated ranges and the power rows (chords of r^(3/2), each source
at u times its power) after a group's loss worked out from docs/power.md. And against the
allocator itself: an alarm exactly when it cannot hold the load after the loss."""

import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from generators import azimuth_vessels, loaded
from generators import faults as drawn_faults
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from power_reference import APOTHEM, SIDES, reference_utilisation

from allocator_pkg import Allocator, FaultMode
from allocator_pkg.capability.consequence import Consequence, GroupUtilisation
from allocator_pkg.capability.group_loss import InForce, Remaining, remaining
from allocator_pkg.effectiveness.faults import Fault
from allocator_pkg.vehicle.config import RedundancyGroup

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"


@st.composite
def powered_vessels(draw):
    """Two or three azimuths (some reversible, with less thrust astern) and up to two tunnels,
    fed by two or three sources (some split) of 300 to 8000 kW, each thruster drawing up to
    0.005 to 0.012 W/N^1.5 x rating^1.5 (tenths to tens of MW: some sources bind), with a group
    per source (its thrusters fed by it alone listed, maybe one more actuator) and a group of
    one actuator alone."""
    vehicle, parameters = draw(azimuth_vessels(units=(2, 3), rates=False))
    names = list(vehicle.names)
    for name in names:             # a lever of a micrometre makes "no yaw" or "a little" a matter of tolerances
        parameters[f"actuators.{name}.position"] = [round(c, 2) for c in parameters[f"actuators.{name}.position"]]
        parameters[f"actuators.{name}.power_coefficient"] = draw(st.floats(min_value=0.005, max_value=0.012))
        if parameters[f"actuators.{name}.type"] == "azimuth" and draw(st.booleans()):
            parameters[f"actuators.{name}.reversible"] = True
            parameters[f"actuators.{name}.thrust_min"] = -draw(st.floats(min_value=0.3, max_value=1.0)) * \
                parameters[f"actuators.{name}.thrust_max"]
    sources = [f"s{k}" for k in range(draw(st.integers(min_value=2, max_value=3)))]
    parameters["power.sources"] = sources
    for source in sources:
        parameters[f"power.{source}.capacity"] = draw(st.floats(min_value=300.0, max_value=8000.0))
    feeds = {}
    for name in names:
        fed = draw(st.lists(st.sampled_from(sources), min_size=1, max_size=2, unique=True))
        share = draw(st.floats(min_value=0.1, max_value=0.9))
        feeds[name] = fed
        parameters[f"actuators.{name}.feeds"] = fed
        parameters[f"actuators.{name}.feed_shares"] = [share, 1.0 - share] if len(fed) == 2 else [1.0]
    groups = []
    for source in sources:
        members = [name for name in names if feeds[name] == [source]]
        extra = draw(st.sampled_from([None, *names]))
        members += [extra] if extra is not None and extra not in members else []
        groups.append((f"lose_{source}", [source], members))
    groups.append(("lose_one", [], [draw(st.sampled_from(names))]))
    parameters["redundancy_groups.names"] = [g for g, _, _ in groups]
    for group, lost, members in groups:
        parameters[f"redundancy_groups.{group}.sources"] = lost
        parameters[f"redundancy_groups.{group}.actuators"] = members
    return loaded(parameters), parameters


@settings(deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(drawn=powered_vessels(), data=st.data())
def test_each_group_utilisation_is_the_linear_programme_of_what_its_loss_leaves(drawn, data):
    """On top of a fault, the available power reported (some sources at 0 kW) and maybe a group
    already failed: the allocator's lost sources and failed thrusters count."""
    vehicle, parameters = drawn
    faults = data.draw(drawn_faults(vehicle, at_most=1))
    fault_map = {name: Fault(mode, efficiency, angle) for name, (mode, efficiency, angle) in faults.items()}
    sources = parameters["power.sources"]
    available = {s: data.draw(st.sampled_from([1.0, 0.0]) | st.floats(min_value=0.05, max_value=1.0))
                 * parameters[f"power.{s}.capacity"] for s in sources}
    failed = data.draw(st.sampled_from([None, *parameters["redundancy_groups.names"]]))
    allocator = Allocator(vehicle)
    for name, fault in fault_map.items():
        allocator.set_fault(name, fault.mode, fault.efficiency, fault.angle)
    allocator.set_available_power(available)
    gone = []
    if failed is not None:
        allocator.set_group_fault(failed)
        gone = parameters[f"redundancy_groups.{failed}.actuators"]
        available.update(dict.fromkeys(parameters[f"redundancy_groups.{failed}.sources"], 0.0))
    efficiency = np.array([0.0 if n in gone or (n in fault_map and fault_map[n].mode == FaultMode.FAILED) else
                           fault_map[n].efficiency if n in fault_map and fault_map[n].mode == FaultMode.DEGRADED else
                           1.0 for n in vehicle.names])
    high = np.array([parameters[f"actuators.{n}.thrust_max"] for n in vehicle.names]) * efficiency
    low = np.array([parameters.get(f"actuators.{n}.thrust_min", 0.0) for n in vehicle.names]) * efficiency
    stuck = {vehicle.names.index(n): f.angle for n, f in fault_map.items()
             if f.mode == FaultMode.STUCK and n not in gone}
    rated = sum(parameters[f"actuators.{n}.thrust_max"] for n in vehicle.names)
    share = data.draw(st.tuples(*[st.just(0.0) | st.floats(min_value=0.01, max_value=1.0) |
                                  st.floats(min_value=-1.0, max_value=-0.01)] * 3))
    load = np.array([share[0] * rated * 0.6, share[1] * rated * 0.4, 0.0, 0.0, 0.0, share[2] * rated * 5.0])
    in_force = InForce.of(allocator)
    assert in_force.lost_sources(vehicle) == tuple(s for s in sources if available[s] == 0.0)
    answers = Consequence(vehicle).utilisation(load, in_force)
    assert [a.group for a in answers] == parameters["redundancy_groups.names"]
    for answer in answers:
        expected = reference_utilisation(vehicle, parameters, answer.group, low, high, stuck, load, available,
                                         efficiency)
        if math.isinf(expected):
            assert math.isinf(answer.utilisation), (answer, expected)
        else:
            assert answer.utilisation == pytest.approx(expected, abs=1e-6 * max(1.0, expected)), answer
        assert answer.margin == 1.0 - answer.utilisation
        assert answer.alarm == (answer.utilisation > 1.0)


def split_fed_vehicle(**overrides):
    """One surge thruster of 100 N fed half and half by two sources, one more on the first alone."""
    parameters = {"actuators.names": ["split", "single"], "dofs": ["surge"], "power.sources": ["a", "b"],
                  "power.a.capacity": 10.0, "power.b.capacity": 10.0, "redundancy_groups.names": ["lose_b", "lose_a"],
                  "redundancy_groups.lose_b.sources": ["b"], "redundancy_groups.lose_a.sources": ["a"],
                  "redundancy_groups.lose_a.actuators": ["single"]}
    for name, feeds, shares in (("split", ["a", "b"], [0.5, 0.5]), ("single", ["a"], [1.0])):
        parameters.update({f"actuators.{name}.type": "fixed", f"actuators.{name}.position": [0.0, 0.0, 0.0],
                           f"actuators.{name}.direction": [1.0, 0.0, 0.0], f"actuators.{name}.thrust_max": 100.0,
                           f"actuators.{name}.feeds": feeds, f"actuators.{name}.feed_shares": shares})
    parameters.update(overrides)
    return loaded(parameters)


def test_a_split_fed_thruster_keeps_its_remaining_share_of_power_to_the_two_thirds():
    vehicle = split_fed_vehicle()
    lose_b, lose_a = Consequence(vehicle).utilisation([120.0, 0, 0, 0, 0, 0])
    kept = 0.5 ** (2 / 3)                                  # 63 % of its thrust on half its power
    assert lose_b.utilisation == pytest.approx(120.0 / (100.0 * kept + 100.0), abs=1e-9)
    assert lose_a.utilisation == pytest.approx(120.0 / (100.0 * kept), abs=1e-9)
    assert lose_a.alarm and not lose_b.alarm


def test_the_available_power_in_force_shares_what_a_source_gives_after_the_loss():
    """Source a at 0.5 kW, b lost: 50 N of surge from the single thruster and the split one (now
    on a alone, derated to 0.5^(2/3) 100 = 63 N) draws least at 25 N each, 2 * 25^1.5 = 250 W
    (25 N = (12/24)^2 of the range is a breakpoint of the chords: exact), half of what a has:
    u = 0.5, where the ranges alone need 25 / 63 = 0.40; with a at its 10 kW the ranges decide,
    50 / (100 + 63)."""
    vehicle = split_fed_vehicle()
    allocator = Allocator(vehicle)
    allocator.set_available_power({"a": 0.5})
    lose_b = Consequence(vehicle).utilisation([50.0, 0, 0, 0, 0, 0], InForce.of(allocator))[0]
    assert lose_b.utilisation == pytest.approx(0.5, abs=1e-9)
    assert Consequence(vehicle).utilisation([50.0, 0, 0, 0, 0, 0])[0].utilisation == pytest.approx(
        50.0 / (100.0 + 100.0 * 0.5 ** (2 / 3)), abs=1e-9)


def test_a_source_already_lost_leaves_nothing_to_its_thrusters():
    vehicle = split_fed_vehicle()
    allocator = Allocator(vehicle)
    allocator.set_group_fault("lose_a")                   # single failed, source a at 0 kW
    in_force = InForce.of(allocator)
    assert in_force.lost_sources(vehicle) == ("a",)
    lose_b, lose_a = Consequence(vehicle).utilisation([50.0, 0, 0, 0, 0, 0], in_force)
    assert math.isinf(lose_b.utilisation)                 # split on b alone, then b lost too
    assert lose_a.utilisation == pytest.approx(50.0 / (100.0 * 0.5 ** (2 / 3)), abs=1e-9)


def test_a_force_range_without_zero_is_a_fixed_force_whatever_the_utilisation():
    """A stuck control surface's lift: the others make up the rest."""
    vehicle = split_fed_vehicle()
    analysis = Consequence(vehicle)
    left = Remaining(np.array([-63.0, 30.0]), np.array([63.0, 30.0]), (None, None), {}, {})
    assert analysis.utilisation_left(0, [80.0, 0, 0, 0, 0, 0], left).utilisation == pytest.approx(50.0 / 63.0)
    assert analysis.utilisation_left(0, [-20.0, 0, 0, 0, 0, 0], left).utilisation == pytest.approx(50.0 / 63.0)


def test_faults_in_force_count_on_top_of_the_group_loss():
    vehicle = split_fed_vehicle()
    allocator = Allocator(vehicle)
    allocator.set_fault("single", FaultMode.DEGRADED, efficiency=0.5)
    lose_b = Consequence(vehicle).utilisation([120.0, 0, 0, 0, 0, 0], InForce.of(allocator))[0]
    assert lose_b.utilisation == pytest.approx(120.0 / (100.0 * 0.5 ** (2 / 3) + 50.0), abs=1e-9)


def test_no_load_needs_nothing_and_a_direction_nothing_left_gives_is_infinite():
    vehicle = split_fed_vehicle()
    analysis = Consequence(vehicle)
    assert analysis.utilisation(np.zeros(6)) == (GroupUtilisation("lose_b", 0.0), GroupUtilisation("lose_a", 0.0))
    everything = loaded({**dp_vessel_parameters(), "redundancy_groups.names": ["all"],
                         "redundancy_groups.all.sources": ["swbd_a", "swbd_b"],
                         "redundancy_groups.all.actuators": ["azimuth_stbd", "azimuth_port", "tunnel_fwd",
                                                             "tunnel_aft"]})
    (lost,) = Consequence(everything).utilisation([1e5, 0, 0, 0, 0, 0])
    assert math.isinf(lost.utilisation) and lost.alarm and lost.margin == -math.inf


def dp_vessel_parameters():
    from allocator_pkg import read_parameters
    parameters = read_parameters(DP_VESSEL)
    return {k: v for k, v in parameters.items() if not k.startswith("redundancy_groups.")}


def test_dp_vessel_a_surge_load_the_port_azimuth_alone_cannot_hold_alarms_switchboard_b_only():
    vehicle = vehicle_from(DP_VESSEL)
    lose_a, lose_b = Consequence(vehicle).utilisation([500e3, 0, 0, 0, 0, 0])
    assert (lose_a.group, lose_b.group) == ("switchboard_a", "switchboard_b")
    assert 500.0 / 655.0 < lose_a.utilisation < 1.0 < 500.0 / 420.0 < lose_b.utilisation


def test_dp_vessel_each_azimuth_sector_lifts_with_the_unit_it_protects():
    """The loss of either switchboard kills the azimuth the other one's sector protects: the
    reference has that sector removed; without ``protects`` a pure sway load is beyond the
    starboard azimuth and the bow tunnel after switchboard B's loss."""
    from allocator_pkg import read_parameters
    parameters = {**read_parameters(DP_VESSEL), **{f"actuators.{n}.feed_shares": [1.0] for n in
                                                   ("azimuth_stbd", "azimuth_port", "tunnel_fwd", "tunnel_aft")}}
    vehicle = vehicle_from(DP_VESSEL)
    analysis = Consequence(vehicle)
    available = {"swbd_a": 5600.0, "swbd_b": 7800.0}
    low = np.array([0.0, 0.0, -300e3, -300e3])
    high = np.array([420e3, 655e3, 300e3, 300e3])
    lifted = {"switchboard_a": "actuators.azimuth_port.forbidden_sectors",
              "switchboard_b": "actuators.azimuth_stbd.forbidden_sectors"}
    for k in range(16):
        angle = 2.0 * math.pi * k / 16
        load = [300e3 * math.cos(angle), 300e3 * math.sin(angle), 0.0, 0.0, 0.0, 2e6 * math.sin(3 * angle)]
        for answer in analysis.utilisation(load):
            reference = {key: value for key, value in parameters.items() if key != lifted[answer.group]}
            expected = reference_utilisation(vehicle, reference, answer.group, low, high, {}, load, available, [1] * 4)
            assert math.isfinite(expected) and answer.utilisation == pytest.approx(expected, rel=1e-6), (k, answer)
    sway = [0.0, 300e3, 0.0, 0.0, 0.0, 0.0]            # tunnel_fwd 300 kN x 41.5 / 78.5 against the yaw
    assert analysis.utilisation(sway)[1].utilisation == pytest.approx(41.5 / 78.5, rel=1e-9)
    fixed = loaded({**parameters, "actuators.azimuth_stbd.protects": [""], "actuators.azimuth_port.protects": [""]})
    assert math.isinf(Consequence(fixed).utilisation(sway)[1].utilisation)


def flushing_vehicle():
    """Two azimuths of 1000 N and 2 m diameter 10 m apart athwartships (5 D: inside the [3.11.3]
    15 D and the [3.11.4] 8 D), surge and sway, ``flushing_zones: dnv``, a group per azimuth."""
    parameters = {"actuators.names": ["az0", "az1"], "dofs": ["surge", "sway"], "flushing_zones": "dnv",
                  "redundancy_groups.names": ["lose_az1", "lose_az0"],
                  "redundancy_groups.lose_az1.actuators": ["az1"], "redundancy_groups.lose_az0.actuators": ["az0"]}
    for name, y in (("az0", 5.0), ("az1", -5.0)):
        parameters.update({f"actuators.{name}.type": "azimuth", f"actuators.{name}.position": [0.0, y, 0.0],
                           f"actuators.{name}.thrust_max": 1000.0, f"actuators.{name}.diameter": 2.0})
    return loaded(parameters)


def polygon_radius(angle):
    """The 256-gon's radius (per unit of thrust) along ``angle``."""
    return APOTHEM / max(math.cos(angle - 2.0 * math.pi * k / SIDES) for k in range(SIDES))


def test_after_a_loss_the_zone_onto_the_dead_thruster_lifts_and_pushing_onto_it_costs_thrust():
    """az0 (y = +5) pushing to starboard (+pi/2) sends its race onto az1: intact a zone of
    arctan(0.1 + 2/10) = 0.29 rad each side; az1 dead, a loss sector of arctan(0.6 x 2/10) =
    0.12 rad each side, beta = 1 - 1 / (0.02 x 5^2 + 0.25 x 5 + 1.2) straight at it."""
    vehicle = flushing_vehicle()
    analysis = Consequence(vehicle)
    beta = 1.0 - 1.0 / (0.02 * 25.0 + 0.25 * 5.0 + 1.2)
    onto = analysis.utilisation([0.0, 500.0, 0.0, 0.0, 0.0, 0.0])[0]
    assert onto.utilisation == pytest.approx(500.0 / (1000.0 * beta * APOTHEM), rel=1e-9)
    angle = math.pi / 2 + 0.2                               # in the lifted zone, out of the loss sector
    beside = analysis.utilisation([500.0 * math.cos(angle), 500.0 * math.sin(angle), 0, 0, 0, 0])[0]
    assert beside.utilisation == pytest.approx(0.5 / polygon_radius(angle), rel=1e-9)
    left = remaining(vehicle, InForce.intact(vehicle), vehicle.redundancy_groups[0])
    assert left.rotations[0].forbidden_sectors == () and [loss.flushed for loss in left.losses[0]] == ["az1"]
    intact = remaining(vehicle, InForce.intact(vehicle), RedundancyGroup("none", (), ()))
    assert len(intact.rotations[0].forbidden_sectors) == 1 and not intact.losses


def test_a_thruster_pushing_onto_a_dead_one_has_its_pieces_cut_and_unless_it_reverses_the_sector_left_alone():
    from allocator_pkg.capability.consequence import force_pieces
    from allocator_pkg.effectiveness.flushing import DeadFlushing
    loss = DeadFlushing("az0", "az1", math.pi / 2, 0.2, 0.6)          # no foot: beta is the least factor
    free = flushing_vehicle().actuators[0].rotation
    cut, *left_alone = force_pieces(free, 0.0, 1000.0, None, [loss])
    assert cut.whole and cut.radius == pytest.approx(600.0)
    assert all(p.radius == 1000.0 and not p.contains(math.pi / 2) for p in left_alone)
    assert any(p.contains(math.pi / 2 + 0.21) for p in left_alone)
    reversing = force_pieces(free, -500.0, 1000.0, None, [loss])
    assert [p.radius for p in reversing] == [pytest.approx(600.0)]      # cut only, the larger side's radius
    (ray,) = force_pieces(free, 0.0, 1000.0, math.pi / 2, [loss])
    assert (ray.start, ray.radius) == (math.pi / 2, pytest.approx(600.0))


FREE = {f"actuators__{name}__{key}": value for name in ("azimuth_stbd", "azimuth_port")
        for key, value in (("azimuth_rate_max", 0.0), ("forbidden_sectors", []), ("protects", []))} | \
    {f"actuators__{name}__thrust_rate_max": 0.0 for name in ("azimuth_stbd", "azimuth_port", "tunnel_fwd",
                                                             "tunnel_aft")}
"""The DP vessel without rate limits and sectors: the allocator settles within a few samples."""
FREE_VESSEL = vehicle_from(DP_VESSEL, **FREE)
CLEAR = 0.02
"""Loads within this share of u = 1 are left out: there the answer is a matter of tolerances."""


@settings(deadline=None, max_examples=40)
@given(load=st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(-1.0, 1.0)).filter(
    lambda v: max(map(abs, v)) >= 0.01), levels=st.tuples(st.floats(0.02, 1.0), st.floats(0.02, 1.0)))
def test_an_alarm_exactly_when_the_allocator_itself_cannot_hold_the_load_after_the_loss(load, levels):
    """Random loads and available power on the DP vessel: for each group, u <= 1 - CLEAR means
    the allocator with the group failed holds the load (after 30 samples within CLEAR / 4 of it,
    in units of each DOF's authority), u >= 1 + CLEAR that it does not (it misses by at least
    1 - (1 + CLEAR)^(-2/3) = 1.3 % where the power binds): the analysis answers with the
    allocator's own power rows."""
    tau = np.array([6e5 * load[0], 4e5 * load[1], 0.0, 0.0, 0.0, 2e7 * load[2]])
    power = {"swbd_a": 5600.0 * levels[0], "swbd_b": 7800.0 * levels[1]}
    allocator = Allocator(FREE_VESSEL)
    allocator.set_available_power(power)
    answers = Consequence(FREE_VESSEL).utilisation(tau, InForce.of(allocator))
    for answer in answers:
        if abs(answer.utilisation - 1.0) < CLEAR:
            continue
        after = Allocator(FREE_VESSEL)
        after.set_available_power(power)
        after.set_group_fault(answer.group)
        for _ in range(30):
            result = after.allocate(tau)
        scale = after.model.dof_scale
        miss = np.linalg.norm((result.achieved - tau)[[0, 1, 5]] / scale) / np.linalg.norm(tau[[0, 1, 5]] / scale)
        assert (miss <= CLEAR / 4) == (not answer.alarm), (answer, miss)
