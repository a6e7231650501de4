"""A vessel's particulars file (YAML, not a ROS params file): the hull for the simulation's load
model and for DNV-ST-0111 Level 1, and the actuators' Level 1 data. Its keys, one table
(:data:`PARTICULARS_KEYS`, lengths [m], areas [m^2], x positions in the vehicle file's body
frame, forward positive):

- the hull keys the simulation's load model shares (:data:`~allocator_pkg.hull.hull_file.HULL_KEYS`);
- Level 1's hull (:data:`LEVEL1_KEYS`, :class:`~..standard.loads.DnvHull`): the body origin's x
  forward of Lpp/2 and height above the keel, the length under water and its middle, the bow
  angle (Figure 3-2), A_WLaft and A_L,current;
- ``thrusters``: per actuator of the vehicle file, by its name, its Table A-3 row
  (:data:`~..standard.thrust.THRUSTER_KEYS`); ``diameter`` and ``ducted`` may be left to the
  vehicle file's ``actuators.<name>.diameter`` / ``.ducted``, which the analysis checks them
  against (:func:`with_vehicle_geometry`);
- ``level2`` (optional, :data:`LEVEL2_KEYS`): the vessel's own coefficients, a site environment
  in place of Table 2-1 (:mod:`.site`) and thrust-loss tables per thruster (:mod:`.loss_tables`);
- ``skegs`` (optional, :data:`~..standard.losses.SKEG_KEYS`) for [3.11.5] and ``rudders``
  (optional, :data:`~..standard.rudders.RUDDER_KEYS`) for [3.10];
- ``name``. The redundancy groups are the vehicle file's (``redundancy_groups.*``, with
  ``power.*`` and each thruster's ``feeds``): a ``failure_groups`` key is refused, saying so.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ...configuration.file_keys import (
    EACH,
    LIST,
    MAPPING,
    NUMBER,
    TEXT,
    FileKey,
    check_keys,
    finite_number,
    key_named,
    names,
)
from ...configuration.yaml_file import read_yaml
from ...hull.environment_loads import VesselParticulars
from ...hull.hull_file import HULL_KEYS, hull_from_mapping
from ..standard.loads import BodyFrame, DnvHull
from ..standard.losses import SKEG_KEYS, Skeg, skegs_from_list
from ..standard.rudders import RUDDER_KEYS, RudderData, rudders_from_mapping
from ..standard.thrust import THRUSTER_KEYS, ThrusterData
from .coefficients import COEFFICIENT_COLUMNS, CoefficientTable, coefficient_table
from .loss_tables import LOSS_TABLE_KEYS, LossTable, loss_tables
from .site import SITE_KEYS, SiteEnvironment, site_from_mapping

if TYPE_CHECKING:
    from ...vehicle.config import Vehicle

LEVEL1_KEYS = (
    FileKey("body_origin_x", NUMBER, "the vehicle file's origin: forward of Lpp/2", required=True, unit="m",
            range_doc="finite"),
    FileKey("body_origin_height", NUMBER, "the vehicle file's origin: above the keel", required=True, unit="m",
            range_doc="finite"),
    FileKey("los", NUMBER, "Los (foremost to aftmost point under water)", required=True, unit="m",
            minimum=0.0, exclusive_minimum=True),
    FileKey("los_centre_x", NUMBER, "the x of the middle of Los", required=True, unit="m, body frame",
            range_doc="finite"),
    FileKey("bow_angle", NUMBER, "Figure 3-2", required=True, unit="deg", minimum=0.0, maximum=90.0,
            exclusive_minimum=True, exclusive_maximum=True),
    FileKey("waterplane_area_aft", NUMBER, "A_WLaft, aft of Lpp/2 (C_WLaft outside [0.85, 1.15] is clipped as "
            "[3.7] says)", required=True, unit="m^2", minimum=0.0, exclusive_minimum=True),
    FileKey("current_area_lateral", NUMBER, "A_L,current", required=True, unit="m^2", minimum=0.0,
            exclusive_minimum=True),
)
"""Level 1's hull, beside the hull keys (:data:`~allocator_pkg.hull.hull_file.HULL_KEYS`)."""
LEVEL2_KEYS = (
    FileKey("wind_coefficients", MAPPING, "Level 2 only: the vessel's own wind coefficients over heading",
            default_doc="[3.5]", keys=COEFFICIENT_COLUMNS),
    FileKey("current_coefficients", MAPPING, "Level 2 only: the vessel's own current coefficients over heading",
            default_doc="[3.6]", keys=COEFFICIENT_COLUMNS),
    FileKey("site", MAPPING, "Level 2 only: a site environment in place of Table 2-1 (the site file's keys)",
            default_doc="Table 2-1", keys=SITE_KEYS),
    FileKey("thrust_loss", MAPPING, "Level 2 only: per thruster of the vehicle file, by its name, its loss tables",
            default_doc="no loss", keys=LOSS_TABLE_KEYS, item="<thruster>"),
)
"""The vessel's own data for Level 2, each optional."""
PARTICULARS_KEYS = (
    *HULL_KEYS,
    *LEVEL1_KEYS,
    FileKey("thrusters", MAPPING, "per thruster of the vehicle file, by its name, its Table A-3 row; every one "
            "needs a row", required=True, keys=THRUSTER_KEYS, item="<actuator>"),
    FileKey("name", TEXT, "the vessel's name", default_doc="the file's name"),
    FileKey("level2", MAPPING, "the vessel's own data for Level 2", keys=LEVEL2_KEYS),
    FileKey("skegs", LIST, "the aft most point of each skeg or gondola (Table A-2), for [3.11.5]",
            default_doc="none: no skeg loss", keys=SKEG_KEYS, item=EACH),
    FileKey("rudders", MAPPING, "per control surface of the vehicle file, by its name, its Table A-4 row for "
            "[3.10]", default_doc="none", keys=RUDDER_KEYS, item="<rudder>"),
)
"""Every key of a particulars file."""
MOVED_GROUPS = ("failure_groups: the redundancy groups are in the vehicle params file: redundancy_groups.names and "
                "redundancy_groups.<group>.actuators / .sources, with power.sources and actuators.<name>.feeds")


@dataclass(frozen=True)
class Particulars:
    """A particulars file: ``vessel`` for the simulation's loads, ``hull`` and ``frame`` for
    Level 1 (the hull in the standard's frame), the actuators' Level 1 data by name."""

    vessel: VesselParticulars
    hull: DnvHull
    frame: BodyFrame
    thrusters: Mapping[str, ThrusterData]
    name: str = ""
    wind_coefficients: CoefficientTable | None = None
    """Level 2: the vessel's wind coefficients over heading (None: [3.5])."""
    current_coefficients: CoefficientTable | None = None
    """Level 2: the vessel's current coefficients over heading (None: [3.6])."""
    site: SiteEnvironment | None = None
    """Level 2: the site environment in place of Table 2-1 (None: Table 2-1)."""
    thrust_loss: Mapping[str, LossTable] = field(default_factory=dict)
    """Level 2: the vessel's thrust-loss tables per thruster, by name (none: no loss)."""
    skegs: tuple[Skeg, ...] = ()
    """The aft most point of each skeg or gondola (body frame) for [3.11.5]."""
    rudders: Mapping[str, RudderData] = field(default_factory=dict)
    """Table A-4 per rudder of the vehicle file, by name, for [3.10]."""


def load_particulars(path: str | Path) -> Particulars:
    """Read a particulars file (YAML); every error names the path."""
    return read_particulars(path)[0]


def read_particulars(path: str | Path) -> tuple[Particulars, str]:
    """A particulars file and its text (what its comments state), from one read; every error
    names the path."""
    path = Path(path)
    data, text = read_yaml(path, "a particulars file")
    try:
        return particulars_from_mapping(data, path.stem), text
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from error


def particulars_from_mapping(data: Mapping[str, Any], name: str = "") -> Particulars:
    """The particulars of a mapping with the keys of a particulars file."""
    if not isinstance(data, Mapping):
        raise ValueError("a particulars file is a mapping of keys to values")
    if "failure_groups" in data:
        raise ValueError(MOVED_GROUPS)
    check_keys(data, PARTICULARS_KEYS, sort_known=True)
    numbers = {key.name: finite_number(data[key.name], key.name) for key in LEVEL1_KEYS}
    vessel = hull_from_mapping(data)
    frame = BodyFrame(numbers["body_origin_x"], numbers["body_origin_height"])
    bow = key_named(LEVEL1_KEYS, "bow_angle")
    if not bow.holds(numbers["bow_angle"]):
        raise ValueError(f"bow_angle: between {bow.minimum:g} and {bow.maximum:g} {bow.unit}, not "
                         f"{numbers['bow_angle']:g}")
    hull = DnvHull(lpp=vessel.lpp, beam=vessel.beam, draught=vessel.draught, los=numbers["los"],
                   los_centre_x=frame.standard_x(numbers["los_centre_x"]),
                   bow_angle=math.radians(numbers["bow_angle"]), waterplane_area_aft=numbers["waterplane_area_aft"],
                   wind_area_frontal=vessel.wind_area_frontal, wind_area_lateral=vessel.wind_area_lateral,
                   wind_centre_x=frame.standard_x(vessel.wind_centre_x),
                   current_area_lateral=numbers["current_area_lateral"],
                   current_centre_x=frame.standard_x(vessel.underwater_centre_x))
    return Particulars(vessel=vessel, hull=hull, frame=frame, thrusters=_thrusters(data["thrusters"]),
                       name=str(data.get("name", name)), skegs=skegs_from_list(data.get("skegs")),
                       rudders=rudders_from_mapping(data.get("rudders")),
                       **_level2(data.get("level2")))


def with_vehicle_geometry(particulars: Particulars, vehicle: Vehicle) -> Particulars:
    """The particulars with each thruster's D and duct one definition with the vehicle file's
    ``actuators.<name>.diameter`` / ``.ducted`` / ``.tunnel`` (the runtime flushing zones'): a value
    the particulars leave out is the vehicle file's; one both give must agree, and ``kind`` is
    ``tunnel`` where the vehicle file says ``tunnel: true``; refused naming both keys otherwise. The
    vehicle file's ``ducted: false`` and ``diameter: 0`` are its defaults, read as not given."""
    thrusters = {}
    for name, data in particulars.thrusters.items():
        actuator = next((a for a in vehicle.actuators if a.name == name), None)
        if actuator is None:
            thrusters[name] = data
            continue
        pair = f"thrusters.{name}.{{0}} and actuators.{name}.{{0}}"
        if data.diameter is None and actuator.diameter <= 0.0:
            raise ValueError(f"thrusters.{name}.diameter: missing, and the vehicle file gives no "
                             f"actuators.{name}.diameter; Level 1 needs D ([3.9.2])")
        if data.diameter is not None and actuator.diameter > 0.0 and data.diameter != actuator.diameter:
            raise ValueError(pair.format("diameter") + f" differ ({data.diameter:g} and {actuator.diameter:g} m); "
                             "give it once")
        if data.ducted is False and actuator.ducted:
            raise ValueError(pair.format("ducted") + " differ (false and true); give it once")
        if actuator.tunnel and data.kind != "tunnel":
            raise ValueError(f"thrusters.{name}.kind: {data.kind}, but the vehicle file's actuators.{name}.tunnel "
                             "is true")
        thrusters[name] = replace(data, diameter=actuator.diameter if data.diameter is None else data.diameter,
                                  ducted=actuator.ducted if data.ducted is None else data.ducted)
    return replace(particulars, thrusters=thrusters)


def _thrusters(thrusters: Any) -> dict[str, ThrusterData]:
    if not isinstance(thrusters, Mapping) or not thrusters:
        raise ValueError("thrusters: a mapping of the vehicle file's actuator names to their Level 1 data")
    result = {}
    for name, row in thrusters.items():
        if not isinstance(row, Mapping):
            raise ValueError(f"thrusters.{name}: a mapping with keys {', '.join(names(THRUSTER_KEYS))}")
        check_keys(row, THRUSTER_KEYS, f"thrusters.{name}")
        result[str(name)] = ThrusterData(name=str(name), **{"diameter": None, "ducted": None, **row})
    return result


def _level2(level2: Any) -> dict[str, Any]:
    if level2 is None:
        return {}
    keys = names(LEVEL2_KEYS)
    if not isinstance(level2, Mapping) or set(level2) - set(keys):
        raise ValueError(f"level2: a mapping with {', '.join(keys)} (each optional)")
    result: dict[str, Any] = {
        key: coefficient_table(level2[key], f"level2.{key}") for key in keys[:2] if key in level2}
    if "site" in level2:
        result["site"] = site_from_mapping(level2["site"], "level2.site", "the particulars' level2.site")
    if "thrust_loss" in level2:
        result["thrust_loss"] = loss_tables(level2["thrust_loss"])
    return result
