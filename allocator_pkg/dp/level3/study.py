"""DNV-ST-0111 Level 3 (time-domain) DP capability as this package reads it:
``allocator-capability --dnv-level3 VESSEL PARTICULARS --out DIR [--headings STEP]
[--level3-criteria FILE] [--workers N | --scheduler ADDRESS] [--resume]``.

Per heading and case (intact, each redundancy group) the conditions rise per [2.4.4] (Table 2-1,
or the Level 2 site's) until the first that fails in seeded in-process closed-loop runs
(:mod:`allocator_pkg.dp.level3.case`); a condition the static Level 2 balance already fails
is not simulated. :func:`study` checks every input before the first case runs, then runs the
cases (:mod:`.engine`) and gives the result as a
:class:`~allocator_pkg.dp.capability_result.CapabilityResult` of level 3 with the static Levels
1 and 2 it rests on (Level 2 given Level 1's result), written out by
:mod:`allocator_pkg.dp.report.level3_report`.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ...configuration.parameters import load_vehicle
from ...simulation.electric_plant import PlantSpec
from ...simulation.scenario import load_scenario, vehicle_config
from ...simulation.scenario_check import check_method_serves, check_vehicle
from ...vehicle.config import Vehicle
from ..capability_result import INTACT, WORST, CapabilityResult
from ..inputs.particulars import load_particulars
from ..inputs.site import SiteSea, load_site
from ..level1 import MAX_STEP_DEG, Level1
from ..level2 import Level2
from .case import CRITERIA_NOTE, CaseResult, CaseSetup, Criteria
from .dp_system import describe_dp_system
from .engine import Interrupted, open_engine, run_search
from .journal import Journal
from .search import STATIC, Level3Search

BASE_SCENARIO = Path(__file__).resolve().parents[3] / "config" / "scenarios" / "dp_station_keeping.yaml"
"""The scenario whose controller gains, thruster time constant and environment variations the
cases use (``--scenario``)."""
JOURNAL = "cases.jsonl"


@dataclass(frozen=True)
class Level3Inputs:
    """What a study runs on: the two files, the base scenario, an optional site, the method,
    the heading step [deg] and the criteria (the seeds per condition among them)."""

    vessel: Path
    particulars: Path
    scenario: Path = BASE_SCENARIO
    site: Path | None = None
    method: str | None = None
    heading_step: float = 10.0
    criteria: Criteria = field(default_factory=Criteria)

    def fingerprint(self) -> dict[str, str]:
        """The journal's header: every input that changes a run, the files by their content (not
        the seeds or how they decide a condition, :data:`~.case.JUDGEMENT_KEYS`: a journal of
        fewer seeds or another quantile is resumed, its runs kept)."""
        def digest(path: Path | None) -> str:
            return hashlib.sha256(path.read_bytes()).hexdigest() if path else ""
        return {"level3": "2", "vessel": digest(self.vessel), "particulars": digest(self.particulars),
                "scenario": digest(self.scenario), "site": digest(self.site), "method": str(self.method),
                "heading_step": repr(self.heading_step), "criteria": self.criteria.run_fingerprint()}


@dataclass(frozen=True)
class Level3Study:
    """The checked set-up: the static Level 2 result (with the Level 1 result it was given) and
    analysis, the case set-up and the search."""

    inputs: Level3Inputs
    level2: CapabilityResult
    analysis: Level2
    setup: CaseSetup
    search: Level3Search


def prepare(inputs: Level3Inputs) -> Level3Study:
    """Check every input and run the static balances; ValueError naming what is wrong."""
    step = inputs.heading_step
    if not 0.0 < step <= 90.0 or not math.isclose(360.0 / step, round(360.0 / step)):
        raise ValueError(f"--headings: a step that divides 360 deg and is at most 90 deg, not {step}")
    vehicle, particulars = load_vehicle(inputs.vessel), load_particulars(inputs.particulars)
    base = load_scenario(inputs.scenario)
    if base.model != "dp_vessel":
        raise ValueError(f"--scenario: a dp_vessel scenario, not {base.model}")
    base = replace(base, vehicle=inputs.vessel.resolve(), particulars=particulars.vessel,
                   method=inputs.method or vehicle.method)
    config = vehicle_config(base.vehicle, base.parameters)
    check_vehicle("dp_vessel", config, str(inputs.vessel))
    check_method_serves(base.method, config)
    check_plant(base.power_plant, config, inputs)
    analysis = Level2(vehicle, particulars, inputs.method, load_site(inputs.site) if inputs.site else None)
    level2 = analysis.run(step, (Level1(vehicle, particulars, inputs.method).run(step),))
    groups = {name: tuple(member for member in members if member in vehicle.names)
              for name, members in analysis.groups.items()}
    setup = CaseSetup(base, tuple(analysis.conditions), groups,
                      frozenset(group.name for group in vehicle.redundancy_groups), inputs.criteria,
                      particulars.hull, particulars.frame, particulars=particulars,
                      sea=analysis.site.sea if analysis.site else SiteSea(),
                      group_sources={group.name: tuple(group.sources) for group in vehicle.redundancy_groups})
    headings = tuple(float(h) for h in level2.headings_deg)
    ceilings = {(heading, case): int(level2.numbers[case][k]) for case in (INTACT, *groups)
                for k, heading in enumerate(headings)}
    search = Level3Search(headings, (INTACT, *groups), inputs.criteria, ceilings, len(analysis.conditions) - 1)
    return Level3Study(inputs, level2, analysis, setup, search)


def check_plant(plant: PlantSpec | None, vehicle: Vehicle, inputs: Level3Inputs) -> None:
    """ValueError when the base scenario's power plant cannot feed the study's vessel: a generator
    set or consumer on a switchboard that is not one of its power sources, or bus ties other
    than the vessel's."""
    if plant is None:
        return
    sources = {source.name for source in vehicle.power_sources}
    named = {s.switchboard for s in plant.generator_sets} | {c.switchboard for c in plant.consumers}
    if named - sources:
        raise ValueError(f"--scenario {inputs.scenario.name}: its power_plant feeds "
                         f"{', '.join(sorted(named - sources))}, not a power source of {inputs.vessel.name} "
                         f"({', '.join(sorted(sources)) or 'none'})")
    ties = {(tie.name, tuple(tie.sources), tie.closed) for tie in vehicle.bus_ties}
    if {(tie.name, tuple(tie.between), tie.closed) for tie in plant.bus_ties} != ties:
        raise ValueError(f"--scenario {inputs.scenario.name}: its power_plant was read for other bus ties than "
                         f"those of {inputs.vessel.name}")


def study(inputs: Level3Inputs, out: Path, workers: int | None = None, scheduler: str | None = None,
          resume: bool = False,
          progress: bool = True) -> tuple[Level3Study, CapabilityResult, dict[tuple, CaseResult]]:
    """Open the engine, check, run every case (journal ``out/cases.jsonl``, touched only once the
    engine and the inputs are known good), and give (study, Level 3 result, cases), the result
    drawn against Level 1 and 2 as published (:func:`published`).
    :class:`~.engine.Interrupted` on SIGINT, the journal resumable."""
    try:
        with open_engine(workers, scheduler) as engine:
            prepared = prepare(inputs)
            journal = Journal(out / JOURNAL, inputs.fingerprint(), resume)
            finished = run_search(prepared.search, prepared.setup, journal, engine, progress=progress)
    except KeyboardInterrupt:
        raise Interrupted(0, None) from None
    return prepared, level3_result(prepared, finished, published(prepared)), finished


def published(prepared: Level3Study) -> tuple[CapabilityResult, CapabilityResult]:
    """Level 1 and Level 2 of the vessel as ``--dnv-level1`` and ``--dnv-level2`` publish them, at
    the standard's heading step (:data:`~allocator_pkg.dp.level1.MAX_STEP_DEG`), for the
    comparison plots: the study's own where its step is that one."""
    level2 = prepared.level2
    if prepared.inputs.heading_step == MAX_STEP_DEG:
        return level2.lower[0], level2
    analysis = prepared.analysis
    level1 = Level1(analysis.vehicle, analysis.particulars, prepared.inputs.method).run(MAX_STEP_DEG)
    return level1, analysis.run(MAX_STEP_DEG, (level1,))


def level3_result(prepared: Level3Study, finished: dict[tuple, CaseResult],
                  lower: tuple[CapabilityResult, ...]) -> CapabilityResult:
    """Numbers per heading and case, the worst single failure the lowest over the groups per
    heading; the limiting wind speed is the number's condition's (no bisection in the time domain);
    ``lower``: the Level 1 and 2 results it is drawn against."""
    search, conditions = prepared.search, prepared.setup.conditions
    headings = np.array(search.headings)
    numbers = {case: np.array([search.outcome((h, case), finished).number for h in search.headings], dtype=int)
               for case in search.cases}
    groups = [case for case in search.cases if case != INTACT]
    numbers[WORST] = np.min([numbers[g] for g in groups], axis=0)
    winds = {case: np.array([conditions[n].wind for n in values]) for case, values in numbers.items()}
    return CapabilityResult(headings, numbers, winds, tuple(notes(prepared, finished)), 3, conditions,
                            lower=lower)


def notes(prepared: Level3Study, finished: dict[tuple, CaseResult]) -> list[str]:
    """What the numbers rest on: criteria, durations, seeds, environment, and per heading and
    case why the number stops where it does."""
    inputs, search = prepared.inputs, prepared.search
    criteria = inputs.criteria
    lines = [f"{CRITERIA_NOTE}: {criteria.describe()}.",
             f"Seeds per condition: {criteria.seeds} (indices 0 ... {criteria.seeds - 1}, the same for every "
             f"condition); a condition holds when the {criteria.quantile:g} quantile ({criteria.quantile_method}) "
             "over its seeds of each run's largest excursion is within its limit; base scenario "
             f"{inputs.scenario.name} (controller gains, thruster time constant, the current's slow variation); "
             f"method {prepared.setup.scenario.method}.",
             environment_note(prepared.setup),
             prepared.analysis.site.describe() if prepared.analysis.site else
             "Environment: Table 2-1 (no site environment given).",
             "Limiting wind speed: the wind of the number's condition (no bisection between conditions in the time "
             "domain)."]
    if prepared.setup.dp_system:
        middle = prepared.setup.conditions[len(prepared.setup.conditions) // 2]
        lines.append(describe_dp_system(prepared.setup.scenario, middle.tp))
    lines.append(power_note(prepared.setup))
    if inputs.heading_step > MAX_STEP_DEG:
        lines.append(f"Headings every {inputs.heading_step:g} deg: coarser than the standard's {MAX_STEP_DEG:g} deg.")
    static = []
    for chain in search.chains():
        outcome = search.outcome(chain, finished)
        if outcome.reason == STATIC:
            static.append(f"{chain[1]} {chain[0]:g} deg: {outcome.number + 1}")
    lines.append("Not simulated, the static Level 2 balance already fails them (case heading: condition): "
                 + ("; ".join(static) if static else "none") + ".")
    return lines


def power_note(setup: CaseSetup) -> str:
    """Where the thrusters' power comes from in the cases."""
    plant = setup.scenario.power_plant
    if plant is None:
        return ("Power: no power plant simulated; the allocator has the vessel file's power sources, if any, at "
                "their capacity, and a named group's loss takes its sources.")
    return (f"Power: the base scenario's simulated power plant ({len(plant.generator_sets)} generator sets with "
            "droop governors, the bus frequency, the power management's available power, "
            f"{'fast load reduction' if plant.load_reduction.enabled else 'no fast load reduction'}; its own events "
            "left out); a named group's loss takes the generator sets of its switchboards with its thrusters.")


def environment_note(setup: CaseSetup) -> str:
    """Where a case's wind, waves and current come from, as :func:`.case.case_environment` builds them."""
    sea = setup.sea
    directions = "wind, waves and current from one heading (Level 1's collinear environment)" if sea.collinear else \
        (f"site directions: waves from {sea.wave_direction or 0.0:g} deg and current from "
         f"{sea.current_direction or 0.0:g} deg relative to the wind (the heading is the wind's)")
    if not setup.spectra:
        return ("Environment: the base scenario's first-order gust at its turbulence intensity and the mean wave drift "
                f"times a first-order factor; {directions}.")
    gusts = {"api": "API", "harris": "Harris"}.get(setup.scenario.environment.wind_spectrum, "NPD")
    crests = (f"a short-crested JONSWAP sea (cos^{sea.spreading:g} spreading, DNV-RP-C205 3.5.8.4, a random "
              "direction per component)") if sea.spreading else "a long-crested JONSWAP sea"
    gamma = "the site's peak factor" if sea.peak_factors else "DNV-RP-C205's peak factor"
    drift = ("mean wave drift [3.7] averaged over the spreading's directions" if sea.spreading
             else "mean wave drift [3.7]")
    return (f"Environment: {gusts} gusts on the mean wind, {crests} of the condition's Hs and Tp "
            f"({gamma}) with Newman's slowly varying drift and the first-order wave motion in the "
            f"position measurement, the mean wind load [3.5] and {drift} of the standard, the current "
            f"with its slow variation; {directions}.")
