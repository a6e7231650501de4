"""Power per source in the allocation (allocation/power_budget.py, docs/power.md): the derating
of a split-fed thruster worked by hand, a source's budget shared by its consumers and its unused
power shared again (by hand), redundancy groups failed and cleared, and properties over random
requests, available power, faults and methods: no source asked for more than it has, every
command within its limits (test_power_stage.py: the rule in a sample)."""

import math

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from hypothesis import given, settings
from hypothesis import strategies as st

from allocator_pkg import METHODS, Allocator, FaultMode, read_parameters, vehicle_from_parameters
from allocator_pkg.allocation.drive_power import DrivePower
from allocator_pkg.allocation.power_budget import PowerBudget
from allocator_pkg.allocation.solve import check_method
from allocator_pkg.effectiveness.faults import static_ranges
from allocator_pkg.vehicle.config import ConfigError

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
BLUEROV = ROOT / "config" / "bluerov2_heavy.yaml"
OVER = 0.01
"""A source may be asked for at most 1 % more than it has (rounding)."""

SPLIT = {"actuators__azimuth_stbd__feeds": ["swbd_a", "swbd_b"],
         "actuators__azimuth_stbd__feed_shares": [0.7, 0.3]}
"""dp_vessel with its starboard azimuth fed 70 % from switchboard A and 30 % from B."""


def split_vessel():
    return vehicle_from(DP_VESSEL, **SPLIT)


def bluerov_on_two_batteries():
    """The BlueROV2 Heavy on two batteries: thrusters 1-4 on bat_a, 5-6 on bat_b, 7-8 split
    50/50; groups that lose either battery with its own thrusters."""
    names = [f"thruster_{k}" for k in range(1, 9)]
    changes = {"power.sources": ["bat_a", "bat_b"], "power.bat_a.capacity": 1.2, "power.bat_b.capacity": 0.9,
               "redundancy_groups.names": ["battery_a", "battery_b"],
               "redundancy_groups.battery_a.sources": ["bat_a"],
               "redundancy_groups.battery_a.actuators": names[:4],
               "redundancy_groups.battery_b.sources": ["bat_b"],
               "redundancy_groups.battery_b.actuators": names[4:6]}
    for name in names[:4]:
        changes[f"actuators.{name}.feeds"] = ["bat_a"]
    for name in names[4:6]:
        changes[f"actuators.{name}.feeds"] = ["bat_b"]
    for name in names[6:]:
        changes[f"actuators.{name}.feeds"] = ["bat_a", "bat_b"]
        changes[f"actuators.{name}.feed_shares"] = [0.5, 0.5]
    parameters = read_parameters(BLUEROV)
    parameters.update(changes)
    return vehicle_from_parameters(parameters)


def test_a_split_fed_thruster_that_loses_a_feed_runs_derated_by_hand():
    """azimuth_stbd: P = 0.0074 W/N^1.5, F = 420 kN, so R = 0.0074 * 420000^1.5 = 2014.3 kW.
    With both feeds live, 200 kN draws 0.0074 * 200000^1.5 = 661.9 kW: 463.3 kW from A (0.7),
    198.6 kW from B (0.3). Switchboard B at 0 kW: S = 0.7, p <= 0.7 * 2014.3 = 1410.0 kW, so
    |f| <= 0.7^(2/3) * 420 kN = 0.78837 * 420 kN = 331.1 kN, all of it drawn from A."""
    allocator = Allocator(split_vessel())
    budget, limit = allocator.power, allocator.power_limit
    thrust = np.array([200000.0, 0.0, 0.0, 0.0])
    assert budget.draw(thrust, limit) == pytest.approx([463.3, 198.6], abs=0.1)
    assert not limit.limited.any()
    allocator.set_available_power({"swbd_b": 0.0})
    limit = allocator.power_limit
    assert limit.bound[0] == pytest.approx(331.1e3, rel=1e-4)
    assert limit.limited.tolist() == [True, True, False, True]       # B's own thrusters have no feed left
    assert budget.draw(np.array([limit.bound[0], 0, 0, 0]), limit) == pytest.approx([1410.0, 0.0], abs=0.1)
    assert allocator.ranges[1][0] == pytest.approx(331.1e3, rel=1e-4)


def test_a_short_source_is_shared_by_its_consumers_in_proportion_to_their_largest_draws():
    """Switchboard A at 1000 kW: its consumers could draw 2014.3 kW (azimuth_stbd) and
    0.0113 * 300000^1.5 = 1856.8 kW (tunnel_fwd), 3871.1 kW together; each is scaled by
    rho = 1000 / 3871.1 = 0.25833, its thrust by rho^(2/3) = 0.40555: 170.3 kN and 121.7 kN (the
    bounds of a method without power rows)."""
    allocator = Allocator(vehicle_from(DP_VESSEL), method="pseudoinverse")
    allocator.set_available_power({"swbd_a": 1000.0})
    bound = allocator.power_limit.bound
    assert bound[[0, 2]] == pytest.approx([170.3e3, 121.7e3], rel=1e-3)
    assert bound[[1, 3]].tolist() == [655000.0, 300000.0]
    assert allocator.power.draw(bound * [1, 0, 1, 0], allocator.power_limit) == pytest.approx([1000.0, 0.0])


def test_the_power_rows_of_a_weak_feed_by_hand():
    """The 70/30 split vessel, switchboard B at 300 kW: azimuth_stbd's rated power is
    R = 0.0074 * 420000^1.5 = 2014.3 kW, so feed B can give e_B = min(0.3, 300 / 2014.3) = 0.14893
    of it and A its 0.7: w = (0.7, 0.14893) / 0.84893 = (0.82457, 0.17543), and the thrust is
    derated to 0.84893^(2/3) * 420 kN = 376.55 kN. Switchboard A's consumers can draw at most
    2014.3 * 0.82457 + 0.0113 * 300000^1.5 = 3517.8 kW of its 5600: its row cannot bind; B's
    (2014.3 * 0.17543 + 0.0074 * 655000^1.5 + 1856.8 = 6132.4 kW > 300) does. The rows see the
    draw through the chords: never below the exact draw, within 2 % of it here."""
    allocator = Allocator(split_vessel())
    allocator.set_available_power({"swbd_b": 300.0})
    rows = allocator.power_limit.rows
    assert rows.weights[0] == pytest.approx([0.82457, 0.17543], abs=2e-5)
    assert rows.weights[1:].tolist() == [[0.0, 1.0], [1.0, 0.0], [0.0, 1.0]]
    assert rows.available.tolist() == [5600e3, 300e3]
    assert rows.short().tolist() == [False, True]
    assert allocator.power_bounds[0] == pytest.approx(376.55e3, rel=1e-4)
    assert rows.pattern.pattern.tolist() == [[True, True], [False, True], [True, False], [False, True]]
    thrust = np.array([200e3, -50e3, 10e3, 0.0])
    exact = np.array([0.0074 * 200e3 ** 1.5 * 0.82457 + 0.0113 * 10e3 ** 1.5,
                      0.0074 * 200e3 ** 1.5 * 0.17543 + 0.0074 * 50e3 ** 1.5])
    draw = DrivePower(rows.forward, rows.reverse, np.full(4, np.inf)).power(thrust) @ rows.weights
    assert draw == pytest.approx(exact, rel=1e-4)
    assert np.all(rows.seen(thrust) >= draw) and rows.seen(thrust) == pytest.approx(exact, rel=0.02)


def test_thrust_moves_to_the_other_sources_actuators():
    """Switchboard A short: the surge the two azimuths share equally moves from azimuth_stbd
    (A) to azimuth_port (B), and the request is still met."""
    allocator = Allocator(vehicle_from(DP_VESSEL))
    tau = [5e5, 0.0, 0.0, 0.0, 0.0, 0.0]
    for _ in range(80):
        nominal = allocator.allocate(tau)
    allocator.set_available_power({"swbd_a": 300.0})
    for _ in range(80):
        short = allocator.allocate(tau)
    assert nominal.thrust[0] == pytest.approx(nominal.thrust[1], rel=1e-6)
    assert short.thrust[0] < 0.5 * nominal.thrust[0] and short.thrust[1] > 1.5 * nominal.thrust[1]
    assert not short.saturated
    assert allocator.power.draw(short.thrust, allocator.power_limit)[0] <= 300.0 * (1 + OVER)


def test_a_group_fault_fails_its_actuators_and_sources_from_the_next_sample_and_clears():
    allocator = Allocator(split_vessel())
    tau = [3e5, 1e5, 0.0, 0.0, 0.0, 2e6]
    for _ in range(50):
        allocator.allocate(tau)
    setups = allocator.stats.solver_setups
    allocator.set_group_fault("switchboard_b")
    result = allocator.allocate(tau)
    assert result.thrust[[1, 3]].tolist() == [0.0, 0.0]
    assert result.mode.tolist() == [0, 2, 0, 2]
    assert allocator.group_faults == ("switchboard_b",)
    assert allocator.power.available.tolist() == [5600.0, 0.0]
    assert abs(result.thrust[0]) <= 0.7 ** (2 / 3) * 420000.0 * (1 + 1e-9)    # outside the group, derated
    allocator.set_available_power({"swbd_b": 7000.0})                           # the topic cannot bring it back
    assert allocator.power.available.tolist() == [5600.0, 0.0]
    allocator.clear_faults()
    assert allocator.group_faults == () and allocator.power.available.tolist() == [5600.0, 7000.0]
    assert not allocator.power_limit.limited.any() and allocator.modes().tolist() == [0, 0, 0, 0]
    allocator.allocate(tau)
    assert allocator.stats.solver_setups == setups            # new bounds for the running solver only


def test_an_unknown_group_or_bad_available_power_is_refused_and_nothing_changes():
    allocator = Allocator(split_vessel())
    with pytest.raises(ValueError, match="unknown redundancy group 'bus'; groups: switchboard_a, switchboard_b"):
        allocator.set_group_fault("bus")
    for bad, reason in (({"swbd_c": 1.0}, "unknown power source 'swbd_c'; sources: swbd_a, swbd_b"),
                        ({"swbd_a": math.nan}, "finite and >= 0"), ({"swbd_a": 10.0, "swbd_b": -1.0}, ">= 0")):
        with pytest.raises(ValueError, match=reason):
            allocator.set_available_power(bad)
    assert allocator.power.available.tolist() == [5600.0, 7800.0] and allocator.faults == {}


def test_the_same_available_power_again_changes_nothing():
    allocator = Allocator(split_vessel())
    allocator.set_available_power({"swbd_a": 1000.0})
    limit = allocator.power_limit
    allocator.set_available_power({"swbd_a": 1000.0, "swbd_b": 7800.0})
    assert allocator.power_limit is limit
    allocator.set_available_power({"swbd_a": 999.0})
    assert allocator.power_limit is not limit


def test_without_sources_or_at_capacity_nothing_changes():
    assert Allocator(vehicle_from(BLUEROV)).power_limit is None
    parameters = read_parameters(DP_VESSEL)
    plain = {k: v for k, v in parameters.items()
             if not k.startswith(("power.", "redundancy_groups.")) and not k.endswith((".feeds", ".feed_shares"))}
    with_power, without = Allocator(vehicle_from_parameters(parameters)), Allocator(vehicle_from_parameters(plain))
    rng = np.random.default_rng(3)
    for _ in range(200):
        tau = rng.normal(size=6) * [4e5, 3e5, 0, 0, 0, 1e7]
        a, b = with_power.allocate(tau), without.allocate(tau)
        assert np.array_equal(a.thrust, b.thrust) and np.array_equal(a.azimuth, b.azimuth)


def test_a_reconfiguration_keeps_the_reported_power_and_the_lost_sources():
    allocator = Allocator(split_vessel())
    allocator.set_available_power({"swbd_a": 2000.0})
    allocator.set_group_fault("switchboard_b")
    allocator.reconfigure(vehicle_from(DP_VESSEL, rate_hz=5.0, **SPLIT))
    assert allocator.power.available.tolist() == [2000.0, 0.0] and allocator.group_faults == ("switchboard_b",)


def test_a_lost_feed_with_no_other_leaves_no_thrust():
    budget = PowerBudget(split_vessel())
    budget.lost = frozenset({"swbd_a"})
    limit = budget.limit(np.full(4, -7e5), np.full(4, 7e5))
    assert limit.bound[2] == 0.0 and limit.bound[0] == pytest.approx(0.3 ** (2 / 3) * 420000.0)


# -- properties: thousands of requests under random power, faults and methods -----------------

VEHICLES = {"dp_vessel_split": split_vessel(), "bluerov_two_batteries": bluerov_on_two_batteries()}
def _serves(method, vehicle) -> bool:
    try:
        check_method(method, vehicle)
    except ConfigError:
        return False
    return True


CASES = [(name, method) for name, vehicle in VEHICLES.items() for method in METHODS if _serves(method, vehicle)]
_ALLOCATORS: dict = {}


def allocator_of(name: str, method: str) -> Allocator:
    key = (name, method)
    if key not in _ALLOCATORS:
        _ALLOCATORS[key] = Allocator(VEHICLES[name], method=method)
    allocator = _ALLOCATORS[key]
    allocator.clear_faults()
    allocator.reset_available_power()
    allocator.reset()
    return allocator


@st.composite
def situations(draw):
    name, method = draw(st.sampled_from(CASES))
    vehicle = VEHICLES[name]
    sources = [s.name for s in vehicle.power_sources]
    capacity = {s.name: s.capacity for s in vehicle.power_sources}
    available = {s: draw(st.sampled_from([0.0, 1.0, capacity[s]]) | st.floats(0.0, capacity[s])) for s in sources}
    faults = draw(st.lists(st.tuples(st.sampled_from([a.name for a in vehicle.actuators]),
                                     st.sampled_from([FaultMode.FAILED, FaultMode.DEGRADED])), max_size=2))
    group = draw(st.none() | st.sampled_from([g.name for g in vehicle.redundancy_groups]))
    seed = draw(st.integers(0, 2 ** 32 - 1))
    held = draw(st.sampled_from([1, 10]))
    return name, method, available, faults, group, seed, held


@settings(deadline=None)              # 30 allocations per example: no timing asserted
@given(situations())
def test_no_source_is_asked_for_more_than_it_has_and_every_command_is_within_its_limits(situation):
    """30 requests in a row for each drawn case (method, available power, actuator faults,
    a failed group), each held for one sample or for ten (where a short source's power is
    shared again and carried over), the available power changed again halfway: 60 examples x 30 requests
    (HYPOTHESIS_PROFILE=explore: 1000 x 30). The allocators are kept between examples (faults,
    power and state reset), as a node keeps its own."""
    name, method, available, faults, group, seed, held = situation
    allocator = allocator_of(name, method)
    vehicle = allocator.vehicle
    for actuator, mode in faults:
        allocator.set_fault(actuator, mode, efficiency=0.5 if mode == FaultMode.DEGRADED else None)
    if group is not None:
        allocator.set_group_fault(group)
    rng = np.random.default_rng(seed)
    scale = np.array([max(abs(a.thrust_max), abs(a.thrust_min)) for a in vehicle.actuators]).sum()
    allocator.set_available_power(available)
    for k in range(30):
        if k == 15:
            allocator.set_available_power({s: v * rng.uniform(0.0, 1.0) for s, v in available.items()})
        if k % held == 0:
            tau = rng.normal(size=6) * scale * rng.choice([0.05, 0.3, 1.0])
        result = allocator.allocate(tau)
        limit = allocator.power_limit
        draw = allocator.power.draw(result.thrust, limit)
        has = allocator.power.available
        assert np.all(draw <= has * (1 + OVER) + 1e-9), (draw, has)
        low, high = static_ranges(vehicle, allocator.fault_set, allocator.speed, allocator.voltage)
        slack = 1e-9 * np.maximum(1.0, np.abs(high - low))
        assert np.all(result.thrust >= low - slack) and np.all(result.thrust <= high + slack)
        assert np.all(np.abs(result.thrust) <= limit.largest * (1 + 1e-9))      # the feed limit: derated
        for actuator, command in zip(vehicle.actuators, result.command.tolist()):
            lowest, highest = sorted((actuator.command.command_min, actuator.command.command_max))
            assert lowest - 1e-9 <= command <= highest + 1e-9


@pytest.mark.parametrize("efficiencies", [[1.0, 0.5, 1.0, 1.0], [0.25, 1.0, 0.8, 1.0], [1.0, 1.0, 1.0, 1.0]])
def test_the_drives_in_force_follow_each_efficiency_settled(efficiencies):
    """P / eta^(3/2) of every drive (docs/power.md, "Degraded") after each settle, the coefficients
    made once per efficiency taken."""
    budget = PowerBudget(vehicle_from(DP_VESSEL))
    forward = budget.drive.forward.copy()
    first = budget.in_force
    assert budget.in_force is first
    np.testing.assert_array_equal(first.forward, forward)
    budget.settle(np.array(efficiencies))
    eta = np.array(efficiencies)
    np.testing.assert_allclose(budget.in_force.forward, forward / eta ** 1.5, rtol=1e-15)
    np.testing.assert_allclose(budget.in_force.reverse, budget.drive.reverse / eta ** 1.5, rtol=1e-15)
    budget.settle(np.ones(len(efficiencies)))
    np.testing.assert_array_equal(budget.in_force.forward, forward)
