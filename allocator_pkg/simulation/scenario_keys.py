"""Every key of a scenario file (``config/scenarios/*.yaml``) in one table,
:data:`SCENARIO_KEYS`, nested as the file nests them: the unknown keys the reader refuses
(:func:`~.scenario_check.unknown_keys`), the defaults and lower bounds of its numbers
(:func:`~.scenario_values.number`) and the key table of docs/closed_loop.md come from it."""

from __future__ import annotations

import re
from typing import Any

from ..configuration.file_keys import (
    BOOLEAN,
    EACH,
    LIST,
    MAPPING,
    NUMBER,
    NUMBERS,
    TEXT,
    FileKey,
)
from .metrics import BOUNDED_METRICS, METRIC_UNITS
from .power_plant_keys import POWER_PLANT
from .spectra import WAVE_SPECTRA, WIND_SPECTRA

MODELS = ("dp_vessel", "bluerov2_heavy")
FAULT_MODES = ("failed", "stuck", "degraded")
ANYTHING = "any"
"""The kind of a key whose value is a node parameter's (checked against the schema instead)."""


def _sigma(name: str, unit: str, text: str) -> FileKey:
    return FileKey(name, NUMBER, f"the standard deviation of a first-order Gauss-Markov process {text}",
                   default=0.0, unit=unit, minimum=0.0)


def _variation(sigma: str, time: str, unit: str, text: str) -> tuple[FileKey, FileKey]:
    return (_sigma(sigma, unit, text),
            FileKey(time, NUMBER, "its time constant", default=60.0, unit="s", minimum=1e-6))


BOUND_KEYS = tuple(FileKey(name, NUMBER, "the largest value of the metric", unit=METRIC_UNITS[name], minimum=0.0)
                   for name in BOUNDED_METRICS)
"""A bound per metric of metrics.json but the real-time factor and the moments."""
METHOD_KEYS = (
    FileKey("bounds", MAPPING, "the method's own bounds over the run, each in place of the scenario's bound of "
            "that metric", default_doc="the scenario's", range_doc="each >= 0", keys=BOUND_KEYS, list_keys=False),
    FileKey("windows", MAPPING, "per window of the file, by its name, the method's own bounds over it",
            default_doc="the window's"),
    FileKey("note", TEXT, "why the method is held to other bounds", default="", default_doc="none"),
)
"""What a scenario expects of one method (``methods.<method>``)."""
BOUNDS = FileKey("bounds", MAPPING, "the largest value of any metric but the real-time factor, "
                 "`position_lost_time` and `alarm_lead_time` (metric name: bound, in the metric's unit), over the "
                 "whole run", default_doc="none", range_doc="each >= 0", keys=BOUND_KEYS, list_keys=False)
WINDOW_BOUNDS = FileKey("bounds", MAPPING, "bounds of the metrics over the window, as `bounds` over the run",
                        default_doc="none", range_doc="each >= 0", keys=BOUND_KEYS, list_keys=False)
ENVIRONMENT_KEYS = (
    FileKey("current", MAPPING, "the current: a mean plus two Gauss-Markov processes (speed, direction)", keys=(
        FileKey("speed", NUMBER, "mean speed", default=0.0, unit="m/s", minimum=0.0),
        FileKey("direction", NUMBER, "where it comes from", default=0.0, unit="deg"),
        _sigma("speed_sigma", "m/s", "of the speed"),
        _sigma("direction_sigma", "deg", "of the direction"),
        FileKey("time_constant", NUMBER, "their time constant", default=60.0, unit="s", minimum=1e-6),
        FileKey("down", NUMBER, "vertical current (ROV)", default=0.0, unit="m/s"))),
    FileKey("wind", MAPPING, "the wind on the vessel (its load by `wind_load` of environment_loads.py)", keys=(
        FileKey("speed", NUMBER, "mean speed", default=0.0, unit="m/s", minimum=0.0),
        FileKey("direction", NUMBER, "where it comes from", default=0.0, unit="deg"),
        *_variation("gust_sigma", "gust_time_constant", "m/s", "of the gust (first_order)"),
        FileKey("spectrum", TEXT, "the gust: a first-order Gauss-Markov process (gust_sigma, gust_time_constant) "
                "or a series from the NPD (ISO 19901-1), API RP 2A or Harris spectrum for the mean speed",
                default="first_order", choices=WIND_SPECTRA),
        *_variation("direction_sigma", "direction_time_constant", "deg",
                    "of the direction, with a gust spectrum"))),
    FileKey("waves", MAPPING, "the waves' mean drift on the vessel times 1 + a Gauss-Markov process, or from a "
            "JONSWAP spectrum the slowly varying drift (Newman) and the wave motion", keys=(
        FileKey("hs", NUMBER, "significant wave height", default=0.0, unit="m", minimum=0.0),
        FileKey("peak_period", NUMBER, "peak period", default=8.0, unit="s", minimum=0.0),
        FileKey("direction", NUMBER, "where they come from", default=0.0, unit="deg"),
        *_variation("drift_sigma", "drift_time_constant", "share of the mean", "of the drift (spectrum none)"),
        FileKey("spectrum", TEXT, "none: the mean drift times 1 + the drift process; jonswap: a JONSWAP sea's "
                "slowly varying drift by Newman's approximation and its first-order motion in the position "
                "measurement", default="none", choices=WAVE_SPECTRA),
        FileKey("peak_factor", NUMBER, "JONSWAP's gamma; 0: DNV-RP-C205's from Hs and Tp", default=0.0,
                minimum=0.0),
        FileKey("spreading", NUMBER, "n of DNV-RP-C205's cos^n directional spreading about `direction` (jonswap: "
                "a random direction per wave component; the mean drift averaged over the directions); 0: "
                "long-crested", default=0.0, minimum=0.0))),
)
OBSERVER_KEYS = (
    FileKey("enabled", BOOLEAN, "the controller acts on the observer's estimate, not on the true state",
            default=False),
    FileKey("wave_period", NUMBER, "the wave model's period, 2 pi / omega_o", unit="s", minimum=0.0,
            exclusive_minimum=True, default_doc="environment.waves.peak_period"),
    FileKey("wave_damping", NUMBER, "lambda, the wave model's relative damping", default=0.1, minimum=0.0,
            exclusive_minimum=True, range_doc="< notch_damping"),
    FileKey("notch_damping", NUMBER, "zeta_n, the notch's relative damping", default=1.0, minimum=0.0,
            exclusive_minimum=True),
    FileKey("cutoff_ratio", NUMBER, "omega_c / omega_o", default=1.5, minimum=1.0, exclusive_minimum=True),
    FileKey("bias_time_constant", NUMBER, "T of the bias model", default=1000.0, unit="s", minimum=0.0,
            exclusive_minimum=True, range_doc=">= 10 / k3_ratio"),
    FileKey("k4_bis", NUMBERS, "K4 in the bis system (surge, sway, yaw)", default=(5.0, 5.0, 0.4),
            range_doc="3 values > 0"),
    FileKey("k3_ratio", NUMBER, "K3 / K4", default=0.02, unit="1/s", minimum=0.0, exclusive_minimum=True,
            range_doc="< omega_o"),
)
"""The passive observer's tuning (``observer``): Fossen's relations 1/T << K3/K4 < omega_o < omega_c."""
RAMP_KEYS = (
    FileKey("to", NUMBER, "the value reached", required=True, minimum=0.0),
    FileKey("duration", NUMBER, "over this time", default=0.0, unit="s", minimum=0.0),
)
EVENT_KEYS = (
    FileKey("time", NUMBER, "when the event happens", required=True, unit="s", minimum=0.0),
    FileKey("fault", MAPPING, "an actuator's fault", keys=(
        FileKey("actuator", TEXT, "an actuator of the vehicle", required=True),
        FileKey("mode", TEXT, "the fault mode", required=True, choices=FAULT_MODES),
        FileKey("value", NUMBER, "the share of force left when degraded (then required, in (0, 1]), the angle "
                "when stuck [deg, -180 to 180, as every angle of the file]; failed takes none", default=0.0,
                default_doc="stuck: the angle it has then"))),
    FileKey("clear_faults", BOOLEAN, "every fault cleared (`clear_faults: true`)"),
    FileKey("battery_ramp", MAPPING, "the battery voltage ramps linearly to `to` [V]", keys=RAMP_KEYS),
    FileKey("parameter", MAPPING, "a node parameter changes", keys=(
        FileKey("name", TEXT, "a parameter of the allocator that may change while the node runs", required=True),
        FileKey("value", ANYTHING, "its new value", required=True))),
    FileKey("setpoint", MAPPING, "a new set-point: a step, or a ramp with `speed` or `heading_rate`", keys=(
        FileKey("position", NUMBERS, "NED", unit="m", range_doc="3 values"),
        FileKey("heading", NUMBER, "heading", unit="deg"),
        FileKey("speed", NUMBER, "a ramp of the position at this speed", unit="m/s", minimum=0.0,
                exclusive_minimum=True),
        FileKey("heading_rate", NUMBER, "a ramp of the heading at this rate", unit="deg/s", minimum=0.0,
                exclusive_minimum=True))),
    FileKey("group_fault", MAPPING, "a redundancy group of the vehicle fails", keys=(
        FileKey("group", TEXT, "a redundancy group of the vehicle", required=True),)),
    FileKey("power", MAPPING, "the available power of a source of the simulated power plant changes", keys=(
        FileKey("source", TEXT, "a power source of the vehicle", required=True),
        FileKey("available", NUMBER, "its available power", required=True, unit="kW", minimum=0.0))),
    FileKey("bus_tie", MAPPING, "a bus-tie breaker of the vehicle (power.bus_ties) opens or closes", keys=(
        FileKey("name", TEXT, "a bus tie of the vehicle", required=True),
        FileKey("closed", BOOLEAN, "true: closed (its sources one bus), false: open", required=True))),
    FileKey("weather_ramp", MAPPING, "the weather grows (or calms) linearly to `to` times the scenario's current "
            "speed, wind speed and significant wave height", keys=RAMP_KEYS),
    FileKey("generator_trip", MAPPING, "a generator set of `power_plant` is lost (its breaker opens)", keys=(
        FileKey("generator_set", TEXT, "a generator set of `power_plant.generator_sets`", required=True),)),
)
"""An event: ``time`` and exactly one of the others."""
SCENARIO_KEYS = (
    FileKey("name", TEXT, "the scenario's name", default_doc="the file's name"),
    FileKey("description", TEXT, "what happens", default="", default_doc="empty"),
    FileKey("model", TEXT, "the hull model", required=True, choices=MODELS),
    FileKey("vehicle", TEXT, "the vehicle params file, relative to the scenario", required=True),
    FileKey("particulars", TEXT, "the vessel's particulars file (its hull keys, for its loads), relative to the "
            "scenario", default_doc="required for dp_vessel"),
    FileKey("method", TEXT, "the allocation method", required=True),
    FileKey("duration", NUMBER, "simulated time", required=True, unit="s", minimum=1e-3),
    FileKey("seed", NUMBER, "the seed of the environment's variations", default=0, minimum=0.0),
    FileKey("thruster_time_constant", NUMBER, "the simulated thrusters' first-order lag", default=1.0, unit="s",
            minimum=1e-6),
    FileKey("position_limit", NUMBER, "the position error beyond which the vessel has lost its position (the alarm "
            "metrics)", default=5.0, unit="m", minimum=1e-6),
    FileKey("setpoint", MAPPING, "the set-point at t = 0", keys=(
        FileKey("position", NUMBERS, "NED", default=(0.0, 0.0, 0.0), unit="m", range_doc="3 values"),
        FileKey("heading", NUMBER, "heading", default=0.0, unit="deg"))),
    FileKey("initial", MAPPING, "the vehicle's pose at t = 0", keys=(
        FileKey("position", NUMBERS, "NED", default_doc="the set-point's", unit="m", range_doc="3 values"),
        FileKey("heading", NUMBER, "heading", default_doc="the set-point's", unit="deg"))),
    FileKey("controller", MAPPING, "the station-keeping controller's gains, per held DOF (3 for dp_vessel, 6 for "
            "bluerov2_heavy)", keys=(
        FileKey("kp", NUMBERS, "proportional gains", required=True, unit="N/m, N m/rad", minimum=0.0),
        FileKey("kd", NUMBERS, "derivative gains", required=True, unit="N s/m, N m s/rad", minimum=0.0),
        FileKey("ki", NUMBERS, "integral gains", required=True, unit="N/(m s), N m/(rad s)", minimum=0.0),
        FileKey("unallocated_threshold", NUMBERS, "the unallocated force or moment above which a DOF counts as "
                "short", default_doc="any nonzero amount", unit="N, N m", minimum=0.0),
        FileKey("wind_feedforward", BOOLEAN, "minus the wind load of the anemometer's wind on the hull added to the "
                "request, low-pass filtered (dp_vessel)", default=False),
        FileKey("wind_filter", NUMBER, "the wind feed-forward's first-order filter", default=10.0, unit="s",
                minimum=0.0, exclusive_minimum=True))),
    FileKey("observer", MAPPING, "the nonlinear passive observer (Fossen and Strand) the controller acts on, from "
            "the measured position and heading (dp_vessel; docs/closed_loop.md)", keys=OBSERVER_KEYS),
    FileKey("measurement", MAPPING, "white noise on the measured position and heading (with the observer)", keys=(
        FileKey("position_sigma", NUMBER, "standard deviation of north and east each", default=0.0, unit="m",
                minimum=0.0),
        FileKey("heading_sigma", NUMBER, "standard deviation of the heading", default=0.0, unit="deg",
                minimum=0.0))),
    FileKey("fault_trip", BOOLEAN, "a failed actuator's thrust drops to zero at once (a trip), not at its rate "
            "limit", default=False),
    FileKey("environment", MAPPING, "current, wind and waves, seeded", keys=ENVIRONMENT_KEYS),
    FileKey("parameters", MAPPING, "node parameters over the vehicle file's (docs/configuration.md)",
            default_doc="none"),
    POWER_PLANT,
    FileKey("battery", MAPPING, "a battery voltage from the start", default_doc="none", keys=(
        FileKey("voltage", NUMBER, "the battery voltage", required=True, unit="V", minimum=0.0),)),
    FileKey("events", LIST, "timed events, each `time` and one of the others", default_doc="none", keys=EVENT_KEYS,
            item=EACH),
    BOUNDS,
    FileKey("methods", MAPPING, "per method that can serve the vehicle, what the scenario expects of it in place of "
            "`bounds`; a method not named is held to `bounds`", default_doc="none", keys=METHOD_KEYS,
            item="<method>"),
    FileKey("windows", LIST, "named stretches of the run over which every metric is taken again", default_doc="none",
            keys=(FileKey("name", TEXT, "not that of an automatic window", required=True),
                  FileKey("start", NUMBER, "its start", required=True, unit="s", minimum=0.0),
                  FileKey("end", NUMBER, "its end", default_doc="the end of the run", unit="s",
                          range_doc="after start, at most duration"),
                  WINDOW_BOUNDS), item=EACH),
)
"""Every key of a scenario file, nested as the file nests them."""


def scenario_key(path: str) -> FileKey | None:
    """The key of :data:`SCENARIO_KEYS` at ``path`` (``events[2].fault.value``,
    ``methods.qp.bounds``), or None."""
    keys, found, named = SCENARIO_KEYS, None, False
    for name in re.sub(r"\[\d+\]", "", path).split("."):
        if named:                                  # a name the file chooses (``methods.<method>``)
            named = False
            continue
        found = next((key for key in keys if key.name == name), None)
        if found is None:
            return None
        keys, named = found.keys, found.item.startswith("<")
    return found


def scenario_default(path: str) -> Any:
    """The default of the key of :data:`SCENARIO_KEYS` at ``path``."""
    key = scenario_key(path)
    if key is None:
        raise KeyError(path)
    return key.default
