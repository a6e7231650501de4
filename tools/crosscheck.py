"""Every output of every sample over vehicles x methods x faults, digested, so that two trees
can be compared bit for bit (a refactoring must leave them identical).

    python tools/crosscheck.py --out build/crosscheck/new.json
    PYTHONPATH=/path/to/other/tree python tools/crosscheck.py --out build/crosscheck/old.json
    python tools/crosscheck.py --compare build/crosscheck/old.json build/crosscheck/new.json

Each case is one shipped or test vehicle under one method that serves it, at one sample time,
driven by a seeded request sequence with faults (degraded, failed, stuck), a clear, speed and
voltage changes and a weights reconfiguration along the way. The digest covers every field of
every sample's result (arrays by their bytes, text as written) and the allocator's counters.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
from dataclasses import fields, replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
VEHICLES = sorted(p for p in (ROOT / "config").glob("*.yaml") if p.name != "default.yaml") + sorted(
    (ROOT / "test" / "data").glob("*.yaml"))
SAMPLES = 400


def _digest_value(h, value) -> None:
    if isinstance(value, np.ndarray):
        h.update(str(value.dtype).encode())
        h.update(np.ascontiguousarray(value).tobytes())
    elif isinstance(value, float):
        h.update(np.float64(value).tobytes())
    elif hasattr(value, "value") and hasattr(value, "name"):   # an enum
        h.update(str(value.value).encode())
    else:
        h.update(repr(value).encode())


def _result_fields(result) -> list[str]:
    """The fields of a result, by name, without the wall-clock ones."""
    names = [f.name for f in fields(result)]
    return [name for name in names if name != "solve_time"]


def run_case(vehicle_path: Path, method: str, dt: float, seed: int) -> dict:
    from allocator_pkg import Allocator, FaultMode, load_vehicle

    vehicle = load_vehicle(vehicle_path)
    try:
        alloc = Allocator(vehicle, method=method, dt=dt)
    except ValueError as error:
        return {"skipped": str(error)}
    rng = np.random.default_rng(seed)
    low, high = alloc.ranges
    scale = float(np.sum(np.maximum(np.abs(low), np.abs(high)))) / max(len(low), 1)
    arms = np.array([1.0, 1.0, 1.0, 0.5, 0.5, 1.0])
    names = vehicle.names
    rotatable = [a.name for a in vehicle.actuators if a.rotatable]
    h = hashlib.sha256()
    per_sample = []
    tau = np.zeros(6)
    for k in range(SAMPLES):
        if k % 25 == 0:
            tau = rng.normal(size=6) * scale * arms * rng.choice([0.2, 1.0, 3.0])
        elif k % 5 == 0:
            tau = tau + rng.normal(size=6) * scale * 0.05
        if k == 60 and len(names) > 1:
            alloc.set_fault(names[0], FaultMode.DEGRADED, efficiency=0.5)
        if k == 120 and len(names) > 2:
            alloc.set_fault(names[1], FaultMode.FAILED)
        if k == 170 and rotatable:
            alloc.set_fault(rotatable[-1], FaultMode.STUCK, angle=float(alloc.azimuth[names.index(rotatable[-1])]))
        if k == 220:
            alloc.clear_faults()
        if k == 250 and vehicle.has_surfaces:
            alloc.set_speed(1.5)
        if k == 280 and vehicle.voltage_range is not None:
            alloc.set_voltage(0.5 * (vehicle.voltage_range[0] + vehicle.voltage_range[1]))
        if k == 300:
            weights = replace(vehicle.weights, minimax=vehicle.weights.minimax + 1.0)
            alloc.reconfigure(replace(vehicle, weights=weights))
        if k == 350:
            alloc.stop()
        if vehicle.has_surfaces and k == 0:
            alloc.set_speed(2.0)
        result = alloc.allocate(tau)
        hs = hashlib.sha256()
        for name in _result_fields(result):
            _digest_value(hs, getattr(result, name))
        digest = hs.hexdigest()
        per_sample.append(digest[:16])
        h.update(digest.encode())
    stats = alloc.stats
    return {"digest": h.hexdigest(), "samples": per_sample,
            "stats": [stats.solver_setups, stats.samples, stats.fallbacks]}


def run_all() -> dict:
    from allocator_pkg import METHODS

    cases = {}
    for path in VEHICLES:
        for method in METHODS:
            for dt in (None, 0.01):
                key = f"{path.relative_to(ROOT)}|{method}|{dt}"
                cases[key] = run_case(path, method, dt, seed=len(cases))
                print(key, cases[key].get("digest", "skipped")[:16], file=sys.stderr)
    return cases


def compare(old_path: Path, new_path: Path) -> int:
    """Print every case whose samples, counters or run/skip state differ (exit 1 if any), and
    count the refusals only reworded."""
    old, new = json.loads(old_path.read_text()), json.loads(new_path.read_text())
    bad = reworded = 0
    for key in sorted(set(old) | set(new)):
        a, b = old.get(key), new.get(key)
        if a is None or b is None:
            print(f"{key}: only in {'new' if a is None else 'old'}")
            bad += 1
        elif "skipped" in a and "skipped" in b:
            reworded += a["skipped"] != b["skipped"]
        elif a.get("digest") != b.get("digest") or a.get("stats") != b.get("stats"):
            first = next((k for k, (x, y) in enumerate(zip(a.get("samples", []), b.get("samples", []))) if x != y),
                         None)
            print(f"{key}: differs (first sample {first}, stats {a.get('stats')} -> {b.get('stats')}, "
                  f"skipped {a.get('skipped')!r} -> {b.get('skipped')!r})")
            bad += 1
    ran = sum("digest" in case for case in new.values())
    print(f"{len(new)} cases ({ran} run, {len(new) - ran} refused): {bad} differ; {reworded} refusals reworded")
    return 1 if bad else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path)
    parser.add_argument("--compare", nargs=2, type=Path, metavar=("OLD", "NEW"))
    args = parser.parse_args()
    if args.compare:
        return compare(*args.compare)
    cases = run_all()
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(cases, indent=0, sort_keys=True))
    return 0


if __name__ == "__main__":
    sys.exit(main())
