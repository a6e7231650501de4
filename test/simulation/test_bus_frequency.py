"""The swing equation of a bus against closed forms: a step load on a droop-governed bus (the
linear second-order response), the frequency ramp with the governor held, droop load sharing
between unequal sets, the frequency relays' delay, and buses joined by closed ties."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from allocator_pkg.simulation.bus_frequency import Bus, BusTieSpec, buses
from allocator_pkg.simulation.generator_set import GeneratorSet, GeneratorSetSpec

H = 0.005
"""[s] the integration step the plant uses (electric_plant.SUBSTEP)."""


def spec(name: str = "g", rating: float = 9100.0, inertia: float = 2.4054, droop: float = 0.02,
         time_constant: float = 0.5, **changes) -> GeneratorSetSpec:
    base = GeneratorSetSpec(name=name, switchboard="a", rating=rating, power_factor=0.85, inertia=inertia,
                            droop=droop, governor_time_constant=time_constant, p_max=10.0, step_allowance=10.0,
                            ramp_max=100.0, under_frequency=0.5, over_frequency=1.5, trip_delay=0.1)
    return replace(base, **changes)


def settled_bus(specs: list[GeneratorSetSpec], load: float) -> Bus:
    """A bus at the droop steady state of ``load`` [kW]."""
    sets = [GeneratorSet(s) for s in specs]
    weights = [s.rating / s.droop for s in specs]
    frequency = (sum(w * s.no_load_frequency for w, s in zip(weights, specs)) - load) / sum(weights)
    for g in sets:
        g.p_m = g.slow = g.reference(frequency)
    return Bus(("a",), sets, frequency)


def run(bus: Bus, load: float, seconds: float) -> np.ndarray:
    frequency = []
    for k in range(round(seconds / H)):
        bus.advance(load, H, (k + 1) * H)
        frequency.append(bus.frequency)
    return np.array(frequency)


def step_response(inertia: float, droop: float, time_constant: float, step: float, t: np.ndarray) -> np.ndarray:
    """Closed form of the linear system 2 H x' = p - dP, T p' = -x / R - p (x = f - f0, p the
    governor's change, from rest) to a step dP [pu]: x(t) = -R dP + exp(-a t)(B cos w t +
    C sin w t) with s^2 + s / T + 1 / (2 H T R) = 0 (a, w from its roots)."""
    a = 1.0 / (2.0 * time_constant)
    w = math.sqrt(1.0 / (2.0 * inertia * time_constant * droop) - a * a)
    b = droop * step                                   # x(0) = 0
    c = (a * b - step / (2.0 * inertia)) / w           # x'(0) = -dP / (2 H)
    return -droop * step + np.exp(-a * t) * (b * np.cos(w * t) + c * np.sin(w * t))


@pytest.mark.parametrize("inertia", [1.0, 2.4054, 5.0])
@pytest.mark.parametrize("droop", [0.02, 0.05])
@pytest.mark.parametrize("time_constant", [0.3, 0.5, 1.0])
@pytest.mark.parametrize("step", [0.05, 0.15])
def test_a_step_load_follows_the_closed_form_nadir_and_droop(inertia, droop, time_constant, step):
    rating = 9100.0
    bus = settled_bus([spec(inertia=inertia, droop=droop, time_constant=time_constant)], 0.4 * rating)
    start = bus.frequency
    seconds = 12.0 * time_constant + 40.0 * inertia * droop + 5.0
    simulated = run(bus, (0.4 + step) * rating, seconds) - start
    t = H * np.arange(1, len(simulated) + 1)
    exact = step_response(inertia, droop, time_constant, step, t)
    assert -simulated.min() == pytest.approx(-exact.min(), rel=0.01)          # the nadir's depth
    assert t[simulated.argmin()] == pytest.approx(t[exact.argmin()], rel=0.03, abs=2 * H)
    assert simulated[-1] == pytest.approx(-droop * step, rel=0.01)            # the droop's steady state


@pytest.mark.parametrize("inertia", [1.0, 2.4054, 4.0])
@pytest.mark.parametrize("step", [0.1, 0.3])
def test_with_the_governor_held_the_frequency_falls_at_the_load_over_2h(inertia, step):
    bus = settled_bus([spec(inertia=inertia, time_constant=1e9)], 0.5 * 9100.0)
    start = bus.frequency
    simulated = run(bus, (0.5 + step) * 9100.0, 0.5)
    assert (simulated[-1] - start) / 0.5 == pytest.approx(-step / (2.0 * inertia), rel=1e-6)


@pytest.mark.parametrize("ratings", [(9100.0, 4000.0), (9100.0, 9100.0, 2500.0)])
@pytest.mark.parametrize("droops", [(0.02, 0.04, 0.03), (0.02, 0.02, 0.02)])
@pytest.mark.parametrize("load", [3000.0, 9000.0])
def test_unequal_sets_share_by_their_droop(ratings, droops, load):
    specs = [spec(f"g{i}", rating=r, droop=d) for i, (r, d) in enumerate(zip(ratings, droops))]
    bus = settled_bus(specs, 0.5 * load)
    run(bus, load, 20.0)
    weights = np.array([s.rating / s.droop for s in specs])
    frequency = (weights @ [s.no_load_frequency for s in specs] - load) / weights.sum()
    shares = weights * (np.array([s.no_load_frequency for s in specs]) - frequency)
    given = bus.electrical(load)
    assert bus.frequency == pytest.approx(frequency, abs=1e-6)
    assert [given[s.name] for s in specs] == pytest.approx(shares, rel=1e-4)
    assert sum(given.values()) == pytest.approx(load, rel=1e-9)


@pytest.mark.parametrize("delay", [0.05, 0.1, 0.3])
def test_the_under_frequency_relay_trips_after_its_delay(delay):
    held = spec(time_constant=1e9, under_frequency=0.9, trip_delay=delay)
    bus = settled_bus([held], 0.5 * 9100.0)
    times, below = [], None
    for k in range(round(3.0 / H)):
        time = (k + 1) * H
        tripped = bus.advance(0.8 * 9100.0, H, time)
        if below is None and 0.0 < bus.frequency < 0.9:
            below = time
        if tripped:
            times.append(time)
            break
    assert times and below is not None
    assert times[0] - below == pytest.approx(delay, abs=H + 1e-9)
    assert not bus.live and bus.frequency == 0.0


def test_the_over_frequency_relay_trips_on_a_load_lost():
    bus = settled_bus([spec(time_constant=1e9, over_frequency=1.05, trip_delay=0.1)], 0.5 * 9100.0)
    run(bus, 0.0, 2.0)
    # from 1 pu at (0.5 pu) / (2 H) per second to 1.05 pu, then the delay
    assert not bus.live and bus.sets[0].tripped_at == pytest.approx(0.05 * 2.0 * 2.4054 / 0.5 + 0.1, abs=2 * H)


@pytest.mark.parametrize("closed, expected", [
    ({"t12": True, "t23": True}, [("a", "b", "c")]),
    ({"t12": False, "t23": True}, [("a",), ("b", "c")]),
    ({"t12": True, "t23": False}, [("a", "b"), ("c",)]),
    ({"t12": False, "t23": False}, [("a",), ("b",), ("c",)]),
])
def test_closed_ties_join_switchboards_into_buses(closed, expected):
    ties = {"t12": BusTieSpec("t12", ("a", "b")), "t23": BusTieSpec("t23", ("b", "c"))}
    assert buses(["a", "b", "c"], ties, closed) == expected
