"""docs/priorities.png: what DOF priorities change, on the BlueROV2 Heavy at 12 V.

One request direction (heave down with a roll and a pitch moment, yaw, surge and sway) scaled
from half to three times what the thrusters can give along it (``Capability.reach``). For each
scale, the fraction of the request each DOF gets: with `priorities: [2, 2, 0, 0, 0, 1]` (depth
and attitude first, then yaw, then surge and sway) by `qp` and by `pseudoinverse`, and without
priorities by `qp` (the weighted trade-off of weights.slack).

What it shows: strict order is strict. The horizontal thrusters sit 1.1 cm below the centre, so
they give a little roll and pitch; once level 0 (heave, roll, pitch) is beyond reach, `qp` spends
them on it, and yaw and sway (lower levels) get nothing, while surge is what that leaves. The
pseudo-inverse scales each level along its own direction instead (heave, roll and pitch by one
factor) and leaves yaw more."""

import sys
from pathlib import Path

import numpy as np

from allocator_pkg import Allocator, load_vehicle, read_parameters, vehicle_from_parameters
from allocator_pkg.capability.envelope import Capability
from allocator_pkg.capability.report.plotting import pyplot
from allocator_pkg.vehicle.config import DOF_NAMES

plt = pyplot()

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "config" / "bluerov2_heavy.yaml"
OUT = ROOT / "docs" / "priorities.png"
PRIORITIES = [2, 2, 0, 0, 0, 1]
DIRECTION = np.array([60.0, 40.0, 120.0, 6.0, 4.0, 8.0])
VOLTS = 12.0
SCALES = np.linspace(0.5, 3.0, 26)


def fractions(vehicle, method: str, reach: float) -> np.ndarray:
    """Achieved over requested per DOF (rows: scales)."""
    allocator = Allocator(vehicle, method=method)
    allocator.set_voltage(VOLTS)
    rows = []
    for scale in SCALES:
        tau = scale * reach * DIRECTION
        rows.append(allocator.allocate(tau).achieved / tau)
    return np.array(rows)


def main() -> int:
    parameters = read_parameters(CONFIG)
    prioritised = vehicle_from_parameters({**parameters, "priorities": PRIORITIES})
    reach = Capability(load_vehicle(CONFIG)).reach(DIRECTION, voltage=VOLTS)[0]
    cases = {"qp, priorities": fractions(prioritised, "qp", reach),
             "pseudoinverse, priorities (sequential desaturation)": fractions(prioritised, "pseudoinverse", reach),
             "qp, no priorities (weights.slack)": fractions(load_vehicle(CONFIG), "qp", reach)}
    figure, axes = plt.subplots(1, 3, figsize=(13, 4.2), sharey=True)
    for axis, (title, values) in zip(axes, cases.items()):
        for k, dof in enumerate(DOF_NAMES):
            axis.plot(SCALES, values[:, k], label=f"{dof} (level {PRIORITIES[k]})",
                      linestyle="-" if PRIORITIES[k] == 0 else ("--" if PRIORITIES[k] == 1 else ":"), linewidth=1.8)
        axis.set_title(title, fontsize=9)
        axis.set_xlabel("request / capability along it")
        axis.grid(True)
    axes[0].set_ylabel("achieved / requested")
    axes[0].set_ylim(-0.05, 1.05)
    axes[-1].legend(fontsize=8, loc="lower left")
    figure.suptitle(f"BlueROV2 Heavy at {VOLTS:g} V, request {DIRECTION.tolist()} scaled; "
                    f"priorities {PRIORITIES} (0 first)", fontsize=10)
    figure.tight_layout()
    figure.savefig(OUT, dpi=100, metadata={"Software": None})
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
