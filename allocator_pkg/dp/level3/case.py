"""One case of the DNV-ST-0111 Level 3 (time-domain) capability analysis: a seeded in-process
closed-loop run (:class:`~...simulation.closed_loop.ClosedLoop` over
:class:`~...simulation.in_process.InProcessLink`) of
the DP vessel on station, with wind, current and waves of one capability number's condition
coming from one heading (or waves and current from the site's directions relative to the wind),
intact or with a redundancy group failed once the vessel has settled
on station, so that the failure's transient counts.

A run holds alone when its horizontal position excursion from the set-point stays within
``position_limit`` [m] and its heading deviation within ``heading_limit_deg``, within
``post_failure_window`` after a group's failure the post-failure limits instead; a condition
holds on the quantile of these over its seeds (:mod:`.statistics`). The public transcription of the
standard used here (WilliamBoland1/Prosjektoppgave_Collab) has no Level 3 text: the criteria, the
settling time, the duration, the seeds, the quantile and the environment's variations are this
package's defaults (:data:`CRITERIA_NOTE`, :data:`CRITERIA_KEYS`, a criteria file),
stated in every output. Each case is a pure function of its inputs, the seed among them.
"""

from __future__ import annotations

import contextlib
import math
import tempfile
from collections.abc import Iterator
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ...configuration.file_keys import INTEGER, NUMBER, TEXT, FileKey, key_named
from ...simulation.closed_loop import ClosedLoop
from ...simulation.environment import EnvironmentSpec
from ...simulation.in_process import InProcessLink
from ...simulation.metrics import heading_errors
from ...simulation.scenario import Event, Scenario
from ...simulation.spreading import spread_mean
from ..capability_result import INTACT
from ..inputs.particulars import Particulars
from ..inputs.site import SiteSea
from ..standard.loads import BodyFrame, DnvHull, wave_drift_load, wind_load
from ..standard.weather import WeatherCondition
from .dp_system import with_dp_system

TRACK_PERIOD = 1.0
"""[s] between the samples of a case's x-y track kept for the footprint plots."""
NO_ONLINE_CONSEQUENCE = {"consequence.rate": 0.0}
"""The node parameter of every case: the online consequence analysis off. Its alarm only marks
the statuses (it changes no allocation), a case's result is its excursions alone, and the case
is that analysis' question asked in the time domain (the group does fail); run at its period it
would cost a case more than the rest of the link's work per sample."""
CRITERIA_NOTE = ("Level 3 criteria: the transcription used has no Level 3 text; a condition holds when, over its "
                 "seeds, the stated quantile of the largest horizontal position excursion from the set-point is "
                 "within the position limit and that of the largest heading deviation within the heading limit "
                 "(after a group's failure, within the post-failure window, the post-failure limits instead) "
                 "(this package's defaults, not the standard's)")
QUANTILE_METHODS = ("linear", "inverted_cdf", "higher", "median_unbiased", "normal_unbiased", "hazen", "weibull")
"""The methods of ``numpy.quantile`` (Hyndman and Fan 1996) a criteria file may name."""


CRITERIA_KEYS = (
    FileKey("position_limit", NUMBER, "largest horizontal excursion from the set-point (outside the post-failure "
            "window)", default=5.0, unit="m", minimum=0.0, exclusive_minimum=True),
    FileKey("heading_limit_deg", NUMBER, "largest heading deviation (outside the post-failure window)", default=3.0,
            unit="deg", minimum=0.0, exclusive_minimum=True),
    FileKey("settle", NUMBER, "on station before a group fails", default=60.0, unit="s", minimum=0.0,
            exclusive_minimum=True),
    FileKey("duration", NUMBER, "simulated after settling", default=600.0, unit="s", minimum=0.0,
            exclusive_minimum=True),
    FileKey("seeds", INTEGER, "seeds per condition (seed indices 0 ... seeds - 1)", default=10, minimum=1),
    FileKey("quantile", NUMBER, "the quantile over the seeds of each case's largest excursion that decides the "
            "condition (0.9: P90; 1: every seed must hold)", default=0.9, minimum=0.0, maximum=1.0,
            exclusive_minimum=True),
    FileKey("quantile_method", TEXT, "numpy.quantile's method for that quantile (Hyndman and Fan)",
            default="linear", choices=QUANTILE_METHODS),
    FileKey("confidence", NUMBER, "level of the percentile-bootstrap confidence interval of the quantile",
            default=0.9, minimum=0.0, maximum=1.0, exclusive_minimum=True, exclusive_maximum=True),
    FileKey("resamples", INTEGER, "bootstrap resamples", default=2000, minimum=100),
    FileKey("bootstrap_seed", INTEGER, "seed of the bootstrap's random numbers (the intervals reproducible)",
            default=0, minimum=0),
    FileKey("post_failure_position_limit", NUMBER, "largest horizontal excursion within the post-failure window",
            default=5.0, unit="m", minimum=0.0, exclusive_minimum=True),
    FileKey("post_failure_heading_limit_deg", NUMBER, "largest heading deviation within the post-failure window",
            default=3.0, unit="deg", minimum=0.0, exclusive_minimum=True),
    FileKey("post_failure_window", NUMBER, "from a group's failure, the time the post-failure limits apply",
            default=60.0, unit="s", minimum=0.0),
)
"""The Level 3 criteria (the criteria file, ``--level3-criteria``; ``--position-limit``,
``--heading-limit``, ``--settle``, ``--duration`` and ``--seeds`` of allocator-capability
override it): this package's defaults, the transcription having no Level 3 text."""
JUDGEMENT_KEYS = ("seeds", "quantile", "quantile_method", "confidence", "resamples", "bootstrap_seed")
"""The criteria that decide a condition from its seeds' runs but change no run: a journal written
with other values of these is resumed (its runs kept)."""


@dataclass(frozen=True)
class Criteria:
    """What a condition must hold [m, deg], how long a case runs [s] (``settle`` on station, then
    ``duration``; a group fails at the end of ``settle``), and how its seeds decide it: the
    ``quantile`` (by ``quantile_method``) over ``seeds`` runs of each run's largest excursion,
    with a percentile-bootstrap interval at ``confidence`` (``resamples`` draws, ``bootstrap_seed``);
    within ``post_failure_window`` after a group's failure the post-failure limits stand in for
    the others. The defaults of :data:`CRITERIA_KEYS`."""

    position_limit: float = key_named(CRITERIA_KEYS, "position_limit").default
    heading_limit_deg: float = key_named(CRITERIA_KEYS, "heading_limit_deg").default
    settle: float = key_named(CRITERIA_KEYS, "settle").default
    duration: float = key_named(CRITERIA_KEYS, "duration").default
    seeds: int = key_named(CRITERIA_KEYS, "seeds").default
    quantile: float = key_named(CRITERIA_KEYS, "quantile").default
    quantile_method: str = key_named(CRITERIA_KEYS, "quantile_method").default
    confidence: float = key_named(CRITERIA_KEYS, "confidence").default
    resamples: int = key_named(CRITERIA_KEYS, "resamples").default
    bootstrap_seed: int = key_named(CRITERIA_KEYS, "bootstrap_seed").default
    post_failure_position_limit: float = key_named(CRITERIA_KEYS, "post_failure_position_limit").default
    post_failure_heading_limit_deg: float = key_named(CRITERIA_KEYS, "post_failure_heading_limit_deg").default
    post_failure_window: float = key_named(CRITERIA_KEYS, "post_failure_window").default

    def __post_init__(self) -> None:
        for name, value in asdict(self).items():
            check_criterion(key_named(CRITERIA_KEYS, name), value)

    def values(self) -> list[tuple[str, str]]:
        """(key, value with its unit) of every criterion, in the key table's order."""
        rows = []
        for key in CRITERIA_KEYS:
            value = getattr(self, key.name)
            text = f"{value:g}" if isinstance(value, float) else str(value)
            rows.append((key.name, f"{text} {key.unit}".strip()))
        return rows

    def describe(self) -> str:
        """Every criterion by its key, for the text outputs and the CSV header lines."""
        return "; ".join(f"{name} {value}" for name, value in self.values())

    def short(self) -> str:
        """The criteria in a few words, for a plot's caption."""
        return (f"P{100 * self.quantile:g} ({self.quantile_method}) of {self.seeds} seeds within "
                f"{self.position_limit:g} m, {self.heading_limit_deg:g} deg ({self.post_failure_position_limit:g} m, "
                f"{self.post_failure_heading_limit_deg:g} deg for {self.post_failure_window:g} s after a failure); "
                f"{self.settle:g} + {self.duration:g} s per case; {100 * self.confidence:g} % bootstrap CI "
                f"({self.resamples} resamples, seed {self.bootstrap_seed})")

    def run_fingerprint(self) -> str:
        """The criteria that change a case's run or its own verdict (not :data:`JUDGEMENT_KEYS`)."""
        return "; ".join(f"{name} {value}" for name, value in self.values() if name not in JUDGEMENT_KEYS)


def check_criterion(key: FileKey, value: Any) -> None:
    """A ValueError naming ``key`` when ``value`` is not of its kind or outside its range."""
    if key.kind == TEXT:
        if value not in key.choices:
            raise ValueError(f"{key.name}: one of {', '.join(key.choices)}, not {value!r}")
        return
    integer = key.kind == INTEGER
    kind_ok = (isinstance(value, int) if integer else isinstance(value, (int, float))) and not isinstance(value, bool)
    if not (kind_ok and math.isfinite(value) and key.holds(value)):
        what = "an integer" if integer else "a finite number"
        raise ValueError(f"{key.name}: {what} {key.documented_range()}, not {value!r}")


@dataclass(frozen=True)
class Case:
    """Heading [deg, environment from; 0 ahead, 90 from starboard], capability number, ``intact``
    or a redundancy group, seed index."""

    heading_deg: float
    number: int
    group: str
    seed: int

    @property
    def key(self) -> tuple[float, int, str, int]:
        return (self.heading_deg, self.number, self.group, self.seed)


@dataclass(frozen=True)
class CaseSetup:
    """Everything a case needs besides itself: the base scenario (vessel, particulars, method,
    controller gains, thruster time constant, the environment's variations), the condition of
    each number, each group's actuators, the vehicle file's named redundancy groups (failed with
    ``Allocator.set_group_fault``) and the criteria."""

    scenario: Scenario
    conditions: tuple[WeatherCondition, ...]
    groups: dict[str, tuple[str, ...]]
    named_groups: frozenset[str]
    criteria: Criteria
    hull: DnvHull | None = None
    """The standard's hull and the body frame of the mean wind load and wave drift [3.5], [3.7]
    (None: those of the simulation's load model)."""
    frame: BodyFrame | None = None
    spectra: bool = True
    """The gusts and the sea from spectra (False: the base scenario's first-order gust at its
    turbulence intensity and its drift factor, the hull's mean loads)."""
    particulars: Particulars | None = None
    """The particulars of the static analysis, for the thrust losses (None: no loss)."""
    dp_system: bool = True
    """The vessel's DP system, a failure a trip, the thrusters' losses (:mod:`.dp_system`; False:
    the controller on the true state, a failure at the rate limit, no loss)."""
    sea: SiteSea = field(default_factory=SiteSea)
    """The site's peak factor, spreading and directions of the waves and the current relative to
    the wind (the default: DNV-RP-C205's peak factor, long-crested, collinear)."""
    group_sources: dict[str, tuple[str, ...]] = field(default_factory=dict)
    """The power sources (switchboards) of each named redundancy group: with the base scenario's
    power plant, a group's loss takes the generator sets of its switchboards with it."""


@dataclass(frozen=True)
class CaseResult:
    """Position excursion [m] (max, mean), heading deviation [deg] (max), whether the run alone
    kept within the criteria's limits, the x-y track (north, east [m]) every
    :data:`TRACK_PERIOD`, and the largest position excursion [m] and heading deviation [deg]
    outside (``steady_``) and within (``transient_``; None for an intact case or an empty window)
    the post-failure window; the quantiles over the seeds decide a condition
    (:mod:`.statistics`)."""

    case: Case
    max_position: float
    mean_position: float
    max_heading_deg: float
    held: bool
    track: tuple[tuple[float, float], ...]
    steady_position: float
    steady_heading_deg: float
    transient_position: float | None
    transient_heading_deg: float | None

    def to_json(self) -> dict[str, Any]:
        return {"heading_deg": self.case.heading_deg, "number": self.case.number, "group": self.case.group,
                "seed": self.case.seed, "max_position_m": self.max_position, "mean_position_m": self.mean_position,
                "max_heading_deg": self.max_heading_deg, "held": self.held, "track": [list(p) for p in self.track],
                "steady_position_m": self.steady_position, "steady_heading_deg": self.steady_heading_deg,
                "transient_position_m": self.transient_position, "transient_heading_deg": self.transient_heading_deg}

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> CaseResult:
        case = Case(float(data["heading_deg"]), int(data["number"]), str(data["group"]), int(data["seed"]))
        transient = [None if data[k] is None else float(data[k]) for k in ("transient_position_m",
                                                                            "transient_heading_deg")]
        return cls(case, float(data["max_position_m"]), float(data["mean_position_m"]),
                   float(data["max_heading_deg"]), bool(data["held"]),
                   tuple((float(n), float(e)) for n, e in data["track"]), float(data["steady_position_m"]),
                   float(data["steady_heading_deg"]), *transient)


def case_environment(setup: CaseSetup, case: Case) -> EnvironmentSpec:
    """The environment of one case: the condition's wind from ``case.heading_deg`` relative to the
    bow (the set-point heading 0 deg, north), the waves and the current from the same heading
    (Level 1's collinear environment) or from the site's directions relative to the wind
    (``setup.sea``); the gusts from the base scenario's gust spectrum (NPD unless it names
    another), a JONSWAP sea of the site's peak factor (DNV-RP-C205's unless given) and spreading
    (long-crested unless given) with Newman's slowly varying drift and the first-order wave
    motion, the mean wind load [3.5] at the wind's direction and the mean wave drift [3.7] at the
    waves' (in a spread sea averaged over the directions weighted by the spreading,
    :func:`~...simulation.spreading.spread_mean`) when the set-up has the standard's hull, the base
    scenario's slow variations of the current."""
    spec, condition, sea = setup.scenario.environment, setup.conditions[case.number], setup.sea
    heading = case.heading_deg
    waves = heading + (sea.wave_direction or 0.0)
    period = condition.tp if condition.tp > 0.0 else spec.wave_period
    common = dict(current_speed=condition.current, current_direction=heading + (sea.current_direction or 0.0),
                  wind_speed=condition.wind, wind_direction=heading, wave_height=condition.hs, wave_direction=waves,
                  wave_period=period, wave_spreading=sea.spreading)
    if not setup.spectra:
        intensity = spec.gusts.sigma / spec.wind_speed if spec.wind_speed > 0.0 else 0.0
        return replace(spec, gusts=replace(spec.gusts, sigma=intensity * condition.wind), **common)
    mean_wind = mean_drift = None
    hull, frame = setup.hull, setup.frame
    if hull is not None and frame is not None:
        mean_wind = tuple(frame.load(wind_load(hull, condition.wind, math.radians(heading))))
        mean_drift = tuple(spread_mean(lambda theta: frame.load(wave_drift_load(
            hull, condition.hs, period, math.radians(waves) + theta)), sea.spreading))
    return replace(spec, wind_spectrum=spec.wind_spectrum if spec.wind_spectrum != "first_order" else "npd",
                   wave_spectrum="jonswap", peak_factor=sea.peak_factor(case.number), mean_wind_load=mean_wind,
                   mean_drift_load=mean_drift, **common)


def case_scenario(setup: CaseSetup, case: Case) -> Scenario:
    """The scenario of one case: its environment (:func:`case_environment`), the seed (the base
    scenario's plus the case's index), a failure of every actuator of the group at ``settle`` and,
    with the base scenario's power plant, the loss of every generator set on the group's
    switchboards at the same time (the plant's own events left out), the online consequence
    analysis off (:data:`NO_ONLINE_CONSEQUENCE`), and the DP system, trip and losses of
    :mod:`.dp_system` (unless ``setup.dp_system`` is False)."""
    base, criteria = setup.scenario, setup.criteria
    environment = case_environment(setup, case)
    failed = () if case.group == INTACT else setup.groups[case.group]
    events = tuple(Event(criteria.settle, "fault", actuator=name, mode="failed", value=0.0) for name in failed)
    if base.power_plant is not None:
        switchboards = setup.group_sources.get(case.group, ())
        events += tuple(Event(criteria.settle, "generator_trip", name=s.name)
                        for s in base.power_plant.generator_sets if s.switchboard in switchboards)
    scenario = replace(base, name=f"{base.name}_l3", duration=criteria.settle + criteria.duration,
                       parameters={**base.parameters, **NO_ONLINE_CONSEQUENCE},
                       seed=base.seed + case.seed, setpoint_position=(0.0, 0.0, 0.0), setpoint_heading=0.0,
                       initial_position=(0.0, 0.0, 0.0), initial_heading=0.0, environment=environment, events=events,
                       bounds={}, windows=())
    if not setup.dp_system:
        return scenario
    return with_dp_system(scenario, setup.particulars, setup.conditions[case.number], case.heading_deg, case.group,
                          failed)


class GroupFaultLink(InProcessLink):
    """The in-process link failing a named redundancy group through ``Allocator.set_group_fault``
    (its actuators and its power sources) at the first fault of one of its actuators."""

    def __init__(self, scenario: Scenario, group: str | None) -> None:
        super().__init__(scenario)
        self.group = group

    def set_fault(self, actuator: str, mode: str, value: float) -> str:
        if self.group is not None and self.group not in self.allocator.group_faults:
            self.allocator.set_group_fault(self.group)
        return super().set_fault(actuator, mode, value)


def run_case(case: Case, setup: CaseSetup) -> CaseResult:
    """One case, start to end (no file is kept)."""
    scenario = case_scenario(setup, case)
    group = case.group if case.group in setup.named_groups else None

    @contextlib.contextmanager
    def connect(run: Scenario, out: Path) -> Iterator[GroupFaultLink]:
        yield GroupFaultLink(run, group)

    with tempfile.TemporaryDirectory(prefix="l3_case_") as folder:
        trace = ClosedLoop(scenario, Path(folder), connect, log=lambda _: None).run().trace
    position = trace.position_errors()
    heading = np.degrees(np.abs(heading_errors(np.array(trace.attitude)[:, 2], np.array(trace.setpoint_heading))))
    every = max(1, round(TRACK_PERIOD / trace.period))
    track = tuple((float(p[0]), float(p[1])) for p in trace.position[::every])
    return excursions(case, setup.criteria, np.array(trace.time), position, heading, track)


def excursions(case: Case, criteria: Criteria, time: np.ndarray, position: np.ndarray, heading: np.ndarray,
               track: tuple[tuple[float, float], ...]) -> CaseResult:
    """A run's result from its samples: time [s], position excursion [m] and heading deviation
    [deg]; the post-failure window is [``settle``, ``settle + post_failure_window``) after a
    group's failure (an intact case has none), and the run alone holds when its excursions keep
    within the limits that apply where they are."""
    window = np.zeros(time.shape, dtype=bool)
    if case.group != INTACT:
        window = (time >= criteria.settle) & (time < criteria.settle + criteria.post_failure_window)
    steady_position = float(np.max(position[~window], initial=0.0))
    steady_heading = float(np.max(heading[~window], initial=0.0))
    transient = (float(np.max(position[window])), float(np.max(heading[window]))) if np.any(window) else (None, None)
    held = (steady_position <= criteria.position_limit and steady_heading <= criteria.heading_limit_deg
            and (transient[0] is None or (transient[0] <= criteria.post_failure_position_limit
                                          and transient[1] <= criteria.post_failure_heading_limit_deg)))
    return CaseResult(case, float(np.max(position)), float(np.mean(position)), float(np.max(heading)), held, track,
                      steady_position, steady_heading, *transient)
