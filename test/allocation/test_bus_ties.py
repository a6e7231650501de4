"""Bus ties (allocation/bus_ties.py, docs/power.md "Bus ties"): the buses of a tie state and
their rows by hand, the fixed pattern against every tie state enumerated, and on dp_vessel with a
tie between its switchboards: a thruster uses the other switchboard's power only with the tie
closed, the bus drawn to its limit and never beyond, the reply and refusals of
``Allocator.set_bus_tie``."""

import itertools

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from hypothesis import given, settings
from hypothesis import strategies as st
from power_reference import Reference

from allocator_pkg import Allocator
from allocator_pkg.allocation.bus_ties import BusTies
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.vehicle.config import DOF_NAMES, BusTie

OVER = 0.01
"""A source may be asked for at most 1 % more than it has (rounding)."""

CHAIN = BusTies.of(("a", "b", "c"), (BusTie("t_ab", ("a", "b"), True), BusTie("t_bc", ("b", "c"), True)))


def chain(ab: bool, bc: bool) -> BusTies:
    ties = BusTies.of(CHAIN.sources, CHAIN.ties)
    ties.set("t_ab", ab)
    ties.set("t_bc", bc)
    return ties


@pytest.mark.parametrize(("ab", "bc", "head", "rows"), [
    (True, True, [0, 0, 0], [600.0, np.inf, np.inf]),
    (False, True, [0, 1, 1], [100.0, 500.0, np.inf]),
    (True, False, [0, 0, 2], [300.0, np.inf, 300.0]),
    (False, False, [0, 1, 2], [100.0, 200.0, 300.0]),
])
def test_the_buses_of_a_chain_of_ties_by_hand(ab, bc, head, rows):
    """Sources a, b, c with 100, 200, 300 kW; a thruster on each. A closed tie pools its two
    sources into the row of the first; a bus's row has the sum of its sources' power."""
    ties = chain(ab, bc)
    assert ties.head.tolist() == head
    np.testing.assert_array_equal(ties.pool_available(np.array([100.0, 200.0, 300.0])), rows)
    pooled = ties.pool_shares(np.eye(3))
    assert [int(np.flatnonzero(row)[0]) for row in pooled] == head


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.booleans(), st.booleans()), min_size=1, max_size=8))
def test_the_buses_follow_every_change_of_the_ties(states):
    """Head and pooling, kept per state of the ties, are those of ties set so afresh (read-only)."""
    ties = BusTies.of(CHAIN.sources, CHAIN.ties)
    for ab, bc in states:
        ties.set("t_ab", ab)
        ties.set("t_bc", bc)
        fresh = chain(ab, bc)
        np.testing.assert_array_equal(ties.head, fresh.head)
        np.testing.assert_array_equal(ties.pooling(), fresh.pooling())
        assert ties.head.tolist() == [0, 0 if ab else 1, (0 if ab else 1) if bc else 2]
        assert not ties.head.flags.writeable and not ties.pooling().flags.writeable


def test_a_bus_draw_splits_over_its_sources_by_their_available_power():
    """a + b + c closed, 600 kW drawn: 100, 200 and 300 kW; b at 0 kW: a and c share by 100/400, 300/400."""
    ties = chain(True, True)
    np.testing.assert_allclose(ties.split(np.array([600.0, 0.0, 0.0]), np.array([100.0, 200.0, 300.0])),
                               [100.0, 200.0, 300.0])
    np.testing.assert_allclose(ties.split(np.array([200.0, 0.0, 0.0]), np.array([100.0, 0.0, 300.0])),
                               [50.0, 0.0, 150.0])
    split = chain(False, True).split(np.array([80.0, 250.0, 0.0]), np.array([100.0, 200.0, 300.0]))
    np.testing.assert_allclose(split, [80.0, 100.0, 150.0])


def test_the_pattern_of_a_chain_by_hand():
    """Row a can carry every thruster (a heads every bus it is in), row b those on b and c (a bus
    b + c without a), row c only c's (any bus with b has b before c)."""
    assert CHAIN.pattern(np.eye(3)).tolist() == [[True, True, True], [False, True, True], [False, False, True]]


@st.composite
def tie_graphs(draw):
    m = draw(st.integers(2, 5))
    pairs = list(itertools.combinations(range(m), 2))
    chosen = draw(st.lists(st.sampled_from(pairs), min_size=1, max_size=min(4, len(pairs)), unique=True))
    r = draw(st.integers(1, 5))
    feeds = draw(st.lists(st.lists(st.booleans(), min_size=m, max_size=m).filter(any), min_size=r, max_size=r))
    sources = tuple(f"s{j}" for j in range(m))
    ties = tuple(BusTie(f"t{k}", (sources[a], sources[b]), True) for k, (a, b) in enumerate(chosen))
    return BusTies.of(sources, ties), np.array(feeds, dtype=float)


@settings(deadline=None, max_examples=60)
@given(tie_graphs())
def test_the_pattern_is_every_pair_some_tie_state_makes_non_zero(graph):
    """Against every one of the 2^k states of k ties, enumerated."""
    ties, shares = graph
    union = np.zeros((len(ties.sources), shares.shape[0]), dtype=bool)
    for states in itertools.product((False, True), repeat=len(ties.ties)):
        state = BusTies.of(ties.sources, ties.ties)
        for tie, closed in zip(ties.ties, states):
            state.set(tie.name, closed)
        union |= state.pool_shares(shares).T > 0.0
    assert np.array_equal(ties.pattern(shares), union)


DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
TIED = {"power__bus_ties": ["bt_ab"], "power__bus_tie__bt_ab__sources": ["swbd_a", "swbd_b"],
        "power__bus_tie__bt_ab__closed": False}
ON_A = np.array([True, False, True, False])
"""dp_vessel's thrusters on swbd_a: azimuth_stbd and tunnel_fwd."""


def drawn(vehicle, thrust: np.ndarray) -> np.ndarray:
    """[kW] of each thruster, P |f|^(3/2) (1.44), from the vehicle file's coefficients."""
    return np.array([a.power_coefficient for a in vehicle.actuators]) * np.abs(thrust) ** 1.5 / 1e3


@pytest.mark.parametrize("tau", [[0, 300e3, 0, 0, 0, 0], [0, -400e3, 0, 0, 0, -5e6], [0, 300e3, 0, 0, 0, 8e6]])
def test_a_thruster_uses_the_other_switchboards_power_only_with_the_tie_closed(tau):
    """300 kW on each switchboard. Open: each switchboard's thrusters draw at most its 300 kW.
    Closed: the bus of 600 kW is drawn to its limit, and the thrusters of swbd_b draw more than
    swbd_b's 300 kW (power of swbd_a); what each source reports stays within its own."""
    vehicle = vehicle_from(DP_VESSEL, **TIED)
    allocator = Allocator(vehicle)
    allocator.set_available_power({"swbd_a": 300.0, "swbd_b": 300.0})
    seen = {}
    for closed in (False, True):
        allocator.set_bus_tie("bt_ab", closed)
        for _ in range(200):
            result = allocator.allocate(tau)
        power = drawn(vehicle, result.thrust)
        reading = allocator.power.reading(result.thrust, allocator.power_limit)
        assert np.all(reading.power <= 300.0 * (1.0 + OVER))
        np.testing.assert_allclose(reading.power.sum(), power.sum(), rtol=1e-9)
        seen[closed] = power[ON_A].sum(), power[~ON_A].sum()
    (open_a, open_b), (closed_a, closed_b) = seen[False], seen[True]
    assert open_a <= 300.0 * (1.0 + OVER) and open_b <= 300.0 * (1.0 + OVER)
    assert closed_a + closed_b <= 600.0 * (1.0 + OVER)
    assert closed_a + closed_b >= 600.0 * (1.0 - OVER)              # the bus's limit reached
    assert max(closed_a, closed_b) > 300.0 * (1.0 + OVER)          # one side on the other's power


def test_a_lost_source_in_a_closed_bus_leaves_its_thrusters_the_others_power():
    """swbd_b at 0 kW: open, azimuth_port and tunnel_aft have no feed; closed, they run on swbd_a."""
    allocator = Allocator(vehicle_from(DP_VESSEL, **TIED))
    allocator.set_available_power({"swbd_b": 0.0})
    _, high = allocator.ranges
    assert high[1] == 0.0 and high[3] == 0.0
    allocator.set_bus_tie("bt_ab", True)
    _, high = allocator.ranges
    assert high[1] > 0.0 and high[3] > 0.0


def test_set_bus_tie_replies_with_the_buses_and_refuses_an_unknown_tie():
    allocator = Allocator(vehicle_from(DP_VESSEL, **TIED))
    assert allocator.set_bus_tie("bt_ab", True) == \
        "bus tie bt_ab closed from the next sample; buses: swbd_a + swbd_b"
    limit = allocator.power_limit
    with pytest.raises(ValueError, match="unknown bus tie 'bt_xy'; bus ties: bt_ab"):
        allocator.set_bus_tie("bt_xy", False)
    assert allocator.power.ties.closed == {"bt_ab": True} and allocator.power_limit is limit
    assert allocator.set_bus_tie("bt_ab", False) == "bus tie bt_ab open from the next sample; buses: swbd_a | swbd_b"
    assert allocator.power.ties.text() == "bt_ab open (swbd_a + swbd_b)"


def test_a_new_configuration_keeps_the_tie_state_set():
    allocator = Allocator(vehicle_from(DP_VESSEL, **TIED))
    allocator.set_bus_tie("bt_ab", True)
    allocator.reconfigure(vehicle_from(DP_VESSEL, **TIED, power__swbd_a__capacity=5000.0))
    assert allocator.power.ties.closed == {"bt_ab": True}


@pytest.mark.parametrize("method", ["qp", "lp"])
def test_rows_and_pattern_for_the_optimisation(method):
    """Closed: swbd_a's row carries all four thrusters and 5600 + 7800 kW, swbd_b's is empty and
    unbounded; the pattern (every state) has both rows' own thrusters and row a all four, so the
    tie's change is values only: the method sets nothing up again."""
    allocator = Allocator(vehicle_from(DP_VESSEL, **TIED, method=method))
    rows = allocator.power.rows()
    np.testing.assert_array_equal(rows.weights.T, [[1, 0, 1, 0], [0, 1, 0, 1]])
    np.testing.assert_array_equal(rows.available, [5600e3, 7800e3])
    allocator.set_bus_tie("bt_ab", True)
    rows = allocator.power.rows()
    np.testing.assert_array_equal(rows.weights.T, [[1, 1, 1, 1], [0, 0, 0, 0]])
    np.testing.assert_array_equal(rows.available, [13400e3, np.inf])
    assert rows.pattern.pattern.T.tolist() == [[True] * 4, [False, True, False, True]]
    allocator.set_available_power({"swbd_a": 300.0, "swbd_b": 300.0})
    request = np.array([300e3, 100e3, 0, 0, 0, 1e6])
    allocator.allocate(request)
    setups = allocator.stats.solver_setups
    for closed in (False, True, False):
        allocator.set_bus_tie("bt_ab", closed)
        allocator.allocate(request)
        assert allocator.power_limit.rows.short().any() and not allocator.power_limit.limited.any()
    assert allocator.stats.solver_setups == setups


def test_a_split_fed_thruster_that_loses_a_feed_draws_on_its_live_rows():
    """azimuth_stbd fed 70/30 from swbd_a and swbd_b, swbd_b at 0 kW: open, all of its power on
    swbd_a's row, derated to its live share 0.7 of its rated power (|f| <= 0.7^(2/3) F, its feed
    limit); closed, both feeds are one bus and live: its full range."""
    vehicle = vehicle_from(DP_VESSEL, **TIED, actuators__azimuth_stbd__feeds=["swbd_a", "swbd_b"],
                           actuators__azimuth_stbd__feed_shares=[0.7, 0.3])
    allocator = Allocator(vehicle)
    rated = vehicle.actuators[0].thrust_max
    allocator.set_available_power({"swbd_b": 0.0})
    allocator.allocate(np.zeros(6))
    rows = allocator.power.rows()
    np.testing.assert_allclose(rows.weights[0], [1.0, 0.0])
    assert rows.available.tolist() == [5600e3, 0.0]
    assert allocator.power_bounds[0] == pytest.approx(0.7 ** (2 / 3) * rated)
    allocator.set_bus_tie("bt_ab", True)
    allocator.allocate(np.zeros(6))
    rows = allocator.power.rows()
    np.testing.assert_allclose(rows.weights[0], [1.0, 0.0])
    assert rows.available.tolist() == [5600e3, np.inf]
    assert allocator.power_bounds[0] == pytest.approx(rated)


@settings(deadline=None, max_examples=25)        # 30 allocations per example: no timing asserted
@given(direction=st.tuples(*[st.floats(-1.0, 1.0)] * 3).filter(lambda d: max(map(abs, d)) > 0.05),
       magnitude=st.sampled_from([0.5, 1.5]), swbd_a=st.sampled_from([0.0, 200.0, 1000.0]),
       swbd_b=st.sampled_from([0.0, 300.0, 7800.0]), closed=st.booleans(), method=st.sampled_from(["qp", "lp"]))
def test_no_bus_and_no_source_over_its_power_whatever_the_tie(direction, magnitude, swbd_a, swbd_b, closed, method):
    """Requests of every direction and size, either tie state: the thrusters of a bus draw at most
    its sources' power together (counted from the thrust, (1.44)), each source reports at most its
    own."""
    vehicle = vehicle_from(DP_VESSEL, **TIED, method=method)
    allocator = Allocator(vehicle)
    allocator.set_available_power({"swbd_a": swbd_a, "swbd_b": swbd_b})
    allocator.set_bus_tie("bt_ab", closed)
    tau = magnitude * np.array([600e3 * direction[0], 400e3 * direction[1], 0, 0, 0, 20e6 * direction[2]])
    for _ in range(30):
        thrust = allocator.allocate(tau).thrust
        power = drawn(vehicle, thrust)
        reading = allocator.power.reading(thrust, allocator.power_limit)
        assert np.all(reading.power <= np.array([swbd_a, swbd_b]) * (1.0 + OVER) + 1e-9)
        if closed:
            assert power.sum() <= (swbd_a + swbd_b) * (1.0 + OVER) + 1e-9
        else:
            assert power[ON_A].sum() <= swbd_a * (1.0 + OVER) + 1e-9
            assert power[~ON_A].sum() <= swbd_b * (1.0 + OVER) + 1e-9


def reach(method, closed, directions):
    """dp_vessel at 300 kW a switchboard, the tie ``closed`` or open: the largest scale of each
    wrench direction ``directions`` [N, N, Nm] that ``method``'s allocator holds, the capability
    programme with the allocator's power rows (~/get_capability's)."""
    vehicle = vehicle_from(DP_VESSEL, **TIED, method=method)
    allocator = Allocator(vehicle)
    allocator.set_available_power({"swbd_a": 300.0, "swbd_b": 300.0})
    allocator.set_bus_tie("bt_ab", closed)
    allocator.allocate(np.zeros(6))
    capability = Capability(vehicle, method=method, speed=0.0)
    power = (allocator.power, allocator.power_limit)
    return np.array([capability.reach_forces(np.array([d[0], d[1], 0, 0, 0, d[2]]), power=power)[0]
                     for d in directions])


@pytest.mark.parametrize("method", ["qp", "lp"])
def test_a_closed_bus_never_gives_less_than_the_open_one_with_the_power_rows(method):
    """The pooled row (A_a + A_b for every thruster of the bus) is implied by the two rows of the
    open tie, so closing the tie can only widen what the rows allow: in 16 directions of surge,
    sway and yaw the closed bus reaches at least what the open one does, and pure surge at least
    0.99 of the exact optimum of the pooled bus (SLSQP on |f|^(3/2), test/power_reference.py).
    The proportional rule of a method without rows gave 170.1 kN closed against 236.0 kN open."""
    angles = np.linspace(0.0, 2.0 * np.pi, 8, endpoint=False)
    directions = [(np.cos(a), np.sin(a), 0.0) for a in angles] + [(np.cos(a), 0.0, 40.0 * np.sin(a)) for a in angles]
    opened, closed = reach(method, False, directions), reach(method, True, directions)
    assert np.all(closed >= opened * (1.0 - 1e-6)), (opened, closed)
    allocator = Allocator(vehicle_from(DP_VESSEL, **TIED))
    vehicle, r = allocator.vehicle, len(allocator.vehicle.actuators)
    rot = np.array([a.rotatable for a in vehicle.actuators])
    low, high = allocator.ranges
    dofs = [DOF_NAMES.index(d) for d in vehicle.dofs]
    exact = Reference(allocator.configuration_matrix(np.zeros(r)),
                      np.where(rot, allocator.configuration_matrix(np.where(rot, np.pi / 2, 0.0)), 0.0), rot, low, high,
                      np.array([a.power_coefficient for a in vehicle.actuators]), np.ones((r, 1)), np.array([600e3]),
                      dofs, allocator.model.dof_scale)
    surge = exact.largest(np.eye(len(dofs))[0]) * allocator.model.dof_scale[0]
    assert 0.99 * surge <= closed[0] <= surge * (1.0 + 1e-6), (closed[0], surge)
    assert closed[0] > 1.35 * 170.1e3, closed[0]
