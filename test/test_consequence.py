"""The consequence analysis (allocator_pkg.analysis.consequence) against a linear programme
written here from the definition: forces in units of each thruster's rating, the configuration
matrix of surge, sway and yaw from the positions, each azimuth's allowed arc cut into pieces at
most 2 pi / 3 wide (the analysis cuts at pi), the 256-gon of method qp, scipy's linprog."""

import itertools
import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from generators import azimuth_vessels, loaded
from generators import faults as drawn_faults
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog

from allocator_pkg import Allocator, FaultMode
from allocator_pkg.analysis.consequence import Consequence, GroupUtilisation, remaining_share
from allocator_pkg.effectiveness.faults import Fault

SIDES = 256                    # method qp: the thrust circle as an inscribed 256-gon
APOTHEM = math.cos(math.pi / SIDES)
WIDEST_PIECE = 2.0 * math.pi / 3.0
DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"


@st.composite
def powered_vessels(draw):
    """Two or three azimuths (some reversible, with less thrust astern) and up to two tunnels,
    fed by two or three sources (some split), with a group per source (its thrusters fed by it
    alone listed, maybe one more actuator) and a group of one actuator alone."""
    vehicle, parameters = draw(azimuth_vessels(units=(2, 3), rates=False))
    names = list(vehicle.names)
    for name in names:             # a lever of a micrometre makes "no yaw" or "a little" a matter of tolerances
        parameters[f"actuators.{name}.position"] = [round(c, 2) for c in parameters[f"actuators.{name}.position"]]
        if parameters[f"actuators.{name}.type"] == "azimuth" and draw(st.booleans()):
            parameters[f"actuators.{name}.reversible"] = True
            parameters[f"actuators.{name}.thrust_min"] = -draw(st.floats(min_value=0.3, max_value=1.0)) * \
                parameters[f"actuators.{name}.thrust_max"]
    sources = [f"s{k}" for k in range(draw(st.integers(min_value=2, max_value=3)))]
    parameters["power.sources"] = sources
    for source in sources:
        parameters[f"power.{source}.capacity"] = 1000.0
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


def reference_utilisation(vehicle, parameters, group, low, high, stuck, load, lost_sources):
    """min u with T f = load, |f_i| <= u R_i in the 256-gon and a piece of its allowed arc (or
    their reverse, with the reverse radius), for the actuators the group leaves (feed shares'
    power to the 2/3), by scipy's linprog."""
    lost = set(parameters[f"redundancy_groups.{group}.sources"]) | set(lost_sources)
    members = parameters[f"redundancy_groups.{group}.actuators"]
    names = list(vehicle.names)
    columns, unit_choices, scale = [], [], []
    for name in names:
        if name in members:
            factor = 0.0
        else:
            shares = parameters[f"actuators.{name}.feed_shares"]
            factor = sum(s for f, s in zip(parameters[f"actuators.{name}.feeds"], shares) if f not in lost) ** (2 / 3)
        i = names.index(name)
        rating = parameters[f"actuators.{name}.thrust_max"]
        x, y, _ = parameters[f"actuators.{name}.position"]
        if parameters[f"actuators.{name}.type"] == "fixed":
            columns.append(("fixed", i, np.array([0.0, rating, x * rating]), high[i] * factor / rating))
        else:
            columns.append(("azimuth", i, np.array([[rating, 0.0], [0.0, rating], [-y * rating, x * rating]]),
                            None))
            unit_choices.append(azimuth_pieces(parameters.get(f"actuators.{name}.forbidden_sectors"), stuck.get(i),
                                               high[i] * factor / rating, -low[i] * factor / rating))
        scale.append(rating)
    dof_scale = np.array([sum(scale), sum(scale), sum(scale) * 40.0])
    best = math.inf
    for combination in itertools.product(*unit_choices):
        best = min(best, solve_reference(columns, combination, np.asarray(load)[[0, 1, 5]] / dof_scale, dof_scale))
    return best


def azimuth_pieces(sector, stuck, forward, reverse):
    """(start, end, radius) cones of the allowed forces, none wider than WIDEST_PIECE, ahead with
    the radius ``forward`` and astern (the cones turned by pi) with ``reverse``; ("whole",
    radius) for a free disk; None: nothing."""
    if max(forward, reverse) <= 0.0:
        return [None]
    if stuck is not None:
        if sector is not None and (stuck - sector[0]) % (2 * math.pi) <= sector[1] - sector[0]:
            return [None]
        return [(stuck, stuck, forward)] + ([(stuck + math.pi, stuck + math.pi, reverse)] if reverse > 0.0 else [])
    if sector is None:
        return [("whole", max(forward, reverse))]
    start, width = sector[1], 2 * math.pi - (sector[1] - sector[0])
    count = math.ceil(width / WIDEST_PIECE)
    cones = [(start + k * width / count, start + (k + 1) * width / count) for k in range(count)]
    return [(a, b, forward) for a, b in cones] + ([(a + math.pi, b + math.pi, reverse) for a, b in cones]
                                                  if reverse > 0.0 else [])


def solve_reference(columns, pieces, rhs, dof_scale):
    size = sum(1 if kind == "fixed" else 2 for kind, *_ in columns) + 1
    u = size - 1
    a_eq = np.zeros((3, size))
    a_ub, b_ub, bounds = [], [], [(None, None)] * u + [(0.0, None)]
    column, azimuth = 0, 0
    for kind, _, matrix, radius in columns:
        if kind == "fixed":
            a_eq[:, column] = matrix / dof_scale
            for sign in (1.0, -1.0):
                row = np.zeros(size)
                row[column], row[u] = sign, -radius
                a_ub.append(row)
                b_ub.append(0.0)
            column += 1
            continue
        piece = pieces[azimuth]
        azimuth += 1
        a_eq[:, column:column + 2] = matrix / dof_scale[:, None]
        if piece is None or piece[-1] <= 0.0:
            bounds[column] = bounds[column + 1] = (0.0, 0.0)
            column += 2
            continue
        for k in range(SIDES):
            row = np.zeros(size)
            row[column], row[column + 1] = math.cos(2 * math.pi * k / SIDES), math.sin(2 * math.pi * k / SIDES)
            row[u] = -piece[-1] * APOTHEM
            a_ub.append(row)
            b_ub.append(0.0)
        if len(piece) == 3:
            start, end, _ = piece                             # left of start, right of end; a ray: along it
            normals = [(math.sin(start), -math.cos(start)), (-math.sin(end), math.cos(end))]
            for normal in normals + ([(-math.cos(start), -math.sin(start))] if start == end else []):
                row = np.zeros(size)
                row[column], row[column + 1] = normal
                a_ub.append(row)
                b_ub.append(0.0)
        column += 2
    cost = np.zeros(size)
    cost[u] = 1.0
    result = linprog(cost, A_ub=np.array(a_ub) if a_ub else None, b_ub=b_ub or None, A_eq=a_eq, b_eq=rhs,
                     bounds=bounds, method="highs")
    return float(result.x[u]) if result.status == 0 else math.inf


@settings(deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(drawn=powered_vessels(), data=st.data())
def test_each_group_utilisation_is_the_linear_programme_of_what_its_loss_leaves(drawn, data):
    vehicle, parameters = drawn
    faults = data.draw(drawn_faults(vehicle, at_most=1))
    fault_map = {name: Fault(mode, efficiency, angle) for name, (mode, efficiency, angle) in faults.items()}
    efficiency = np.array([0.0 if n in fault_map and fault_map[n].mode == FaultMode.FAILED else
                           fault_map[n].efficiency if n in fault_map and fault_map[n].mode == FaultMode.DEGRADED else
                           1.0 for n in vehicle.names])
    high = np.array([parameters[f"actuators.{n}.thrust_max"] for n in vehicle.names]) * efficiency
    low = np.array([parameters.get(f"actuators.{n}.thrust_min", 0.0) for n in vehicle.names]) * efficiency
    stuck = {vehicle.names.index(n): f.angle for n, f in fault_map.items() if f.mode == FaultMode.STUCK}
    lost_sources = data.draw(st.sampled_from([(), (parameters["power.sources"][-1],)]))
    rated = sum(parameters[f"actuators.{n}.thrust_max"] for n in vehicle.names)
    share = data.draw(st.tuples(*[st.just(0.0) | st.floats(min_value=0.01, max_value=1.0) |
                                  st.floats(min_value=-1.0, max_value=-0.01)] * 3))
    load = np.array([share[0] * rated * 0.6, share[1] * rated * 0.4, 0.0, 0.0, 0.0, share[2] * rated * 5.0])
    answers = Consequence(vehicle).utilisation(load, low, high, fault_map, lost_sources)
    assert [a.group for a in answers] == parameters["redundancy_groups.names"]
    for answer in answers:
        expected = reference_utilisation(vehicle, parameters, answer.group, low, high, stuck, load, lost_sources)
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
    low, high = Allocator(vehicle).ranges
    lose_b, lose_a = Consequence(vehicle).utilisation([120.0, 0, 0, 0, 0, 0], low, high)
    kept = 0.5 ** (2 / 3)                                  # 63 % of its thrust on half its power
    assert lose_b.utilisation == pytest.approx(120.0 / (100.0 * kept + 100.0), abs=1e-9)
    assert lose_a.utilisation == pytest.approx(120.0 / (100.0 * kept), abs=1e-9)
    assert lose_a.alarm and not lose_b.alarm
    assert remaining_share(vehicle, vehicle.redundancy_groups[1]).tolist() == [0.5, 0.0]
    assert remaining_share(vehicle, vehicle.redundancy_groups[0], lost_sources=["a"]).tolist() == [0.0, 0.0]


def test_a_force_range_without_zero_is_a_fixed_force_whatever_the_utilisation():
    """A stuck control surface's lift: the others make up the rest."""
    vehicle = split_fed_vehicle()
    lose_b = Consequence(vehicle).utilisation([80.0, 0, 0, 0, 0, 0], np.array([-100.0, 30.0]),
                                              np.array([100.0, 30.0]))[0]
    assert lose_b.utilisation == pytest.approx(50.0 / (100.0 * 0.5 ** (2 / 3)), abs=1e-9)
    lose_b = Consequence(vehicle).utilisation([-20.0, 0, 0, 0, 0, 0], np.array([-100.0, 30.0]),
                                              np.array([100.0, 30.0]))[0]
    assert lose_b.utilisation == pytest.approx(50.0 / (100.0 * 0.5 ** (2 / 3)), abs=1e-9)


def test_faults_in_force_count_on_top_of_the_group_loss():
    vehicle = split_fed_vehicle()
    allocator = Allocator(vehicle)
    allocator.set_fault("single", FaultMode.DEGRADED, efficiency=0.5)
    low, high = allocator.ranges
    lose_b = Consequence(vehicle).utilisation([120.0, 0, 0, 0, 0, 0], low, high, allocator.faults)[0]
    assert lose_b.utilisation == pytest.approx(120.0 / (100.0 * 0.5 ** (2 / 3) + 50.0), abs=1e-9)


def test_no_load_needs_nothing_and_a_direction_nothing_left_gives_is_infinite():
    vehicle = split_fed_vehicle()
    low, high = Allocator(vehicle).ranges
    analysis = Consequence(vehicle)
    assert analysis.utilisation(np.zeros(6), low, high) == (GroupUtilisation("lose_b", 0.0),
                                                            GroupUtilisation("lose_a", 0.0))
    everything = loaded({**dp_vessel_parameters(), "redundancy_groups.names": ["all"],
                         "redundancy_groups.all.sources": ["swbd_a", "swbd_b"],
                         "redundancy_groups.all.actuators": ["azimuth_stbd", "azimuth_port", "tunnel_fwd",
                                                             "tunnel_aft"]})
    low, high = Allocator(everything).ranges
    (lost,) = Consequence(everything).utilisation([1e5, 0, 0, 0, 0, 0], low, high)
    assert math.isinf(lost.utilisation) and lost.alarm and lost.margin == -math.inf


def dp_vessel_parameters():
    from allocator_pkg import read_parameters
    parameters = read_parameters(DP_VESSEL)
    return {k: v for k, v in parameters.items() if not k.startswith("redundancy_groups.")}


def test_dp_vessel_a_surge_load_the_port_azimuth_alone_cannot_hold_alarms_switchboard_b_only():
    vehicle = vehicle_from(DP_VESSEL)
    low, high = Allocator(vehicle).ranges
    lose_a, lose_b = Consequence(vehicle).utilisation([500e3, 0, 0, 0, 0, 0], low, high)
    assert (lose_a.group, lose_b.group) == ("switchboard_a", "switchboard_b")
    assert 500.0 / 655.0 < lose_a.utilisation < 1.0 < 500.0 / 420.0 < lose_b.utilisation
