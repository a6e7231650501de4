"""The explicit method (1.35), survey 4.1: exact against independent solvers (scipy's BVLS,
quadprog with the minimax term), and its cache of laws (hits, neighbours, faults, speed, rate
limits, reconfiguration, a bounded size). The law itself: test_explicit_law.py. No timing
here: `make bench` times it."""

from dataclasses import replace

import numpy as np
import pytest
from conftest import DATA, ROOT, vehicle_from
from reference import constrained_allocation
from scipy.optimize import lsq_linear

from allocator_pkg import Allocator, ConfigError, FaultMode, load_vehicle
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.cli import allocator_explicit as explicit_tool
from allocator_pkg.effectiveness.configuration_matrix import configuration_matrix
from allocator_pkg.effectiveness.model import SampleLimits
from allocator_pkg.methods.explicit import ExplicitAllocation
from allocator_pkg.solvers import BACKENDS

BLUEROV = ROOT / "config" / "bluerov2_heavy.yaml"
OTTER = ROOT / "config" / "otter_usv.yaml"
INFANTE = ROOT / "config" / "infante_auv.yaml"
EIGHT = DATA / "eight_thrusters.yaml"
RELATIVE = 1e-6
"""The objective of (1.35) within this fraction of the independent optimum's."""


def problem(vehicle, speed=0.0):
    """T (controlled rows, T(alpha) at zero angles: fixed directions), W, Q and the static
    force ranges of ``vehicle``, from the configuration alone (surfaces: lift at ``speed``)."""
    allocator = Allocator(vehicle, method="explicit")
    allocator.set_speed(speed)
    t = configuration_matrix(vehicle.actuators, np.zeros(len(vehicle.actuators)))[list(vehicle.dof_indices)]
    w = np.array([a.weight for a in vehicle.actuators])
    model = allocator.model
    q = model.slack_weights(w)
    low, high = allocator._limits.low.copy(), allocator._limits.high.copy()
    return t, w, q, low, high


def bvls(t, w, q, low, high, tau):
    """(1.35) with beta = 0 is bounded least squares: min |W^1/2 f|^2 + |Q^1/2 (T f - tau)|^2
    over low <= f <= high, solved by scipy's BVLS (forces whose bounds meet are fixed there)."""
    fixed = high - low <= 0.0
    f = np.where(fixed, low, 0.0)
    free = ~fixed
    design = np.vstack((np.diag(np.sqrt(w[free])), np.sqrt(q)[:, None] * t[:, free]))
    target = np.concatenate((np.zeros(free.sum()), np.sqrt(q) * (tau - t @ f)))
    f[free] = lsq_linear(design, target, bounds=(low[free], high[free]), method="bvls", tol=1e-15).x
    return f


def objective(t, w, q, f, tau, beta=0.0):
    s = t @ f - tau
    return float(f @ (w * f) + s @ (q * s) + beta * np.max(np.abs(f)))


def limits(low, high, version=-1):
    r = len(low)
    return SampleLimits(low, high, np.zeros(0, int), [], np.zeros(r), np.zeros(r), version)


def requests(vehicle, count, scale, seed):
    """Random requests on the controlled DOFs up to ``scale`` times each DOF's authority."""
    model = Allocator(vehicle, method="explicit").model
    rng = np.random.default_rng(seed)
    return model.authority * rng.uniform(-scale, scale, size=(count, model.n))


@pytest.mark.parametrize("path, speed", [(BLUEROV, 0.0), (EIGHT, 0.0), (OTTER, 0.0), (INFANTE, 2.0)])
@pytest.mark.parametrize("scale", [0.3, 1.5])                    # mostly attainable; saturating
def test_the_objective_equals_bounded_least_squares_with_the_bounds_as_parameters(path, speed, scale):
    """Random bounds inside the static ranges each sample (as rate limits and faults make them):
    the law takes them as parameters, and every answer is the BVLS optimum."""
    vehicle = load_vehicle(path)
    t, w, q, low, high = problem(vehicle, speed)
    method = ExplicitAllocation(Allocator(vehicle).model, BACKENDS["osqp"])
    rng = np.random.default_rng(1)
    for tau in requests(vehicle, 60, scale, seed=2):
        a, b = rng.uniform(low, high), rng.uniform(low, high)
        lo, hi = np.minimum(a, b), np.maximum(a, b)
        if rng.random() < 0.5:                                      # the static range, often
            lo, hi = low, high
        output = method.solve(tau, limits(lo, hi))
        expected = bvls(t, w, q, lo, hi, tau)
        assert output.usable and "no exact region" not in output.status
        slack = 1e-8 * np.maximum(high, -low)
        assert np.all(output.force >= lo - slack) and np.all(output.force <= hi + slack)
        reference = objective(t, w, q, expected, tau)
        assert objective(t, w, q, output.force, tau) == pytest.approx(reference, rel=RELATIVE)
    assert method.inexact == 0


def test_the_allocator_with_explicit_meets_bvls_on_random_and_saturating_requests():
    vehicle = load_vehicle(BLUEROV)
    t, w, q, low, high = problem(vehicle)
    allocator = Allocator(vehicle, method="explicit")
    for tau in np.vstack((requests(vehicle, 40, 0.4, seed=3), requests(vehicle, 40, 2.0, seed=4))):
        result = allocator.allocate(tau)
        expected = bvls(t, w, q, low, high, tau)
        assert objective(t, w, q, result.thrust, tau) == pytest.approx(objective(t, w, q, expected, tau),
                                                                       rel=RELATIVE)
        assert result.thrust == pytest.approx(expected, abs=1e-6 * np.max(high))


@pytest.mark.parametrize("path, speed", [(EIGHT, 0.0), (OTTER, 0.0), (INFANTE, 2.0)])
def test_the_minimax_term_matches_an_independent_qp(path, speed):
    """beta fbar of (1.35), against quadprog's dual active-set method; requests of zero too
    (every minimax row active at once: a degenerate point)."""
    beta = 10.0
    vehicle = vehicle_from(path, weights__minimax=beta)
    t, w, q, low, high = problem(vehicle, speed)
    method = ExplicitAllocation(Allocator(vehicle).model, BACKENDS["osqp"])
    taus = np.vstack((requests(vehicle, 30, 0.4, seed=5), requests(vehicle, 30, 1.5, seed=6),
                      np.zeros((2, t.shape[0]))))
    for tau in taus:
        output = method.solve(tau, limits(low, high))
        expected = constrained_allocation(t, w, q, low, high, tau, beta=beta)
        reference = objective(t, w, q, expected, tau, beta)
        assert objective(t, w, q, output.force, tau, beta) == pytest.approx(reference, rel=RELATIVE, abs=1e-9)
    assert method.inexact == 0


def test_a_repeated_region_is_a_hit_and_computes_no_law():
    """The method starts in the region where no limit is active; a saturating request moves it
    to another, and the same request again is a hit there."""
    allocator = Allocator(load_vehicle(BLUEROV), method="explicit")
    method = allocator._solver.method
    assert allocator.allocate([10.0, 5.0, -3.0, 0.2, 0.1, 0.5]).status == "hit; regions 1, hits 1/1"
    first = allocator.allocate([150.0, 5.0, -3.0, 0.2, 0.1, 0.5])
    built = method.built
    again = allocator.allocate([150.0, 5.0, -3.0, 0.2, 0.1, 0.5])
    assert not first.status.startswith("hit") and again.status == "hit; regions 2, hits 2/3"
    assert method.built == built and method._region.key != 0


def test_a_failure_leaves_the_laws_and_moves_to_the_region_where_the_actuator_is_at_zero():
    """FAILED makes an actuator's bounds zero: a value change. The previous region's checks fail
    (the actuator is free in it), a neighbour has it at a bound, and the answer is the optimum
    without it. Cleared, the moves lead back to the first region, from the cache."""
    vehicle = load_vehicle(BLUEROV)
    t, w, q, low, high = problem(vehicle)
    allocator = Allocator(vehicle, method="explicit")
    method = allocator._solver.method
    tau = np.array([20.0, 10.0, -5.0, 0.5, 0.2, 1.0])
    allocator.allocate(tau)
    nominal = method._region.key
    allocator.set_fault("thruster_1", FaultMode.FAILED)
    result = allocator.allocate(tau)
    assert result.status.startswith("neighbour") and result.thrust[0] == 0.0
    low[0] = high[0] = 0.0
    expected = bvls(t, w, q, low, high, tau)
    assert objective(t, w, q, result.thrust, tau) == pytest.approx(objective(t, w, q, expected, tau), rel=RELATIVE)
    assert allocator.allocate(tau).status.startswith("hit")
    allocator.clear_faults()
    result = allocator.allocate(tau)
    assert result.status.startswith("neighbour") and method._region.key == nominal and method.regions == 2
    assert allocator.stats.solver_setups == 1


def test_a_new_speed_and_a_new_efficiency_change_values_only():
    """Speed scales a control surface's bounds, DEGRADED a thruster's: the laws stay. At a new
    speed the request stays in its region (every sample a hit); a thruster degraded below what
    the request needs of it moves to the region with it at its bound, and another efficiency
    keeps it there, at the new bound. Each answer is the optimum for the request with the
    surfaces' drag added to surge (1.56)-(1.58)."""
    vehicle = load_vehicle(INFANTE)
    allocator = Allocator(vehicle, method="explicit")
    allocator.set_speed(2.0)
    method = allocator._solver.method
    tau = np.zeros(6)
    tau[[0, 5]] = [500.0, 400.0]

    def settle():
        for _ in range(100):                                            # through the rate limits
            result = allocator.allocate(tau)
        t, w, q, _, _ = problem(vehicle, allocator.speed)
        low, high = allocator._limits.low, allocator._limits.high
        compensated = tau.copy()
        compensated[0] += result.drag
        expected = bvls(t, w, q, low, high, compensated[list(vehicle.dof_indices)])
        assert result.thrust == pytest.approx(expected, abs=1e-6 * np.max(high))
        return result

    settle()
    free = method._region.key
    hits = method.hits
    allocator.set_speed(2.5)
    settle()
    assert method._region.key == free and method.hits == hits + 200      # two solves a sample (drag)
    allocator.set_fault("thruster_port", FaultMode.DEGRADED, efficiency=0.5)
    assert settle().thrust[0] == pytest.approx(200.0)
    bound = method._region.key
    hits = method.hits
    allocator.set_fault("thruster_port", FaultMode.DEGRADED, efficiency=0.6)
    assert settle().thrust[0] == pytest.approx(240.0)
    assert method._region.key == bound != free


def test_a_new_battery_voltage_changes_values_only_and_stays_exact():
    """The voltage moves the thrust limits of the BlueROV2's T200 curves, parameters of the law:
    a request inside the ranges at every voltage keeps its region with no law computed, and
    every answer, saturating or not, is BVLS's at the ranges of that voltage."""
    vehicle = load_vehicle(BLUEROV)
    t, w, q, _, _ = problem(vehicle)
    allocator = Allocator(vehicle, method="explicit")
    method = allocator._solver.method
    held = requests(vehicle, 1, 0.1, seed=7)[0]
    allocator.allocate(held)
    region = method._region.key
    tops = []
    for volts in (20.0, 12.0, 14.5):
        built = method.built
        allocator.set_voltage(volts)
        allocator.allocate(held)
        assert method._region.key == region and method.built == built
        low, high = allocator._limits.low.copy(), allocator._limits.high.copy()
        tops.append(high[0])
        for tau in requests(vehicle, 30, 1.2, seed=int(volts)):
            result = allocator.allocate(tau)
            expected = bvls(t, w, q, low, high, tau)
            assert objective(t, w, q, result.thrust, tau) == pytest.approx(objective(t, w, q, expected, tau),
                                                                           rel=RELATIVE)
    assert tops[1] < tops[2] < tops[0]


def test_rate_limits_are_parameters_every_sample():
    """The Otter's thrust rate limit (slowed to 120 N/s, so that the ramp below is held at it)
    moves both bounds every sample; a ramp held at the rate limit stays in one region (a hit each
    sample) and each answer is the optimum within that sample's bounds, computed here from the
    previous thrust."""
    vehicle = vehicle_from(OTTER, actuators__propeller_port__thrust_rate_max=120.0,
                           actuators__propeller_stbd__thrust_rate_max=120.0)
    t, w, q, low, high = problem(vehicle)
    allocator = Allocator(vehicle, method="explicit")
    step = np.array([a.thrust_rate_max for a in vehicle.actuators]) * allocator.dt
    previous = np.zeros(2)
    statuses = []
    for k in range(60):
        tau = np.zeros(6)
        tau[[0, 5]] = [200.0 * min(1.0, k / 20.0), 30.0]
        result = allocator.allocate(tau)
        lo = np.clip(previous - step, low, high)
        hi = np.clip(previous + step, low, high)
        expected = bvls(t, w, q, lo, hi, tau[[0, 5]])
        assert result.thrust == pytest.approx(expected, abs=1e-9 * np.max(high))
        previous = result.thrust
        statuses.append(result.status.split(";")[0])
    assert statuses[1:3] == ["hit"] * 2 and statuses[4:] == ["hit"] * 56     # a rate bound, then the thrust limit


def test_the_cache_is_bounded_and_the_answers_stay_exact():
    vehicle = load_vehicle(BLUEROV)
    t, w, q, low, high = problem(vehicle)
    method = ExplicitAllocation(Allocator(vehicle).model, BACKENDS["osqp"], capacity=3)
    for tau in requests(vehicle, 40, 2.0, seed=7):
        output = method.solve(tau, limits(low, high, version=0))
        assert method.regions <= 3
        expected = bvls(t, w, q, low, high, tau)
        assert objective(t, w, q, output.force, tau) == pytest.approx(objective(t, w, q, expected, tau), rel=RELATIVE)
    assert method.built > 3


def test_reconfiguration_keeps_the_laws_for_new_limits_and_clears_them_for_new_weights():
    """Limits are parameters; W and Q are data. (The default Q follows the force ranges, so
    with it a new thrust_max is new data too: weights.slack is set here.)"""
    vehicle = vehicle_from(BLUEROV, weights__slack=[1e7] * 6)
    allocator = Allocator(vehicle, method="explicit")
    method = allocator._solver.method
    for tau in requests(vehicle, 10, 1.0, seed=8):
        allocator.allocate(tau)
    regions = method.regions
    allocator.reconfigure(vehicle_from(BLUEROV, weights__slack=[1e7] * 6, actuators__thruster_1__thrust_max=40.0))
    assert method.regions == regions
    allocator.reconfigure(vehicle_from(BLUEROV, weights__slack=[1e7] * 6, actuators__thruster_1__weight=2.0))
    assert method.regions == 1 and method._region.key == 0              # cleared; the start region again
    t, w, q, low, high = problem(allocator.vehicle)
    tau = requests(vehicle, 1, 1.0, seed=9)[0]
    expected = bvls(t, w, q, low, high, tau)
    assert allocator.allocate(tau).thrust == pytest.approx(expected, abs=1e-6 * np.max(high))
    assert allocator.stats.solver_setups == 1


def test_rotatable_thrusters_and_saturations_other_than_weighted_are_refused_by_name():
    with pytest.raises(ConfigError, match=r"method: 'explicit' cannot serve this vehicle: it needs actuators of "
                                          r"fixed direction \(survey 4.1\), and azimuth_fwd, azimuth_aft rotate"):
        Allocator(vehicle_from(ROOT / "config" / "example1_rov.yaml", method="explicit"))
    with pytest.raises(ValueError, match="azimuth_fwd, azimuth_aft rotate"):
        Allocator(load_vehicle(ROOT / "config" / "example1_rov.yaml"), method="explicit")
    for saturation in ("preserve_direction", "direct"):
        with pytest.raises(ConfigError, match=f"it does not implement saturation '{saturation}' "
                                              r"\(it takes weighted\)"):
            Allocator(vehicle_from(BLUEROV, method="explicit", saturation=saturation))
    with pytest.raises(ConfigError, match=r"method: 'explicit' cannot serve this vehicle: .* rotate"):
        Capability(load_vehicle(ROOT / "config" / "example1_rov.yaml"), method="explicit")


def test_the_status_and_diagnostics_report_regions_and_hit_rate():
    from std_msgs.msg import Header

    from allocator_pkg.ros.conversions import status_message
    from allocator_pkg.ros.diagnostics import Counters, allocation_status

    allocator = Allocator(load_vehicle(BLUEROV), method="explicit")
    for _ in range(3):
        result = allocator.allocate([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert status_message(result, result.status, Header()).solver_status == "hit; regions 1, hits 3/3"
    counters = Counters()
    counters.count(result)
    values = {kv.key: kv.value for kv in allocation_status("/n", allocator, counters, False, result).values}
    assert values["solver status"] == "hit; regions 1, hits 3/3" and values["fallbacks in period"] == "0"


def test_a_smooth_sequence_stays_in_few_regions():
    """A controller's slowly turning request (the benchmark's smooth sequence): almost every
    sample a hit."""
    vehicle = load_vehicle(BLUEROV)
    allocator = Allocator(vehicle, method="explicit")
    turn = np.linspace(0.0, 2.0 * np.pi, 500)
    for angle in turn:
        allocator.allocate([40.0 * np.cos(angle), 40.0 * np.sin(angle), 10.0 * np.sin(3 * angle), 0.0, 0.0,
                            5.0 * np.sin(2 * angle)])
    method = allocator._solver.method
    assert method.hits >= 0.95 * method.calls and method.solved <= 2


def test_precompute_finds_the_otters_nine_regions_and_the_allocator_loads_them(tmp_path, capsys):
    """Two thrusters, surge and yaw: T is square and invertible, so any forces are the optimum
    of some request, each thruster free or at either bound: 3 x 3 regions. Loaded, the moves
    between them need no law computed while allocating."""
    out = tmp_path / "otter.regions.npz"
    assert explicit_tool.main(["precompute", str(OTTER), "--out", str(out)]) == 0
    assert "9 regions of 9 active sets" in capsys.readouterr().out
    vehicle = vehicle_from(OTTER, method="explicit", explicit__regions=str(out))
    allocator = Allocator(vehicle)
    method = allocator._solver.method
    assert len(method.table) == 9 and method.regions == 9
    for request in requests(vehicle, 100, 2.0, seed=10):
        tau = np.zeros(6)
        tau[[0, 5]] = request
        allocator.allocate(tau)
    assert method.built == 0 and method.solved == 0 and len(method.laws) == 0


def test_a_regions_file_for_other_data_and_vehicles_it_cannot_enumerate_are_refused(tmp_path, capsys):
    out = tmp_path / "otter.regions.npz"
    explicit_tool.main(["precompute", str(OTTER), "--out", str(out)])
    with pytest.raises(ConfigError, match="was computed for another configuration"):
        Allocator(vehicle_from(OTTER, method="explicit", explicit__regions=str(out),
                               actuators__propeller_port__weight=2.0))
    with pytest.raises(ConfigError, match=r"explicit\.regions: .*No such file"):
        Allocator(vehicle_from(OTTER, method="explicit", explicit__regions=str(tmp_path / "missing.npz")))
    capsys.readouterr()
    assert explicit_tool.main(["precompute", str(ROOT / "config" / "dp_vessel.yaml"), "--out", str(out)]) == 1
    assert "azimuth_stbd, azimuth_port rotate" in capsys.readouterr().err
    minimax = tmp_path / "minimax.yaml"
    minimax.write_text(OTTER.read_text().replace("ros__parameters:", "ros__parameters:\n    weights: {minimax: 1.0}"))
    assert explicit_tool.main(["precompute", str(minimax), "--out", str(out)]) == 1
    assert "the enumeration covers beta = 0" in capsys.readouterr().err


def test_files_that_are_no_regions_file_are_refused_with_a_clear_error(tmp_path):
    array = tmp_path / "array.npy"
    np.save(array, np.arange(3))
    corrupt = tmp_path / "corrupt.npz"
    corrupt.write_bytes(b"PK\x03\x04 not a zip archive")
    other = tmp_path / "other.npz"
    np.savez(other, values=np.arange(3))
    for path, reason in ((array, "not an .npz archive"), (corrupt, "cannot read"), (other, "no fingerprint")):
        with pytest.raises(ConfigError, match=f"explicit.regions: .*{reason}"):
            Allocator(vehicle_from(OTTER, method="explicit", explicit__regions=str(path)))


def test_precompute_writes_the_file_the_configuration_names_even_when_missing_or_stale(tmp_path):
    out = tmp_path / "otter.regions.npz"
    config = tmp_path / "otter.yaml"
    config.write_text(OTTER.read_text().replace("method: qp", f"method: explicit\n    explicit: {{regions: {out}}}", 1))
    assert explicit_tool.main(["precompute", str(config), "--out", str(out)]) == 0          # missing
    assert len(Allocator(load_vehicle(config))._solver.method.table) == 9
    heavier = "ros__parameters:\n    weights: {slack: [1e3, 1e3]}"
    config.write_text(config.read_text().replace("ros__parameters:", heavier, 1))
    with pytest.raises(ConfigError, match="computed for another configuration"):
        Allocator(load_vehicle(config))
    assert explicit_tool.main(["precompute", str(config), "--out", str(out)]) == 0          # stale
    assert len(Allocator(load_vehicle(config))._solver.method.table) == 9


def test_reconfiguration_refuses_what_the_method_cannot_serve_and_drops_a_cached_method_that_cannot(tmp_path):
    """With a regions file: after a switch to qp, a change of Q makes the cached explicit's
    file stale; the allocator drops it and keeps working, and switching back to explicit with
    the stale file is refused whole, the running configuration unchanged."""
    out = tmp_path / "otter.regions.npz"
    explicit_tool.main(["precompute", str(OTTER), "--out", str(out)])
    tau = np.array([300.0, 0.0, 0.0, 0.0, 0.0, 100.0])
    vehicle = vehicle_from(OTTER, method="explicit", explicit__regions=str(out))
    allocator = Allocator(vehicle)
    with pytest.raises(ValueError, match="it does not implement saturation 'direct'"):
        allocator.reconfigure(replace(vehicle, saturation="direct"))
    assert allocator.vehicle is vehicle
    allocator.reconfigure(replace(vehicle, method="qp"))
    assert set(allocator._solver.methods) == {"explicit", "qp"}
    heavier = replace(vehicle, method="qp", weights=replace(vehicle.weights, slack=(1e3, 1e3)))
    allocator.reconfigure(heavier)
    assert set(allocator._solver.methods) == {"qp"}
    with pytest.raises(ValueError, match="computed for another configuration"):
        allocator.reconfigure(replace(heavier, method="explicit"))
    assert allocator.vehicle is heavier and allocator.method == "qp"
    reference = Allocator(heavier)
    for _ in range(200):                                            # through the rate limits
        result, expected = allocator.allocate(tau), reference.allocate(tau)
    assert result.thrust == pytest.approx(expected.thrust, abs=1e-3)
