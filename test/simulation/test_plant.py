"""The simulated vehicle's step: the 3-DOF hull's Runge-Kutta on floats against the same
fourth-order Runge-Kutta written in vector form on the hull's derivative (Vessel.derivative),
bit for bit, over states, commands, currents and headings."""

import copy

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.simulation.run_setup import build_plant
from allocator_pkg.simulation.scenario import load_scenario


def vector_step(plant, thrust, angle, dt):
    """Plant.step of a 3-DOF hull as the vector form: k = [eta', nu'] of the state arrays."""
    plant.environment.step(dt)
    current = plant.environment.current()[:2]
    load = plant.environment.hull_load(plant.eta[2])
    h = dt / plant.substeps
    state = np.concatenate([plant.eta, plant.nu])

    def derivative(x, tau):
        return np.concatenate(plant.hull.derivative(x[:3], x[3:], tau, current))

    for _ in range(plant.substeps):
        plant.thrusters.step(thrust, angle, h)
        tau = plant.body_wrench(load)
        k1 = derivative(state, tau)
        k2 = derivative(state + 0.5 * h * k1, tau)
        k3 = derivative(state + 0.5 * h * k2, tau)
        k4 = derivative(state + h * k3, tau)
        state = state + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return state[:3], state[3:]


@pytest.fixture(scope="module")
def plant():
    scenario = load_scenario(ROOT / "config/scenarios/dp_station_keeping.yaml")
    return build_plant(scenario, load_vehicle(scenario.vehicle))


@pytest.mark.parametrize("seed", range(6))
def test_the_planar_step_is_the_vector_runge_kutta_bit_for_bit(plant, seed):
    rng = np.random.default_rng(seed)
    plant = copy.deepcopy(plant)
    plant.eta = rng.normal(size=3) * [20.0, 20.0, 3.0]
    plant.nu = rng.normal(size=3) * [2.0, 1.0, 0.05]
    n = len(plant.thrusters.thrust)
    for _ in range(20):
        thrust = rng.uniform(-1.0, 1.0, n) * 3e5
        angle = rng.uniform(-np.pi, np.pi, n)
        dt = float(rng.choice([0.05, 0.1, 0.2]))
        reference = copy.deepcopy(plant)
        eta, nu = vector_step(reference, thrust, angle, dt)
        plant.step(thrust, angle, dt)
        np.testing.assert_array_equal(plant.eta, eta)
        np.testing.assert_array_equal(plant.nu, nu)
        np.testing.assert_array_equal(plant.thrusters.thrust, reference.thrusters.thrust)
        np.testing.assert_array_equal(plant.thrusters.angle, reference.thrusters.angle)

