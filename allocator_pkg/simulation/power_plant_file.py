"""Reading a scenario's ``power_plant`` section (:data:`~.power_plant_keys.POWER_PLANT`) into a
:class:`~.electric_plant.PlantSpec`, each mistake refused with its key (``ScenarioError``): a
switchboard that is not a power source of the vehicle, a name given twice, a frequency band
that does not hold 1 pu, a bus (by the vehicle's ties closed at start) without a connected set."""

from __future__ import annotations

from typing import Any

from ..vehicle.config import Vehicle
from .bus_frequency import BusTieSpec, buses
from .electric_plant import Consumer, PlantSpec
from .generator_set import GeneratorSetSpec
from .metrics import PLANT_METRICS
from .power_management import LoadReductionSpec, PowerManagementSpec
from .scenario_values import ScenarioError, number, section

ROOT = "power_plant."


def _flag(data: dict, key: str, where: str, default: bool) -> bool:
    value = data.get(key, default)
    if not isinstance(value, bool):
        raise ScenarioError(f"{where}{key}: true or false, not {value!r}")
    return value


def _name(data: Any, key: str, where: str, known: list[str] | None = None, what: str = "") -> str:
    value = data.get(key) if isinstance(data, dict) else None
    if not isinstance(value, str) or not value:
        raise ScenarioError(f"{where}{key}: required, a name")
    if known is not None and value not in known:
        raise ScenarioError(f"{where}{key}: '{value}' is not {what} (" + (", ".join(known) or "it has none") + ")")
    return value


def _items(data: dict, key: str) -> list[tuple[str, dict]]:
    value = data.get(key, []) or []
    if not isinstance(value, list):
        raise ScenarioError(f"{ROOT}{key}: a list, not {value!r}")
    for index, item in enumerate(value):
        if not isinstance(item, dict):
            raise ScenarioError(f"{ROOT}{key}[{index}]: a mapping, not {item!r}")
    return [(f"{ROOT}{key}[{index}].", item) for index, item in enumerate(value)]


def _generator_set(item: dict, where: str, sources: list[str]) -> GeneratorSetSpec:
    values = {key: number(item, key, where) for key in (
        "rating", "power_factor", "inertia", "droop", "governor_time_constant", "p_max", "step_allowance", "ramp_max",
        "under_frequency", "over_frequency", "trip_delay")}
    return GeneratorSetSpec(name=_name(item, "name", where),
                            switchboard=_name(item, "switchboard", where, sources, "a power source of the vehicle"),
                            connected=_flag(item, "connected", where, True), **values)


def _unique(names: list[str], where: str) -> None:
    repeated = sorted({name for name in names if names.count(name) > 1})
    if repeated:
        raise ScenarioError(f"{where}: names given twice: {', '.join(repeated)}")


def read_power_plant(data: Any, vehicle: Vehicle) -> PlantSpec:
    """The plant of a scenario's ``power_plant`` mapping for ``vehicle``."""
    if not isinstance(data, dict):
        raise ScenarioError(f"power_plant: a mapping, not {data!r}")
    sources = [source.name for source in vehicle.power_sources]
    if not sources:
        raise ScenarioError("power_plant: the vehicle has no power sources (power.sources) for it to feed")
    sets = [_generator_set(item, where, sources) for where, item in _items(data, "generator_sets")]
    if not sets:
        raise ScenarioError(f"{ROOT}generator_sets: at least one generator set")
    _unique([s.name for s in sets], f"{ROOT}generator_sets")
    for index, s in enumerate(sets):
        if not s.under_frequency < 1.0 < s.over_frequency:
            raise ScenarioError(f"{ROOT}generator_sets[{index}]: under_frequency < 1 < over_frequency")
    ties = [BusTieSpec(tie.name, tie.sources, tie.closed) for tie in vehicle.bus_ties]
    consumers = [Consumer(_name(item, "switchboard", where, sources, "a power source of the vehicle"),
                             number(item, "power", where), number(item, "start", where), number(item, "on_time", where),
                             number(item, "off_time", where)) for where, item in _items(data, "consumers")]
    management = section(data, "management")
    reduction = section(data, "load_reduction")
    where = ROOT + "load_reduction."
    spec = LoadReductionSpec(enabled=_flag(reduction, "enabled", where, True),
                             reaction_time=number(reduction, "reaction_time", where),
                             restore_time=number(reduction, "restore_time", where),
                             frequency_start=number(reduction, "frequency_start", where),
                             frequency_zero=number(reduction, "frequency_zero", where))
    if not spec.frequency_zero < spec.frequency_start:
        raise ScenarioError(f"{where}frequency_zero: below frequency_start ({spec.frequency_start:g}), "
                            f"not {spec.frequency_zero:g}")
    plant = PlantSpec(
        generator_sets=tuple(sets), bus_ties=tuple(ties),
        consumers=tuple(consumers),
        management=PowerManagementSpec(number(management, "reaction_time", ROOT + "management."),
                                       number(management, "ramp_time", ROOT + "management.")),
        load_reduction=spec)
    unfed = _unfed(sources, ties, sets)
    if unfed:
        raise ScenarioError(f"{ROOT}generator_sets: no connected set feeds {', '.join(unfed)}, nor any switchboard "
                            "a closed bus tie (power.bus_ties of the vehicle) joins it to")
    return plant


def _unfed(sources: list[str], ties: list[BusTieSpec], sets: list[GeneratorSetSpec]) -> list[str]:
    """The switchboards whose bus (by the ties closed at start) has no connected set."""
    groups = buses(sources, {t.name: t for t in ties}, {t.name: t.closed for t in ties})
    fed = {s.switchboard for s in sets if s.connected}
    return [name for group in groups if not fed & set(group) for name in group]


PLANT_EVENTS = {"generator_trip": "generator_set"}
"""The events that need a ``power_plant``, and the key naming what of it they act on."""
SOURCE_EVENTS = ("power", "group_fault")
"""The events that set a source's power by hand, which a simulated plant gives by itself."""


def check_plant_events(events: list, plant: PlantSpec | None) -> None:
    """Raise ScenarioError for an event the plant (None: no ``power_plant``) cannot take."""
    for index, event in enumerate(events):
        if event.kind in PLANT_EVENTS and plant is None:
            raise ScenarioError(f"events[{index}].{event.kind}: needs a power_plant section")
        if event.kind in SOURCE_EVENTS and plant is not None:
            raise ScenarioError(f"events[{index}].{event.kind}: the power_plant gives each source's power; "
                                "use generator_trip")
        if event.kind != "generator_trip":
            continue
        known = [s.name for s in plant.generator_sets]
        if event.name not in known:
            key = PLANT_EVENTS[event.kind]
            raise ScenarioError(f"events[{index}].{event.kind}.{key}: '{event.name}' is not one of "
                                + (", ".join(known) or "none"))


def check_plant_bounds(bounds: dict[str, float], plant: PlantSpec | None) -> None:
    """Raise ScenarioError for a bound on a power plant's metric without a ``power_plant``."""
    named = [name for name in bounds if name in PLANT_METRICS]
    if named and plant is None:
        raise ScenarioError(f"bounds.{named[0]}: a power plant's metric; the scenario has no power_plant")
