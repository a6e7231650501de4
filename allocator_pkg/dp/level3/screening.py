"""The Level 3 screening estimate: per intact case, the excursion's standard deviation from the
closed loop the case runs, linearised in the frequency domain, beside the time domain's, the
standard deviation of the case's track after settling (north and east: the set-point heading is
north, so they are surge and sway). The loop: with the DP system (``CaseSetup.dp_system``) the
PID on the passive observer's estimate, wind feed-forward, the measurement's noise and wave
motion (:mod:`allocator_pkg.simulation.observer_loop`); without, the PID on the true state
(:mod:`allocator_pkg.simulation.frequency_domain`); both excited by the force spectra of
:mod:`allocator_pkg.simulation.force_spectra`. With the DP system the thrust losses enter as one
factor on the loop's gain; the trips and the allocator are left out. A fast estimate to screen
conditions, not a criterion.
"""

from __future__ import annotations

import math

import numpy as np

from ...simulation.force_spectra import force_spectrum, gust_force_spectrum
from ...simulation.frequency_domain import LinearLoop, current_vector, linear_damping
from ...simulation.observer import PassiveObserver
from ...simulation.observer_loop import INPUTS, ObservedLoop, noise_spectrum, wave_motion_spectrum
from ...simulation.scenario import Scenario, vehicle_config
from ...simulation.thrust_losses import ThrustLosses
from ...simulation.vessel import Vessel, VesselParameters
from ..capability_result import INTACT
from .case import TRACK_PERIOD, Case, CaseResult, CaseSetup, case_scenario

OMEGA = np.linspace(2e-4, 1.5, 6000)
"""[rad/s] of the frequency-domain integral (the closed loop's bandwidth is near 0.1 rad/s)."""
SCREENING_COLUMNS = ("heading_deg", "capability_number", "seeds", "fd_north_std_m", "fd_east_std_m",
                     "fd_yaw_std_deg", "td_north_std_m", "td_east_std_m")
"""The screening table's columns: the frequency-domain (fd) estimate and the time domain's (td)."""
SCREENING_TABLE = {
    True: ("Excursion standard deviation, intact: the frequency-domain screening estimate (the DP system's closed "
           "loop linearised about the mean environment: the PID on the passive observer's estimate from the "
           "measured position with wave motion and noise, wind feed-forward, thruster lag; the thrust losses "
           "as one factor on the loop's gain; trips left out) beside the time-domain cases (after settling, "
           "over the seeds)"),
    False: ("Excursion standard deviation, intact: the frequency-domain screening estimate (the closed loop "
            "linearised about the mean environment: the PID on the true position and velocity, thruster lag) "
            "beside the time-domain cases (after settling, over the seeds)"),
}
"""The screening table's title, by whether the cases run the DP system (``CaseSetup.dp_system``)."""


def screening_estimate(setup: CaseSetup, case: Case) -> np.ndarray:
    """[north [m], east [m], yaw [rad]] standard deviations of the case's excursion by the
    linearised closed loop (the case's vessel, gains, thruster lag and environment; with the DP
    system, its observer, measurement noise, wave motion and wind feed-forward)."""
    scenario = case_scenario(setup, case)
    spec = scenario.environment
    vessel = Vessel(VesselParameters(coefficients=scenario.particulars.coefficients))
    current = current_vector(spec.current_speed, math.radians(spec.current_direction))
    damping = linear_damping(vessel, current)
    forces = force_spectrum(spec, scenario.particulars, vessel, OMEGA)
    if not setup.dp_system:
        loop = LinearLoop(vessel.mass, damping, scenario.gains, scenario.thruster_time_constant)
        return loop.excursion_std(OMEGA, forces)
    return observed_estimate(scenario, vessel, damping, forces)


def observed_estimate(scenario: Scenario, vessel: Vessel, damping: np.ndarray, forces: np.ndarray) -> np.ndarray:
    """The estimate of :func:`screening_estimate` through the DP system's loop
    (:class:`~allocator_pkg.simulation.observer_loop.ObservedLoop`): the gust's force apart (the
    feed-forward and the observer's model see it), the other forces, the first-order wave motion
    and the white measurement noise at the control period; the thrust losses as one factor on the
    loop's gain (:func:`thrust_factor`)."""
    spec, control, p = scenario.environment, scenario.control, scenario.particulars
    observer = PassiveObserver(control.observer, vessel.mass, vessel.linear_damping, vessel.parameters.mass,
                               vessel.parameters.length)
    vehicle = vehicle_config(scenario.vehicle, scenario.parameters)
    loop = ObservedLoop(vessel.mass, damping, scenario.gains, scenario.thruster_time_constant, observer,
                        control.wind_filter if control.wind_feedforward else None,
                        thrust_factor(scenario.thrust_losses, vehicle.names))
    gust = gust_force_spectrum(spec, p, OMEGA)
    inputs = np.zeros((OMEGA.size, INPUTS, INPUTS), dtype=complex)
    inputs[:, 0:3, 0:3], inputs[:, 3:6, 3:6] = gust, forces - gust
    if spec.wave_spectrum != "none":
        inputs[:, 6:9, 6:9] = wave_motion_spectrum(OMEGA, spec.wave_height, spec.wave_period, spec.peak_factor,
                                                   math.radians(spec.wave_direction), spec.wave_spreading,
                                                   p.lpp, p.beam)
    period = 1.0 / vehicle.rate_hz
    sigma = [control.noise.position_sigma, control.noise.position_sigma, control.noise.heading_sigma]
    inputs[:, 9:12, 9:12] = noise_spectrum(OMEGA, np.array(sigma), period)
    return loop.excursion_std(OMEGA, inputs)


def thrust_factor(losses: ThrustLosses | None, actuators: tuple[str, ...]) -> float:
    """The intact case's thrust loss as one factor on the loop's gain: the mean over the
    ``actuators`` of their forward factors (1 where none is given or without losses). The
    factors of a case differ little between thrusters (within a few per cent: ventilation and
    misc. losses), which the allocator's distribution would weigh."""
    if losses is None or not actuators:
        return 1.0
    intact = losses.case(frozenset())
    return float(np.mean([intact.forward.get(name, 1.0) for name in actuators]))


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
    return SCREENING_TABLE[setup.dp_system], SCREENING_COLUMNS, screening_rows(setup, finished)
