"""What a closed-loop run cost and how well it held station, from the samples anyone can read
back from its recording (odometry, set-point, commands, status):

- ``position_error_rms``, ``position_error_max`` [m]: distance from the set-point in the DOFs
  the scenario holds (the horizontal plane for a vessel, 3-D for an ROV);
- ``heading_error_rms`` [deg];
- ``energy`` [J]: the power model (1.44), P = sum_i P_i |f_i|^(3/2) over the commanded
  thrusts, times the sample period;
- ``azimuth_travel`` [rad]: the commanded angles' total movement (each step wrapped);
- ``thrust_reversals``: sign changes of each commanded thrust, counted where its size
  exceeds ``REVERSAL_SHARE`` of its largest force;
- ``saturated_fraction``: the share of samples the status flags saturated.
"""

from __future__ import annotations

import math

import numpy as np

METRIC_UNITS = {"position_error_rms": "m", "position_error_max": "m", "heading_error_rms": "deg",
                "heading_error_max": "deg", "depth_error_max": "m", "energy": "J", "azimuth_travel": "rad",
                "thrust_reversals": "count", "saturated_fraction": "share", "realtime_factor": "x real time"}
"""Every metric of a run, in the order they are reported, with its unit."""
BOUNDED_METRICS = tuple(name for name in METRIC_UNITS if name != "realtime_factor")
"""The metrics a scenario's ``bounds`` may hold a run to (from above): all but the wall-clock one."""
REVERSAL_SHARE = 0.01
"""A thrust counts as having a sign when it exceeds this share of the actuator's largest force."""


def position_errors(position: np.ndarray, setpoint: np.ndarray, horizontal: bool) -> np.ndarray:
    """Distance [m] of each sample's position (n x 3, NED) from its set-point."""
    difference = np.asarray(position, dtype=float) - np.asarray(setpoint, dtype=float)
    if horizontal:
        difference = difference[:, :2]
    return np.linalg.norm(difference, axis=1)


def heading_errors(heading: np.ndarray, setpoint: np.ndarray) -> np.ndarray:
    """Heading error [rad] of each sample, wrapped to [-pi, pi)."""
    return (np.asarray(heading) - np.asarray(setpoint) + math.pi) % (2.0 * math.pi) - math.pi


def energy(thrust: np.ndarray, power_coefficients: np.ndarray, period: float) -> float:
    """[J] of n samples x r thrusts held one period each under (1.44)."""
    return float(np.sum(np.abs(np.asarray(thrust)) ** 1.5 @ np.asarray(power_coefficients)) * period)


def azimuth_travel(angles: np.ndarray) -> float:
    """[rad] the angles (n samples x r) moved in all, each step the short way round."""
    steps = np.diff(np.asarray(angles, dtype=float), axis=0)
    return float(np.sum(np.abs((steps + math.pi) % (2.0 * math.pi) - math.pi)))


def thrust_reversals(thrust: np.ndarray, thrust_scale: np.ndarray) -> int:
    """Sign changes of each column of ``thrust`` (n x r), a sample counting only where
    |f| > REVERSAL_SHARE x its column's ``thrust_scale``."""
    count = 0
    for column, scale in zip(np.asarray(thrust, dtype=float).T, thrust_scale):
        signs = np.sign(column[np.abs(column) > REVERSAL_SHARE * scale])
        count += int(np.count_nonzero(np.diff(signs)))
    return count


def run_metrics(*, position: np.ndarray, position_setpoint: np.ndarray, heading: np.ndarray,
                heading_setpoint: np.ndarray, horizontal: bool, thrust: np.ndarray, angles: np.ndarray,
                saturated: np.ndarray, power_coefficients: np.ndarray, thrust_scale: np.ndarray,
                period: float) -> dict[str, float]:
    """Every metric of a run but the real-time factor (its wall time is not in the samples)."""
    distance = position_errors(position, position_setpoint, horizontal)
    return {
        "position_error_rms": float(np.sqrt(np.mean(distance ** 2))),
        "position_error_max": float(np.max(distance)),
        "heading_error_rms": float(np.degrees(np.sqrt(np.mean(heading_errors(heading, heading_setpoint) ** 2)))),
        "energy": energy(thrust, power_coefficients, period),
        "azimuth_travel": azimuth_travel(angles),
        "thrust_reversals": thrust_reversals(thrust, thrust_scale),
        "saturated_fraction": float(np.mean(np.asarray(saturated, dtype=float))),
    }
