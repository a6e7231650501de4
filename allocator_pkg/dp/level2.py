"""DP capability Level 2 of DNV-ST-0111 as this package reads it: the Level 1 balance
(:class:`~.level1.Level1`) with its prescriptive parts replaced where the vessel's own data
are given.

- Wind and current: the particulars' coefficient tables over heading
  (:mod:`.inputs.coefficients`) where given, else [3.5] and [3.6];
- thrust: each thruster's ``thrust_min`` and ``thrust_max`` of the vehicle file, taken as the
  thrust it delivers (no [3.9.3], [3.9.4], [3.11.4] or [3.11.5] loss applied), times share^(2/3)
  (the power-to-thrust relation of [3.9.2]) of the share of its P_B its feeds give it, as in Level
  1 (a lost feed share, a board short of power [3.12]);
- thrust losses: the particulars' ``level2.thrust_loss`` tables where given
  (:mod:`.inputs.loss_tables`): over the thrust direction as a thrust profile (the capability
  programme takes it as it takes Level 1's [3.11.4]/[3.11.5] losses), over the current speed a
  factor on both limits at each condition's current;
- forbidden directions: the vehicle file's ``forbidden_sectors`` instead of the [3.11.3] zones; a
  sector whose race points only at failed thrusters lifts in that case, as a zone does;
- environment: a site's (:mod:`.inputs.site`: its own condition table, or Table 2-1 with the site's
  current, waves or periods) where given, in a file of its own or the particulars'
  ``level2.site``, else Table 2-1.

Kept from Level 1: wave drift [3.7], the dynamic factor 1.25 [3.2.2], a shaft line's rudder
[3.10], the joint power balance [3.12], the search and the redundancy groups. The public
transcription of the standard has no Level 2 text: what is replaced, and how, is this package's
reading (:data:`~.capability_result.SCOPE_L2` says so on every output). Not verified by DNV.
"""

from __future__ import annotations

import math

import numpy as np

from ..capability.thrust_profile import ThrustProfile
from ..hull.environment_loads import RHO_AIR, RHO_WATER
from ..vehicle.config import ActuatorConfig, Vehicle
from .capability_result import SCOPE_L2
from .inputs.loss_tables import check_thrusters
from .inputs.particulars import Particulars
from .inputs.site import SiteEnvironment
from .level1 import Level1
from .standard.interaction_zones import Zone
from .standard.weather import WeatherCondition

AREA_NOTE = ("coefficients: Fx = q A_F,wind Cx, Fy = q A_L,wind Cy, Mz = q A_L,wind Lpp Cn for wind; B T, "
             "A_L,current and A_L,current Lpp for current; the standard's frame, moment about Lpp/2")


TABLE_READING = ("factors linear in the thrust angle (body frame) between rows and around 360 deg, drawn by chords "
                 "every 1 deg and 0.02 of the factor below 1 (never above the linear factor); a fixed thruster at "
                 "its direction, reversed at the opposite one; the speed factor linear in the condition's current, "
                 "held beyond the table, on both thrust limits")


class Level2(Level1):
    """The Level 2 balance of one vehicle and its particulars."""

    level = 2
    scope = SCOPE_L2

    def __init__(self, vehicle: Vehicle, particulars: Particulars, method: str | None = None,
                 site: SiteEnvironment | None = None):
        thrusters = {a.name: a for a in vehicle.actuators if not a.is_surface}
        check_thrusters(particulars.thrust_loss, thrusters)
        self.loss_profiles: dict[str, ThrustProfile] = {
            name: profile for name, table in particulars.thrust_loss.items()
            if (profile := table.profile(_directions(thrusters[name]))) is not None}
        """The direction tables as thrust profiles, by thruster (a fixed one's drawn exactly at its directions)."""
        super().__init__(vehicle, particulars, method)
        self.site = site or particulars.site
        """The site environment in force (a file's, else the particulars' ``level2.site``; None: Table 2-1)."""
        if self.site is not None:
            self.conditions = self.site.conditions

    def standard_loads(self, condition: WeatherCondition, direction: float) -> dict[str, np.ndarray]:
        """[Fx, Fy, Mz] per source [N, N m], the standard's frame: the vessel's coefficients where given."""
        loads = super().standard_loads(condition, direction)
        hull, particulars = self.particulars.hull, self.particulars
        for source, table, rho, speed, areas in (
                ("wind", particulars.wind_coefficients, RHO_AIR, condition.wind,
                 (hull.wind_area_frontal, hull.wind_area_lateral, hull.wind_area_lateral * hull.lpp)),
                ("current", particulars.current_coefficients, RHO_WATER, condition.current,
                 (hull.beam * hull.draught, hull.current_area_lateral, hull.current_area_lateral * hull.lpp))):
            if table is not None:
                loads[source] = 0.5 * rho * speed ** 2 * np.array(areas) * table.at(direction)
        return loads

    def thrust_range(self, name: str, condition: WeatherCondition, direction: float,
                     lost: tuple[str, ...] = ()) -> tuple[float, float]:
        """[low, high] [N]: the vehicle file's thrust limits, times share^(2/3) of its
        :meth:`power_share` (a lost feed share; a board short of power is the balance's) and the
        speed table's factor at the condition's current (:mod:`.inputs.loss_tables`)."""
        actuator = self.actuators[name].config
        share = self.power_share(name, lost)
        if share <= 0.0:
            raise ValueError(f"{name}: every feed lost ({', '.join(actuator.feeds)}) but not the thruster; "
                             "list it in the redundancy group's actuators")
        factor = share ** (2.0 / 3.0)
        if name in self.particulars.thrust_loss:
            factor *= self.particulars.thrust_loss[name].speed_factor(condition.current)
        return actuator.thrust_min * factor, actuator.thrust_max * factor

    def thrust_profiles(self, failed: tuple[str, ...] = ()) -> dict[str, ThrustProfile]:
        """Per working thruster with a direction table, its profile (none: the vehicle file's
        thrust limits hold in every direction)."""
        return {name: profile for name, profile in self.loss_profiles.items() if name not in failed}

    def zones(self, failed: tuple[str, ...] = ()) -> list[Zone]:
        """The vehicle file's forbidden sectors of the working thrusters, but those whose race
        points at a failed thruster only (the bearing from it to the thruster inside the sector):
        a sector lifts with the thruster it protects, as a [3.11.3] zone does."""
        position = {a.name: a.position for a in self.vehicle.actuators}
        zones = []
        for actuator in self.vehicle.actuators:
            if actuator.name in failed or actuator.rotation is None:
                continue
            x, y, _ = actuator.position
            for start, end in actuator.rotation.forbidden_sectors:
                zone = Zone(actuator.name, "(vehicle file)", 0.5 * (start + end), 0.5 * (end - start))
                protected = [name for name in position if name != actuator.name and zone.forbids(
                    math.atan2(y - position[name][1], x - position[name][0]))]
                if not protected or not all(name in failed for name in protected):
                    zones.append(zone)
        return zones

    def notes(self) -> list[str]:
        """Level 1's notes with the method, the thrusters and the sectors of Level 2."""
        notes = super().notes()
        notes[1] = (f"Method {self.method}. The vehicle file gives each thruster's position, type, azimuth range, "
                    "thrust limits and forbidden sectors. " + AREA_NOTE + ". Coefficient tables: "
                    + ", ".join(f"{source} {'given' if table else 'none ([3.5]/[3.6])'}" for source, table in
                                (("wind", self.particulars.wind_coefficients),
                                 ("current", self.particulars.current_coefficients))) + ".")
        notes[3] = "Thrusters (thrust_min / thrust_max [kN] of the vehicle file): " + "; ".join(
            f"{a.name} {a.thrust_min / 1e3:.1f} / {a.thrust_max / 1e3:.1f}" for a in self.vehicle.actuators) + "."
        notes[4] = "Forbidden sectors (vehicle file): " + ("; ".join(
            f"{z.thruster} {math.degrees(z.sector[0]):.1f} to {math.degrees(z.sector[1]):.1f} deg"
            for z in self.zones()) or "none") + " (thrust angle in the body frame, 0 forward, 90 to starboard)."
        tables = self.particulars.thrust_loss
        notes[5] = ("Thrust losses ([3.11.4], [3.11.5], [3.9.3], [3.9.4]): not applied; the vessel's own tables "
                    "(level2.thrust_loss): " + ("; ".join(table.describe() for table in tables.values()) or "none")
                    + (f" ({TABLE_READING}); other thrusters" if tables else "; every thruster")
                    + " the vehicle file's thrust limits in every direction and at every current.")
        notes.insert(2, self.site.describe() if self.site else "Environment: Table 2-1 (no site environment given).")
        return notes


def _directions(actuator: ActuatorConfig) -> tuple[float, ...]:
    """A fixed thruster's thrust directions [rad] (ahead; astern when it reverses); none for a rotatable one."""
    if actuator.rotatable:
        return ()
    angle = math.atan2(actuator.direction[1], actuator.direction[0])
    return (angle, angle + math.pi) if actuator.thrust_min < 0.0 else (angle,)
