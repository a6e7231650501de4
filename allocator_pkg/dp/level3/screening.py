"""The Level 3 screening estimate: per intact case, the excursion's standard deviation from the
closed loop linearised in the frequency domain (:mod:`allocator_pkg.simulation.frequency_domain`,
force spectra of :mod:`allocator_pkg.simulation.force_spectra`) beside the time domain's, the
standard deviation of the case's track after settling (north and east: the set-point heading is
north, so they are surge and sway). A fast estimate to screen conditions, not a criterion.
"""

from __future__ import annotations

import math

import numpy as np

from ...simulation.force_spectra import force_spectrum
from ...simulation.frequency_domain import LinearLoop, current_vector, linear_damping
from ...simulation.vessel import Vessel, VesselParameters
from ..capability_result import INTACT
from .case import TRACK_PERIOD, Case, CaseResult, CaseSetup, case_scenario

OMEGA = np.linspace(2e-4, 1.5, 6000)
"""[rad/s] of the frequency-domain integral (the closed loop's bandwidth is near 0.1 rad/s)."""
SCREENING_COLUMNS = ("heading_deg", "capability_number", "seeds", "fd_north_std_m", "fd_east_std_m",
                     "fd_yaw_std_deg", "td_north_std_m", "td_east_std_m")
"""The screening table's columns: the frequency-domain (fd) estimate and the time domain's (td)."""
SCREENING_TABLE = ("Excursion standard deviation, intact: the frequency-domain screening estimate (the closed "
                   "loop linearised about the mean environment) beside the time-domain cases (after settling, "
                   "over the seeds)")
"""The screening table's title."""


def screening_estimate(setup: CaseSetup, case: Case) -> np.ndarray:
    """[north [m], east [m], yaw [rad]] standard deviations of the case's excursion by the
    linearised closed loop (the case's vessel, gains, thruster lag and environment)."""
    scenario = case_scenario(setup, case)
    spec = scenario.environment
    vessel = Vessel(VesselParameters(coefficients=scenario.particulars.coefficients))
    current = current_vector(spec.current_speed, math.radians(spec.current_direction))
    loop = LinearLoop(vessel.mass, linear_damping(vessel, current), scenario.gains, scenario.thruster_time_constant)
    return loop.excursion_std(OMEGA, force_spectrum(spec, scenario.particulars, vessel, OMEGA))


def track_std(results: list[CaseResult], settle: float) -> tuple[float, float]:
    """(north, east) standard deviations [m] of the tracks after ``settle`` [s], pooled over the
    results (each about its own mean)."""
    start = math.ceil(settle / TRACK_PERIOD)
    parts = [np.array(r.track[start:]) - np.mean(r.track[start:], axis=0) for r in results]
    pooled = np.concatenate(parts)
    return tuple(float(v) for v in np.sqrt(np.mean(pooled ** 2, axis=0)))


def screening_rows(setup: CaseSetup, finished: dict[tuple, CaseResult]) -> list[tuple]:
    """One row per (heading, number) with intact cases run: heading, number, seeds, the estimate
    (north, east [m], yaw [deg]) and the time domain's (north, east [m])."""
    runs: dict[tuple[float, int], list[CaseResult]] = {}
    for key, result in finished.items():
        if key[2] == INTACT:
            runs.setdefault((key[0], key[1]), []).append(result)
    rows = []
    for (heading, number), results in sorted(runs.items()):
        north, east, yaw = screening_estimate(setup, Case(heading, number, INTACT, 0))
        measured = track_std(results, setup.criteria.settle)
        rows.append((heading, number, len(results), float(north), float(east), math.degrees(yaw), *measured))
    return rows


def screening_table(setup: CaseSetup, finished: dict[tuple, CaseResult]) -> tuple[str, tuple[str, ...], list[tuple]]:
    """(title, columns, rows) of the screening table for the Level 3 report."""
    return SCREENING_TABLE, SCREENING_COLUMNS, screening_rows(setup, finished)
