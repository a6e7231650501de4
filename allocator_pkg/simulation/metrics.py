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
- ``saturated_fraction``: the share of samples the status flags saturated;

and of the power and the consequence analysis (:func:`power_metrics`, :func:`alarm_metrics`):

- ``time_over_available`` [s]: how long some power source drew more than its available power
  (the simulated power plant's) by more than ``OVER_SHARE`` of it; per source, in the report,
  with its peak power [kW] (:func:`source_figures`);
- ``consequence_alarm_time`` [s]: when the status's ``consequence_alarm`` first rose (inf: never);
- ``position_lost_time`` [s]: when the position error first exceeded the scenario's
  ``position_limit`` while the set-point held still (inf: never); a commanded move (a step or
  ramp of the set-point's position) is not a loss: the error counts again from the first
  sample after it that is back within the limit (:func:`settled_samples`);
- ``alarm_lead_time`` [s]: how long before the position was lost the alarm rose (inf: the
  position was never lost; -inf: no alarm);
- ``alarm_after_position_loss`` [s]: how long the position had been lost when the alarm rose
  (0: the alarm came first, or the position was never lost; inf: lost, and no alarm);

and, with a simulated electric power plant (:mod:`.plant_metrics`, over the run only):

- ``frequency_dip`` [pu]: 1 less the lowest frequency of any bus (1: a bus went dead);
- ``time_under_frequency`` [s]: how long some bus was below 0.95 pu;
- ``generator_sets_tripped``: the sets the frequency relays tripped.
"""

from __future__ import annotations

import math

import numpy as np

METRIC_UNITS = {"position_error_rms": "m", "position_error_max": "m", "heading_error_rms": "deg",
                "heading_error_max": "deg", "depth_error_max": "m", "energy": "J", "azimuth_travel": "rad",
                "thrust_reversals": "count", "saturated_fraction": "share", "time_over_available": "s",
                "consequence_alarm_time": "s", "position_lost_time": "s", "alarm_lead_time": "s",
                "alarm_after_position_loss": "s", "frequency_dip": "pu", "time_under_frequency": "s",
                "generator_sets_tripped": "count", "realtime_factor": "x real time"}
"""Every metric of a run, in the order they are reported, with its unit."""
UNBOUNDED = ("position_lost_time", "alarm_lead_time", "realtime_factor")
"""Metrics an upper bound means nothing for: two moments that are better later, and the wall clock."""
BOUNDED_METRICS = tuple(name for name in METRIC_UNITS if name not in UNBOUNDED)
"""The metrics a scenario's ``bounds`` may hold a run to (from above)."""
PLANT_METRICS = ("frequency_dip", "time_under_frequency", "generator_sets_tripped")
"""The metrics of a simulated electric power plant, over the run only."""
OVER_SHARE = 0.01
"""A source is over its available power when it draws more than (1 + this) times it."""
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


def over_available(power: np.ndarray, available: np.ndarray) -> np.ndarray:
    """Per sample and source (n x s, kW): whether it draws more than (1 + OVER_SHARE) of its available power."""
    return np.asarray(power, dtype=float) > (1.0 + OVER_SHARE) * np.asarray(available, dtype=float)


def source_figures(sources: list[str], power: np.ndarray, available: np.ndarray,
                   period: float) -> dict[str, dict[str, float]]:
    """Per source: ``peak_power`` [kW] drawn, the least available power [kW] and
    ``time_over_available`` [s], over n samples (n x s, kW)."""
    if not sources or len(power) == 0:
        return {}
    over = over_available(power, available)
    return {name: {"peak_power": float(np.max(power[:, j])), "least_available": float(np.min(available[:, j])),
                   "time_over_available": float(np.count_nonzero(over[:, j]) * period)}
            for j, name in enumerate(sources)}


def power_metrics(power: np.ndarray, available: np.ndarray, period: float) -> dict[str, float]:
    """``time_over_available`` [s]: samples (n x s, kW) in which some source is over, times the period."""
    if np.size(power) == 0:
        return {"time_over_available": 0.0}
    return {"time_over_available": float(np.count_nonzero(over_available(power, available).any(axis=1)) * period)}


def first_time(time: np.ndarray, flags: np.ndarray) -> float:
    """The time [s] of the first sample flagged (inf: none)."""
    flagged = np.flatnonzero(np.asarray(flags, dtype=bool))
    return float(np.asarray(time)[flagged[0]]) if flagged.size else math.inf


def settled_samples(setpoint: np.ndarray, distance: np.ndarray, limit: float) -> np.ndarray:
    """Per sample (n x 3 set-point positions, n position errors [m]): whether its error can
    count as a loss of position. A sample whose set-point moved from the one before starts (or
    continues) a commanded move; the samples of a move do not count, nor those after it until
    the first whose set-point holds still and whose error is within ``limit``."""
    setpoint = np.asarray(setpoint, dtype=float)
    moved = np.zeros(len(setpoint), dtype=bool)
    moved[1:] = np.any(setpoint[1:] != setpoint[:-1], axis=1)
    counted = np.ones(len(setpoint), dtype=bool)
    moving = False
    for k, (step, error) in enumerate(zip(moved, distance)):
        moving = step or (moving and error > limit)
        counted[k] = not moving
    return counted


def alarm_metrics(time: np.ndarray, alarm: np.ndarray, distance: np.ndarray, limit: float,
                  counted: np.ndarray | None = None) -> dict[str, float]:
    """The consequence alarm's time against the loss of position (the module's last four metrics):
    ``distance`` [m] the position error of each sample, ``limit`` [m] the scenario's
    ``position_limit``, ``counted`` the samples whose error can count as a loss
    (:func:`settled_samples`; default all)."""
    raised = first_time(time, alarm)
    beyond = np.asarray(distance) > limit
    lost = first_time(time, beyond if counted is None else beyond & np.asarray(counted, dtype=bool))
    return {"consequence_alarm_time": raised, "position_lost_time": lost,
            "alarm_lead_time": -math.inf if math.isinf(raised) else lost - raised,
            "alarm_after_position_loss": 0.0 if math.isinf(lost) else max(0.0, raised - lost)}
