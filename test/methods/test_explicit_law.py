"""The piecewise-affine law of (1.35), survey 4.1: one active set's forces and checks against an
independent optimum (scipy's BVLS), the step to a neighbouring set, the minimax rows, and the
regions file. The method that uses the law is tested in test_explicit.py."""

import numpy as np
import pytest
from conftest import DATA, ROOT, matrices, vehicle_from
from reference import bounded_least_squares

from allocator_pkg import Allocator, load_vehicle
from allocator_pkg.methods.explicit_law import Law, read_regions

BLUEROV = ROOT / "config" / "bluerov2_heavy.yaml"
EIGHT = DATA / "eight_thrusters.yaml"


def setting(path, **overrides):
    """The vehicle's law, T, W, Q and configured force ranges."""
    vehicle = vehicle_from(path, **overrides) if overrides else load_vehicle(path)
    model = Allocator(vehicle, method="explicit").model
    t, w, low, high = matrices(vehicle)
    return Law(model), t, w, model.slack_weights(w), low, high


def parameters(tau, low, high):
    """p_1 = [tau, f_min, f_max, 1]."""
    return np.concatenate((tau, low, high, [1.0]))


def bounds_key(force, low, high, tolerance=0.0):
    """The active set of box bounds where ``force`` sits (within ``tolerance``): bit 2i its
    upper, 2i + 1 its lower."""
    return sum(1 << 2 * i for i in np.flatnonzero(force >= high - tolerance)) + \
        sum(1 << 2 * i + 1 for i in np.flatnonzero(force <= low + tolerance))


@pytest.mark.parametrize("path", [BLUEROV, EIGHT])
def test_the_region_of_the_optimums_active_set_gives_the_optimum_and_holds_it(path):
    """Random requests (mostly saturating) and random bounds inside the ranges: the law of the
    active set BVLS ends on gives BVLS's forces, and every check of that region holds."""
    law, t, w, q, low, high = setting(path)
    rng = np.random.default_rng(11)
    saturated = 0
    for _ in range(40):
        a, b = rng.uniform(low, high), rng.uniform(low, high)
        lo, hi = np.minimum(a, b), np.maximum(a, b)
        tau = rng.uniform(-1.0, 1.0, t.shape[0]) * (np.abs(t) @ np.maximum(high, -low))
        expected = bounded_least_squares(t, w, q, lo, hi, tau)
        key = bounds_key(expected, lo, hi, 1e-9 * np.max(high))
        saturated += key != 0
        region = law.region(key)
        out = region.matrix @ parameters(tau, lo, hi)
        assert out[:law.r] == pytest.approx(expected, abs=1e-6 * np.max(high))
        assert np.max(out[law.r:]) <= 0.0
    assert saturated > 10


def test_a_violated_bound_is_the_step_to_the_neighbouring_set():
    """From the set with nothing active, a request that drives forces past their bounds: the
    full step adds every violated bound, the single step only the most violated one (in units
    of each actuator's range)."""
    law, t, _, _, low, high = setting(BLUEROV)
    tau = 2.0 * t @ high
    region = law.region(0)
    out = region.matrix @ parameters(tau, low, high)
    force, checks = out[:law.r], out[law.r:].tolist()
    expected = bounds_key(force, low, high)
    assert expected != 0
    assert region.neighbour(checks) == (expected, expected)
    excess = np.maximum(force - high, low - force) / np.maximum(high, -low)
    i = int(np.argmax(excess))
    row = 2 * i if force[i] > high[i] else 2 * i + 1
    assert region.neighbour(checks, single=True) == (1 << row, 1 << row)


def test_with_a_minimax_weight_a_set_needs_a_minimax_row():
    """With beta > 0 nothing bounds fbar from below without a minimax row: no law. With the row
    of the largest force the law meets the request that force came from."""
    law, t, w, q, low, high = setting(BLUEROV, weights__minimax=10.0)
    assert law.minimax and law.region(0) is None
    tau = 0.2 * t @ high
    force = bounded_least_squares(t, w, q, low, high, tau)
    region = law.region(law.largest(force))
    assert region is not None
    assert t @ (region.matrix @ parameters(tau, low, high))[:law.r] == pytest.approx(tau, rel=1e-3, abs=1e-3)


def test_a_regions_file_is_read_for_its_own_data_only(tmp_path):
    law, *_ = setting(BLUEROV)
    other, *_ = setting(BLUEROV, actuators__thruster_1__weight=2.0)
    good = tmp_path / "good.npz"
    np.savez(good, keys=np.array([0, 1, 4]), fingerprint=np.array(law.fingerprint))
    assert read_regions(str(good), law) == [0, 1, 4]
    with pytest.raises(ValueError, match="computed for another configuration"):
        read_regions(str(good), other)
    array = tmp_path / "array.npy"
    np.save(array, np.arange(3))
    corrupt = tmp_path / "corrupt.npz"
    corrupt.write_bytes(b"PK\x03\x04 not a zip archive")
    keyless = tmp_path / "keyless.npz"
    np.savez(keyless, values=np.arange(3))
    for path, reason in ((array, "not an .npz archive"), (corrupt, "cannot read"), (keyless, "no fingerprint"),
                         (tmp_path / "missing.npz", "cannot read")):
        with pytest.raises(ValueError, match=reason):
            read_regions(str(path), law)
