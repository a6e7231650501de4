"""A vessel's particulars file (YAML, not a ROS params file): the hull for the simulation's load
model and for DNV-ST-0111 Level 1, and the actuators' Level 1 data.

Keys (lengths [m], areas [m^2]; x positions in the vehicle file's body frame, forward positive):

- ``lpp``, ``beam``, ``draught``, ``wind_area_frontal``, ``wind_area_lateral`` (> 0), ``wind_centre_x``
  (centre of the lateral wind area), ``underwater_centre_x`` (centre of the lateral underwater
  area, the standard's x_L,current), ``coefficients`` (the simulation's load model only,
  :class:`~allocator_pkg.hull.environment_loads.LoadCoefficients`): shared by both models;
- ``body_origin_x`` (the body origin's x forward of Lpp/2), ``body_origin_height`` (its height
  above the keel), ``los`` and ``los_centre_x`` (the length under water and the x of its middle),
  ``bow_angle`` [deg, 0-90] (Figure 3-2), ``waterplane_area_aft`` (A_WLaft, aft of Lpp/2),
  ``current_area_lateral`` (A_L,current): Level 1's hull (:class:`~.dnv_loads.DnvHull`);
- ``thrusters``: per actuator of the vehicle file, by its name, its Table A-3 row
  (:class:`~.dnv_thrust.ThrusterData`: ``kind``, ``diameter`` [m], ``power`` P_B [kW], ``pitch``,
  ``ducted``, ``contra_rotating``, ``permanent_magnet``, ``tunnel_inlet``); ``diameter`` and
  ``ducted`` may be left to the vehicle file's ``actuators.<name>.diameter`` / ``.ducted``, which
  the analysis checks them against (:func:`with_vehicle_geometry`);
- ``level2`` (optional): the vessel's own data for Level 2, ``wind_coefficients`` and
  ``current_coefficients`` (:class:`~.dnv_coefficients.CoefficientTable`: ``heading_deg``,
  ``cx``, ``cy``, ``cn``), ``site``: a site environment in place of Table 2-1
  (:mod:`.dnv_site`), and ``thrust_loss``: per thruster, by its name, its loss tables over the
  thrust direction and over the current speed (:mod:`.dnv_loss_tables`);
- ``skegs`` (optional): the aft most point of each skeg or gondola, ``x`` and ``y`` [m] in the
  body frame (Table A-2), for the skeg loss of [3.11.5] (:func:`~.dnv_losses.skegs_from_list`);
- ``rudders`` (optional): per rudder of the vehicle file, by its name, its Table A-4 row for
  [3.10] (:class:`~.dnv_rudders.RudderData`: ``propeller``, ``profile``, ``area`` A_r [m^2],
  ``behind_fixed_nozzle``);
- ``name``. The redundancy groups are the vehicle file's (``redundancy_groups.*``, with
  ``power.*`` and each thruster's ``feeds``): a ``failure_groups`` key is refused, saying so.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ...configuration.yaml_file import read_mapping
from ...hull.environment_loads import VesselParticulars
from ...hull.hull_file import HULL_KEYS, finite_number, hull_from_mapping
from ..standard.loads import BodyFrame, DnvHull
from ..standard.losses import Skeg, skegs_from_list
from ..standard.rudders import RudderData, rudders_from_mapping
from ..standard.thrust import ThrusterData
from .coefficients import CoefficientTable, coefficient_table
from .loss_tables import LossTable, loss_tables
from .site import SiteEnvironment, site_from_mapping

if TYPE_CHECKING:
    from ...vehicle.config import Vehicle

LEVEL1_KEYS = ("body_origin_x", "body_origin_height", "los", "los_centre_x", "bow_angle", "waterplane_area_aft",
               "current_area_lateral")
THRUSTER_KEYS = tuple(f.name for f in fields(ThrusterData) if f.name != "name")
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
    path = Path(path)
    data = read_mapping(path, "a particulars file")
    try:
        return particulars_from_mapping(data, path.stem)
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from error


def particulars_from_mapping(data: Mapping[str, Any], name: str = "") -> Particulars:
    """The particulars of a mapping with the keys of a particulars file."""
    if not isinstance(data, Mapping):
        raise ValueError("a particulars file is a mapping of keys to values")
    if "failure_groups" in data:
        raise ValueError(MOVED_GROUPS)
    known = {*HULL_KEYS, *LEVEL1_KEYS, "coefficients", "thrusters", "name", "level2", "skegs", "rudders"}
    unknown = sorted(set(data) - known)
    if unknown:
        raise ValueError(f"unknown key(s): {', '.join(unknown)}; known: {', '.join(sorted(known))}")
    missing = [key for key in (*HULL_KEYS[:5], *LEVEL1_KEYS, "thrusters") if key not in data]
    if missing:
        raise ValueError(f"missing key(s): {', '.join(missing)}")
    numbers = {key: finite_number(data, key) for key in LEVEL1_KEYS}
    vessel = hull_from_mapping(data)
    frame = BodyFrame(numbers["body_origin_x"], numbers["body_origin_height"])
    if not 0.0 < numbers["bow_angle"] < 90.0:
        raise ValueError(f"bow_angle: between 0 and 90 deg, not {numbers['bow_angle']:g}")
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
            raise ValueError(f"thrusters.{name}: a mapping with keys {', '.join(THRUSTER_KEYS)}")
        unknown = sorted(set(row) - set(THRUSTER_KEYS))
        if unknown:
            raise ValueError(f"thrusters.{name}: unknown key(s) {', '.join(unknown)}; "
                             f"known: {', '.join(THRUSTER_KEYS)}")
        missing = [key for key in ("kind", "power") if key not in row]
        if missing:
            raise ValueError(f"thrusters.{name}: missing key(s) {', '.join(missing)}")
        result[str(name)] = ThrusterData(name=str(name), **{"diameter": None, "ducted": None, **row})
    return result


def _level2(level2: Any) -> dict[str, Any]:
    if level2 is None:
        return {}
    keys = ("wind_coefficients", "current_coefficients", "site", "thrust_loss")
    if not isinstance(level2, Mapping) or set(level2) - set(keys):
        raise ValueError(f"level2: a mapping with {', '.join(keys)} (each optional)")
    result: dict[str, Any] = {
        key: coefficient_table(level2[key], f"level2.{key}") for key in keys[:2] if key in level2}
    if "site" in level2:
        result["site"] = site_from_mapping(level2["site"], "level2.site", "the particulars' level2.site")
    if "thrust_loss" in level2:
        result["thrust_loss"] = loss_tables(level2["thrust_loss"])
    return result
