"""The power rows inside the optimisation (methods/power_block.py, docs/power.md "Power rows"):
against an exact reference (SLSQP with the power |f|^(3/2) itself, test/power_reference.py)
the allocator reaches at least 0.99 of the largest attainable scale in 24 directions at several
power levels on the DP vessel (single and 70/30 split feeds) and the BlueROV2 Heavy on two
batteries, never draws more than a source has, and more power never gives less thrust."""

import numpy as np
import pytest
from conftest import ROOT, vehicle_from
from power_reference import Reference

from allocator_pkg import Allocator, read_parameters, vehicle_from_parameters
from allocator_pkg.allocation.drive_power import KW
from allocator_pkg.vehicle.config import DOF_NAMES

DP_VESSEL = ROOT / "config" / "dp_vessel.yaml"
BLUEROV = ROOT / "config" / "bluerov2_heavy.yaml"
FAST = {f"actuators__{name}__{key}": value for name in ("azimuth_stbd", "azimuth_port")
        for key, value in (("azimuth_rate_max", 0.0), ("forbidden_sectors", []), ("protects", []))} | \
    {f"actuators__{name}__thrust_rate_max": 0.0
     for name in ("azimuth_stbd", "azimuth_port", "tunnel_fwd", "tunnel_aft")}
"""The DP vessel's actuators without rate limits and its azimuths without sectors: the reference
is the power problem alone, and the allocator settles within a few samples."""
SPLIT = {"actuators__azimuth_stbd__feeds": ["swbd_a", "swbd_b"], "actuators__azimuth_stbd__feed_shares": [0.7, 0.3]}
REACH = 0.99
"""The share of the exact optimum the allocator reaches in every direction and power level."""
SOLVER = 2e-5
"""The solver's tolerance on a source's draw, as a share of its consumers' rated power."""


def bluerov_on_two_batteries():
    names = [f"thruster_{k}" for k in range(1, 9)]
    changes = {"power.sources": ["bat_a", "bat_b"], "power.bat_a.capacity": 0.4, "power.bat_b.capacity": 0.3}
    for name in names:
        changes[f"actuators.{name}.feeds"] = ["bat_a"] if name in names[:4] else \
            (["bat_b"] if name in names[4:6] else ["bat_a", "bat_b"])
        if name in names[6:]:
            changes[f"actuators.{name}.feed_shares"] = [0.5, 0.5]
    parameters = read_parameters(BLUEROV)
    parameters.update(changes)
    return vehicle_from_parameters(parameters)


VEHICLES = {"dp_vessel": lambda: vehicle_from(DP_VESSEL, **FAST),
            "dp_vessel_split": lambda: vehicle_from(DP_VESSEL, **FAST, **SPLIT),
            "bluerov_two_batteries": bluerov_on_two_batteries}


def weights_by_hand(vehicle, available):
    """w_ij of docs/power.md from the shares: e_ij = min(s_ij, A_j / R_i) for a split feed, s_ij
    for a single live one, 0 for a dead one; w = e / sum_j e."""
    sources = [s.name for s in vehicle.power_sources]
    weights = np.zeros((len(vehicle.actuators), len(sources)))
    for i, a in enumerate(vehicle.actuators):
        shares = a.feed_shares or (1.0,) * len(a.feeds)
        rated = a.power_coefficient * max(abs(a.thrust_min), abs(a.thrust_max)) ** 1.5
        for feed, share in zip(a.feeds, shares):
            j = sources.index(feed)
            room = available[j] / rated if len(a.feeds) > 1 else np.inf
            weights[i, j] = min(share, room) if available[j] > 0 else 0.0
        if weights[i].sum() > 0:
            weights[i] /= weights[i].sum()
    return weights


def reference_of(allocator, available):
    vehicle = allocator.vehicle
    r = len(vehicle.actuators)
    rot = np.array([a.rotatable for a in vehicle.actuators])
    columns = allocator.configuration_matrix(np.zeros(r))
    across = allocator.configuration_matrix(np.where(rot, np.pi / 2, 0.0))
    low, high = allocator.ranges
    dofs = [DOF_NAMES.index(d) for d in vehicle.dofs]
    return Reference(columns, np.where(rot, across, 0.0), rot, low, high,
                     np.array([a.power_coefficient for a in vehicle.actuators]),
                     weights_by_hand(vehicle, available), available, dofs, allocator.model.dof_scale)


def settle(allocator, tau, samples):
    allocator.reset()
    for _ in range(samples):
        result = allocator.allocate(tau)
    return result


def directions(count, n, seed=1):
    rng = np.random.default_rng(seed)
    d = rng.normal(size=(count, n))
    return d / np.linalg.norm(d, axis=1)[:, None]


LEVELS = [0.05, 0.25, 0.6, 1.5]
"""Available power of every source as a share of its capacity."""


@pytest.mark.slow
@pytest.mark.parametrize("name", list(VEHICLES))
@pytest.mark.parametrize("level", LEVELS)
def test_the_allocator_reaches_the_exact_power_limited_optimum_and_keeps_every_source_within_its_power(name, level):
    """24 directions: the request at the reference's largest scale lambda*; after settling the
    achieved wrench's component along the direction is >= 0.99 lambda*, and every source's draw
    within its available power (to the solver's tolerance). Method qp."""
    reaches_the_optimum(name, level, "qp")


@pytest.mark.slow
@pytest.mark.parametrize("name", list(VEHICLES))
def test_the_linear_programme_reaches_the_exact_power_limited_optimum_too(name):
    """Method lp with the same rows, at a quarter of the power."""
    reaches_the_optimum(name, 0.25, "lp")


def reaches_the_optimum(name, level, method):
    vehicle = VEHICLES[name]()
    allocator = Allocator(vehicle, method=method)
    capacity = np.array([s.capacity for s in vehicle.power_sources])
    allocator.set_available_power({s.name: level * c for s, c in zip(vehicle.power_sources, capacity)})
    available = allocator.power.available * KW
    reference = reference_of(allocator, available)
    scale = allocator.model.dof_scale
    dofs = [DOF_NAMES.index(d) for d in vehicle.dofs]
    rated = np.array([a.power_coefficient * max(abs(a.thrust_min), abs(a.thrust_max)) ** 1.5
                      for a in vehicle.actuators]) @ reference.weights
    reaches = []
    for k, d in enumerate(directions(24, len(dofs))):
        best = reference.largest(d, seed=k)
        tau = np.zeros(6)
        tau[dofs] = best * d * scale
        result = settle(allocator, tau, 30)
        achieved = result.achieved[dofs] / scale
        reaches.append(float(achieved @ d) / best)
        draw = reference.power(result.thrust, np.zeros_like(result.thrust))
        assert np.all(draw <= available * (1 + 1e-6) + SOLVER * rated), (k, draw, available)
    assert min(reaches) >= REACH, (min(reaches), np.mean(reaches))


SWEEP = [0.0, 1e-3, 1.0, 10.0, 100.0, 300.0, 1000.0, 3000.0, 7800.0]
"""Switchboard B's available power [kW] along a sweep."""
MONOTONE = 1e-3
"""How far the thrust along a request may fall as the power grows: none but rounding and the
chords (measured: at most 2.4e-4 of the request)."""


def test_more_power_never_gives_less_thrust_the_split_feed_of_the_issue_included():
    """The 70/30 split-fed starboard azimuth, switchboard A at its capacity, 600 kN of surge asked
    (and five more requests): along a sweep of B's available power the achieved wrench's
    component along the request never falls by more than MONOTONE of the request (a weak feed's
    weight, min(s, A / R), moves with its power, and the chords' overestimate with it). At
    B = 0 kW the azimuth runs on A alone, derated to 0.7^(2/3) 420 kN = 331.1 kN, and with port's
    and the aft tunnel's power gone the surge is that azimuth's; a weak B (1 W) adds to it rather
    than tying the azimuth to B's watts."""
    vehicle = VEHICLES["dp_vessel_split"]()
    allocator = Allocator(vehicle)
    scale = allocator.model.dof_scale
    requests = [np.array([600e3, 0.0, 0.0, 0.0, 0.0, 0.0])]
    for d in directions(5, 3, seed=7):
        requests.append(np.array([d[0] * scale[0], d[1] * scale[1], 0.0, 0.0, 0.0, d[2] * scale[2]]) * 0.6)
    for tau in requests:
        unit = tau[[0, 1, 5]] / scale / np.linalg.norm(tau[[0, 1, 5]] / scale)
        along = []
        for kilowatts in SWEEP:
            allocator.set_available_power({"swbd_a": 5600.0, "swbd_b": kilowatts})
            result = settle(allocator, tau, 30)
            along.append(float(result.achieved[[0, 1, 5]] / scale @ unit))
        assert np.all(np.diff(along) >= -MONOTONE * np.linalg.norm(tau[[0, 1, 5]] / scale)), (tau, along)
        if tau[1] == 0.0:
            assert along[0] * scale[0] == pytest.approx(0.7 ** (2 / 3) * 420e3, rel=1e-3)
