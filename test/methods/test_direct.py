"""saturation: direct (Durham's direct method, section 4.3) against an LP reference for the
largest scale, over directions and magnitudes, for every method that implements it; and how it
differs from preserve_direction."""

import math

import numpy as np
import pytest
from conftest import DATA, ROOT, vehicle_from
from reference import largest_attainable_scale, weighted_pseudo_inverse
from scipy.optimize import linprog

from allocator_pkg import METHODS, Allocator
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix

EIGHT = DATA / "eight_thrusters.yaml"
DIRECT = [name for name in METHODS if "direct" in METHODS[name].saturation_modes]


def matrices(vehicle):
    t = configuration_matrix(vehicle.actuators, [0.0] * len(vehicle.actuators))[list(vehicle.dof_indices)]
    low = np.array([a.thrust_min for a in vehicle.actuators])
    high = np.array([a.thrust_max for a in vehicle.actuators])
    return t, low, high


def requests(count=40, seed=3):
    rng = np.random.default_rng(seed)
    directions = rng.normal(size=(count, 6)) * np.array([1.0, 1.0, 1.0, 0.1, 0.1, 0.1])
    return [magnitude * d / np.linalg.norm(d) for d in directions for magnitude in (10.0, 60.0, 200.0)]


@pytest.mark.parametrize("method", DIRECT)
def test_the_answer_is_the_largest_scale_of_the_request_an_lp_reference_finds(method):
    vehicle = vehicle_from(EIGHT, saturation="direct")
    t, low, high = matrices(vehicle)
    tolerance = 2e-5 if method == "qp" else 1e-9        # qp meets attainable requests to OSQP's tolerance
    unattainable = 0
    for tau in requests():
        scale = largest_attainable_scale(t, low, high, tau)
        result = Allocator(vehicle, method=method).allocate(tau)
        size = np.max(np.abs(tau))
        assert result.achieved == pytest.approx(min(scale, 1.0) * tau, abs=tolerance * size)
        assert np.all(result.thrust >= low - 1e-9) and np.all(result.thrust <= high + 1e-9)
        assert result.saturated == (scale < 1.0 - 1e-3)
        if scale < 1.0:
            unattainable += 1
            assert result.status.startswith("direct: lambda")
            assert float(result.status.split()[-1]) == pytest.approx(scale, rel=1e-5)
    assert 30 <= unattainable <= 100


def test_on_the_boundary_the_solution_is_durhams_unique_vertex():
    """Eight thrusters in general position (random directions and positions, so that every six
    columns of T are independent): on the boundary n - 1 = 5 actuators are strictly inside
    their limits and the others at one, and no other forces give the same scale (an LP that
    maximises the distance from the answer along the boundary face finds none)."""
    rng = np.random.default_rng(11)
    overrides = {}
    for i in range(1, 9):
        overrides[f"actuators__t{i}__direction"] = list(rng.normal(size=3))
        overrides[f"actuators__t{i}__position"] = list(rng.uniform(-0.3, 0.3, size=3))
    vehicle = vehicle_from(EIGHT, saturation="direct", **overrides)
    t, low, high = matrices(vehicle)
    for tau in requests(10)[2::3]:
        scale = largest_attainable_scale(t, low, high, tau)
        assert scale < 1.0
        result = Allocator(vehicle, method="pseudoinverse").allocate(tau)
        inside = (result.thrust > low + 1e-7) & (result.thrust < high - 1e-7)
        assert np.sum(inside) == len(vehicle.dofs) - 1
        for sign in (1.0, -1.0):
            other = linprog(-sign * np.eye(8)[int(np.argmax(inside))], A_eq=t, b_eq=scale * tau,
                            bounds=list(zip(low, high)), method="highs")
            assert other.x == pytest.approx(result.thrust, abs=1e-6)


def test_an_attainable_request_keeps_the_minimum_norm_answer():
    vehicle = vehicle_from(EIGHT, saturation="direct")
    t, _, _ = matrices(vehicle)
    tau = np.array([10.0, -5.0, 8.0, 1.0, -0.5, 2.0])
    minimum_norm = weighted_pseudo_inverse(t, np.ones(8)) @ tau
    for method in ("pseudoinverse", "qp"):
        result = Allocator(vehicle, method=method).allocate(tau)
        assert not result.saturated and result.status == "solved"
        assert result.thrust == pytest.approx(minimum_norm, abs=1e-3)


def test_preserve_direction_reaches_less_far_than_direct():
    """The pseudo-inverse's preserve_direction scales its own answer until its most loaded
    actuator is at a limit; direct goes to the boundary of the attainable set. qp's
    preserve_direction approximates the boundary with a QP to OSQP's tolerance."""
    t, low, high = matrices(vehicle_from(EIGHT))
    shortfall, qp_miss = [], []
    for tau in requests(20)[2::3]:
        scale = largest_attainable_scale(t, low, high, tau)
        direct = Allocator(vehicle_from(EIGHT, saturation="direct"), method="pseudoinverse").allocate(tau)
        preserve = Allocator(vehicle_from(EIGHT, saturation="preserve_direction"), method="pseudoinverse").allocate(tau)
        reached = [float(np.dot(r.achieved, tau) / np.dot(tau, tau)) for r in (direct, preserve)]
        assert reached[0] == pytest.approx(scale, abs=1e-9)
        assert reached[1] <= reached[0] + 1e-9
        shortfall.append(reached[0] - reached[1])
        qp = Allocator(vehicle_from(EIGHT, saturation="preserve_direction"), method="qp").allocate(tau)
        qp_miss.append(abs(float(np.dot(qp.achieved, tau) / np.dot(tau, tau)) - scale))
    assert np.mean(shortfall) > 0.05
    assert max(qp_miss) < 1e-2


@pytest.mark.parametrize("method", DIRECT)
def test_with_azimuths_the_scale_is_the_circles_to_the_polygons_error_and_the_direction_is_kept(method):
    """Example 1 without rate limits: lambda* from the inscribed 32-gon is within
    1 - cos(pi/32) of the circle's (Capability, an independent LP on a 256-gon), and no thrust
    is clipped, so the achieved wrench is parallel to the request."""
    free = {f"actuators__{name}__{key}": 0.0 for name in ("azimuth_fwd", "azimuth_aft")
            for key in ("azimuth_rate_max", "thrust_rate_max")}
    free.update({f"actuators__{name}__thrust_rate_max": 0.0 for name in ("main_port", "main_stbd")})
    vehicle = vehicle_from(ROOT / "config" / "example1_rov.yaml", saturation="direct", **free)
    capability = Capability(vehicle, method="nonlinear")
    for angle in np.radians(np.arange(0.0, 360.0, 30.0)):
        tau = np.array([2000.0 * math.cos(angle), 2000.0 * math.sin(angle), 0.0, 0.0, 0.0, 100.0])
        allocator = Allocator(vehicle, method=method)
        for _ in range(3):
            result = allocator.allocate(tau)
        reached = float(np.dot(result.achieved[[0, 1, 5]], tau[[0, 1, 5]]) / np.dot(tau, tau))
        circle = capability.scale(tau)
        assert circle < 1.0
        assert circle * (1.0 - (1.0 - math.cos(math.pi / 32)) - 1e-6) <= reached <= circle + 1e-6
        rows = list(vehicle.dof_indices)
        assert result.achieved[rows] == pytest.approx(reached * tau[rows], abs=1e-6 * 2000.0)
