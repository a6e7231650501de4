"""DP capability Level 1 of DNV-ST-0111 (edition December 2021): the highest environmental
condition held per heading.

Level 1 is a quasi-static balance: for each heading of the environment (wind, waves and current
from the same direction [3.3.1]), the loads of the condition of each DP capability number (0-11,
Table 2-1: :data:`WEATHER_CONDITIONS`) times the dynamic factor :data:`DYNAMIC_FACTOR` [3.2.2] must be
balanced by the thrusters. The number of a heading is the highest condition balanced with every
lower one balanced too; the limiting wind speed the highest wind balanced when the conditions
between two numbers are interpolated linearly (:func:`condition_at`). This is done intact and
for each redundancy group of the vehicle file (actuators and power sources lost together; a
thruster fed in part by a lost source keeps its remaining share of P_B, :meth:`Level1.power_share`);
the worst single failure is, per heading, the lowest over the groups.
:meth:`~.capability_result.CapabilityResult.summary` gives DP capability-L1(A, B, C, D).
:meth:`Level1.run` gives the complete result: the numbers and, per case and heading, the
allocation behind Tables A-8 to A-10 (:meth:`Level1.thruster_use`).

Per the standard: the loads of [3.5]-[3.7] (:mod:`.standard.loads`); each actuator's thrust from its
type, diameter and power, T_nominal [3.9.2] times beta_misc [3.9.3] and the ventilation loss
beta_vent [3.9.4] of the condition and heading (:mod:`.standard.thrust`); the forbidden zones of
[3.11.3] among the thrusters working in the case (:mod:`.standard.interaction_zones`), in place of the vehicle
file's forbidden sectors; the losses flushing the case's dead thrusters [3.11.4] and skegs
[3.11.5] by thrust direction (:mod:`.standard.losses`); a shaft line's rudder [3.10] (:mod:`.standard.rudders`).
Per (condition, heading, case) a variant of the vehicle, its working thrusters with those thrust
ranges, zones and losses, is balanced as :meth:`~..capability.envelope.Capability.attains` would (a
linear programme with the configured method's constraints), jointly with the power of each source
that could be short ([3.12.3]-[3.12.5], :mod:`.standard.power_balance`), on the case's programmes
kept from one balance to the next (:mod:`.case_balance`). The search per heading stays the rising
one of :func:`.standard.weather.limit`. Not yet: :data:`~.capability_result.NOT_YET`. Not verified by DNV.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..capability.envelope import Capability
from ..capability.thrust_profile import ForceProfile, ThrustProfile
from ..vehicle.config import DOF_NAMES, ActuatorConfig, Vehicle
from .capability_result import INTACT, SCOPE_L1, WORST, Allocation, CapabilityResult, ThrusterUse
from .case_balance import MARGIN, CaseBalance, authority_scale
from .inputs.particulars import Particulars, with_vehicle_geometry
from .notes import hull_note, source_note, thruster_note
from .standard.interaction_zones import Unit, Zone, flushing_zones
from .standard.loads import LoadComponents, current_load, wave_drift_load, wind_load
from .standard.losses import case_profiles, describe_losses, loss_units
from .standard.power_balance import PoweredCapability, PowerLimits, demand, feed_share, power_limits
from .standard.rudders import describe_rudders, force_profiles, rudder_pairs
from .standard.thrust import BETA_MISC, nominal_thrust, ventilation_factor
from .standard.weather import WEATHER_CONDITIONS, WeatherCondition, condition_at, limit

DYNAMIC_FACTOR = 1.25
"""[3.2.2]: on the sum of the environmental loads."""
MAX_STEP_DEG = 10.0
"""The standard asks for headings this far apart or closer."""
LOAD_SOURCES = ("wind", "current", "waves")
POWER_READING = ("A group's loss fails its actuators; a thruster outside it fed in part by a lost source keeps the "
                 "P_B of its remaining feed shares, (1 - s) P_B, so T_nominal (1 - s)^(2/3) [3.9.2] ([3.12] and "
                 "Table A-5 as transcribed: what it can consume from each source). Each source keeps 10 % of its "
                 "capacity for hotel and non-thruster consumers [3.12.3]-[3.12.4]; in each balance the power its "
                 "working thrusters draw, s P_B r^(3/2) at the thrust fraction r, stays within the rest.")


@dataclass(frozen=True)
class _Actuator:
    """What Level 1 needs of one thruster: its data, x [m forward of Lpp/2], submergence [m],
    the horizontal angle [rad] its positive thrust pushes along (fixed thrusters) and the nominal
    thrust [N] either way (reverse 0 when the vehicle file does not reverse it)."""

    config: ActuatorConfig
    x: float
    submergence: float
    angle: float
    forward: float
    reverse: float


class Level1:
    """The Level 1 balance of one vehicle and its particulars."""

    level = 1
    scope = SCOPE_L1

    def __init__(self, vehicle: Vehicle, particulars: Particulars, method: str | None = None):
        self.vehicle = vehicle
        self.particulars = with_vehicle_geometry(particulars, vehicle)
        """The particulars, each thruster's D and duct joined with the vehicle file's."""
        particulars = self.particulars
        self.groups = ({g.name: (*g.actuators, *g.sources) for g in vehicle.redundancy_groups}
                       or {name: (name,) for name in vehicle.names})
        """What each group's loss takes away: its actuators, then its power sources (the vehicle
        file's redundancy groups; without any, each actuator alone)."""
        self.actuators = _actuators(vehicle, particulars)
        self.loss_units = loss_units(vehicle.actuators, particulars.thrusters, particulars.frame)
        self.rudders = rudder_pairs(vehicle, particulars.thrusters, particulars.rudders)
        self.capacities = {source.name: source.capacity for source in vehicle.power_sources}
        self.conditions = WEATHER_CONDITIONS
        """The condition of each capability number: Table 2-1."""
        self.method = method or vehicle.method
        self.uncontrolled = [DOF_NAMES.index(d) for d in ("surge", "sway", "yaw") if d not in vehicle.dofs]
        self._zones: dict[tuple[str, ...], list[Zone]] = {}
        self._profiles: dict[tuple[str, ...], dict[str, ThrustProfile]] = {}
        self._capabilities: dict[tuple, Capability] = {}
        self._winners: dict[tuple[str, ...], int] = {}
        self._power: dict[tuple[str, ...], PowerLimits | None] = {}
        self._balances: dict[tuple, CaseBalance | None] = {}
        self.capability(vehicle)                               # the method can serve the vehicle

    def loads(self, condition: WeatherCondition, direction: float) -> LoadComponents:
        """The unfactored wind, current and wave loads [X, Y, N] (body frame) from ``direction``."""
        loads = self.standard_loads(condition, direction)
        return LoadComponents(*(self.particulars.frame.load(loads[source]) for source in LOAD_SOURCES))

    def standard_loads(self, condition: WeatherCondition, direction: float) -> dict[str, np.ndarray]:
        """The unfactored [Fx, Fy, Mz] of wind [3.5], current [3.6] and waves [3.7] in the
        standard's frame [2.8.2] [N, N m]."""
        hull = self.particulars.hull
        return {"wind": wind_load(hull, condition.wind, direction),
                "current": current_load(hull, condition.current, direction),
                "waves": wave_drift_load(hull, condition.hs, condition.tp, direction)}

    def power_share(self, name: str, lost: tuple[str, ...] = ()) -> float:
        """The share of its P_B a thruster keeps when ``lost`` (actuators and sources) are: the
        sum of its remaining feed shares (Table A-5); 1 for a thruster without feeds."""
        return feed_share(self.vehicle, name, lost)

    def source_demand(self, source: str, lost: tuple[str, ...] = ()) -> float:
        """[kW] what the working thrusters a source feeds draw from it at full thrust: the sum of
        feed share times P_B (Table A-5)."""
        return demand(self.vehicle, self.powers, source, lost)

    @property
    def powers(self) -> dict[str, float]:
        """P_B [kW] by thruster (the particulars')."""
        return {name: self.particulars.thrusters[name].power for name in self.actuators}

    def power_limits(self, lost: tuple[str, ...] = ()) -> PowerLimits | None:
        """The power rows of a case ([3.12.3]-[3.12.5], :func:`.standard.power_balance.power_limits`); None when
        no working source could be short."""
        if lost not in self._power:
            self._power[lost] = power_limits(self.vehicle, self.powers, lost)
        return self._power[lost]

    def thrust_range(self, name: str, condition: WeatherCondition, direction: float,
                     lost: tuple[str, ...] = ()) -> tuple[float, float]:
        """[low, high] [N] of one thruster: nominal thrust times beta_misc and beta_vent, each way.
        A thruster runs on the P_B times its :meth:`power_share` (what its remaining feeds can give
        it): T_nominal times share^(2/3) [3.9.2], beta_vent of that T_nominal. What a source short of
        power allows is the balance's (:meth:`capability`)."""
        unit = self.actuators[name]
        data = self.particulars.thrusters[name]
        share = self.power_share(name, lost)
        if share <= 0.0:
            raise ValueError(f"{name}: every feed lost ({', '.join(unit.config.feeds)}) but not the thruster; "
                             "list it in the redundancy group's actuators")
        if share < 1.0:
            data = replace(data, power=data.power * share)
            unit = replace(unit, forward=nominal_thrust(data) if unit.forward else 0.0,
                           reverse=nominal_thrust(data, reverse=True) if unit.reverse else 0.0)

        def effective(nominal: float, reverse: bool) -> float:
            if nominal == 0.0:
                return 0.0
            return nominal * BETA_MISC * ventilation_factor(data, unit.x, unit.submergence, self.particulars.hull.lpp,
                                                            condition.hs, condition.tp, direction, reverse)

        return 0.0 - effective(unit.reverse, True), effective(unit.forward, False)

    def zones(self, failed: tuple[str, ...] = ()) -> list[Zone]:
        """The [3.11.3] zones among the thrusters that work when ``failed`` are lost."""
        if failed not in self._zones:
            self._zones[failed] = flushing_zones([
                Unit(name, unit.config.position[0], unit.config.position[1],
                     self.particulars.thrusters[name].diameter, self.particulars.thrusters[name].kind == "tunnel")
                for name, unit in self.actuators.items() if name not in failed])
        return self._zones[failed]

    def thrust_profiles(self, failed: tuple[str, ...] = ()) -> dict[str, ThrustProfile]:
        """Per working thruster with a loss, its [3.11.4] and [3.11.5] factor by direction (:mod:`.standard.losses`)."""
        dead = tuple(name for name in self.actuators if name in failed)
        if dead not in self._profiles:
            self._profiles[dead] = case_profiles(self.loss_units, dead, self.particulars.skegs)
        return self._profiles[dead]

    def variant(self, condition: WeatherCondition, direction: float, failed: tuple[str, ...] = ()) -> Vehicle:
        """The vehicle's working thrusters (the failed ones left out) with Level 1's thrust ranges and
        zones for the condition, heading and case (a fixed thruster's range times its loss factors):
        the zones of the case, none to lift or add (no ``protects``, ``flushing_zones`` none)."""
        zones, profiles = self.zones(failed), self.thrust_profiles(failed)
        actuators = []
        for actuator in self.vehicle.actuators:
            if actuator.name in failed or actuator.is_surface:
                continue
            unit = self.actuators[actuator.name]
            low, high = self.thrust_range(actuator.name, condition, direction, failed)
            own = [zone for zone in zones if zone.thruster == actuator.name]
            if actuator.rotatable:
                rotation = replace(actuator.rotation, forbidden_sectors=tuple(zone.sector for zone in own), protects=())
                actuators.append(replace(actuator, thrust_min=low, thrust_max=high, rotation=rotation))
                continue
            if actuator.name in profiles:
                low, high = (low * profiles[actuator.name].factor(unit.angle + math.pi),
                             high * profiles[actuator.name].factor(unit.angle))
            if any(zone.forbids(unit.angle) for zone in own):
                high = 0.0
            if any(zone.forbids(unit.angle + math.pi) for zone in own):
                low = 0.0
            pair, fixed = self.rudders.get(actuator.name), replace(actuator, thrust_min=low, thrust_max=high)
            actuators.append(pair.turned(fixed) if pair and pair.rudder not in failed else fixed)
        return replace(self.vehicle, actuators=tuple(actuators), flushing_zones="none")

    def variant_profiles(self, variant: Vehicle) -> dict[str, ForceProfile]:
        """What the capability analysis takes for a variant's rotatable thrusters: the
        :meth:`thrust_profiles` of its case (the thrusters it leaves out), a turned shaft line's rudder fan."""
        dead = tuple(sorted(set(self.actuators) - {a.name for a in variant.actuators}))
        return force_profiles(variant, self.thrust_profiles(dead), self.rudders)

    def capability(self, variant: Vehicle, failed: tuple[str, ...] | None = None) -> Capability:
        """The capability analysis of a variant with its case's :meth:`thrust_profiles` (the case:
        the thrusters it leaves out), kept by its ranges, zones and profiles; with the power rows of
        the case that loses ``failed`` (None: without power rows)."""
        profiles = self.variant_profiles(variant)
        limits = None if failed is None else self.power_limits(failed)
        key = (tuple((a.name, a.thrust_min, a.thrust_max, a.rotation.forbidden_sectors if a.rotation else (),
                      profiles.get(a.name)) for a in variant.actuators), limits.key() if limits else None)
        if key not in self._capabilities:
            self._capabilities[key] = (Capability(variant, self.method, speed=0.0, profiles=profiles) if limits is None
                                       else PoweredCapability(variant, self.method, limits, profiles))
        return self._capabilities[key]

    def case_balance(self, variant: Vehicle, failed: tuple[str, ...]) -> CaseBalance | None:
        """The kept programmes of the case that loses ``failed`` (:class:`.case_balance.CaseBalance`),
        set up at its first variant; None for a method that cannot redistribute force."""
        key = (failed, tuple(a.name for a in variant.actuators))
        if key not in self._balances:
            kept = self.capability(variant, failed)
            self._balances[key] = None if kept.sides is None else CaseBalance(kept, self.power_limits(failed))
        return self._balances[key]

    def required(self, condition: WeatherCondition, direction: float) -> np.ndarray:
        """The wrench [X, Y, Z, K, M, N] (body frame) the thrusters must give: -1.25 times the loads."""
        tau = np.zeros(6)
        tau[[0, 1, 5]] = -DYNAMIC_FACTOR * self.loads(condition, direction).total
        return tau

    def balanced(self, level: float, direction: float, failed: tuple[str, ...] = ()) -> bool:
        """Whether the thrusters hold the condition at ``level`` from ``direction`` [rad]."""
        condition = condition_at(level, self.conditions)
        tau = self.required(condition, direction)
        if not np.any(tau):
            return True
        if np.any(np.abs(tau[self.uncontrolled]) > 1e-9 * np.max(np.abs(tau))):
            return False                        # a load where no actuator is asked to push
        variant = self.variant(condition, direction, failed)
        if not variant.actuators:
            return False
        balance = self.case_balance(variant, failed)
        if balance is None:
            capability = self.capability(variant, failed)
            scale = authority_scale(tau, capability.model.dof_index, capability.model.authority)
            held, winner = capability.attains(tau / scale, scale * (1.0 - MARGIN), self._winners.get(failed, 0))
        else:
            held, winner = balance.attains(variant, self.variant_profiles(variant), tau, self._winners.get(failed, 0))
        if held:                                # in units of authority; the pieces that held first next time
            self._winners[failed] = winner
        return held

    def heading(self, direction: float, failed: tuple[str, ...] = ()) -> tuple[int, float]:
        """(capability number, limiting wind speed [m/s]) of one heading."""
        return limit(lambda level: self.balanced(level, direction, failed), self.conditions)

    def run(self, step_deg: float = 10.0, lower: tuple[CapabilityResult, ...] = ()) -> CapabilityResult:
        """The complete result: every heading's number and limiting wind speed per case, the notes
        and the allocations behind Tables A-8 to A-10 (``lower``: the results of the lower levels
        of the same vessel, kept with it)."""
        if not 0.0 < step_deg <= 90.0 or not math.isclose(360.0 / step_deg, round(360.0 / step_deg)):
            raise ValueError(f"a heading step that divides 360 deg and is at most 90 deg, not {step_deg}")
        headings = np.arange(round(360.0 / step_deg)) * step_deg
        numbers, winds = {}, {}
        for case, failed in self.cases().items():
            pairs = [self.heading(math.radians(h), failed) for h in headings]
            numbers[case] = np.array([p[0] for p in pairs], dtype=int)
            winds[case] = np.array([p[1] for p in pairs])
        numbers[WORST] = np.min([numbers[g] for g in self.groups], axis=0)
        winds[WORST] = np.min([winds[g] for g in self.groups], axis=0)
        notes = self.notes()
        if step_deg > MAX_STEP_DEG:
            notes.append(f"Headings every {step_deg:g} deg: coarser than the standard's {MAX_STEP_DEG:g} deg.")
        return CapabilityResult(headings, numbers, winds, tuple(notes), self.level, self.conditions,
                                self.allocations(headings, numbers), lower)

    def cases(self) -> dict[str, tuple[str, ...]]:
        """What each case loses: ``intact`` nothing, then each redundancy group its members."""
        return {INTACT: (), **self.groups}

    def allocations(self, headings_deg: np.ndarray, numbers: dict[str, np.ndarray]) -> tuple[Allocation, ...]:
        """Per case and heading, the heading's number and :meth:`thruster_use` at its condition
        (the allocation Tables A-8 to A-10 report)."""
        return tuple(Allocation(case, float(heading), int(numbers[case][k]),
                                self.thruster_use(int(numbers[case][k]), math.radians(heading), tuple(failed)))
                     for case, failed in self.cases().items() for k, heading in enumerate(headings_deg))

    def thruster_use(self, number: int, direction: float, failed: tuple[str, ...] = ()) -> tuple[ThrusterUse, ...]:
        """Each working thruster's thrust in an allocation that holds the condition of ``number`` from
        ``direction``: the forces of the largest multiple of the load, scaled to the load (none when
        the case leaves no thruster working)."""
        condition = self.conditions[number]
        variant = self.variant(condition, direction, failed)
        if not variant.actuators:
            return ()
        capability, balance = self.capability(variant, failed), self.case_balance(variant, tuple(failed))
        model, tau = capability.model, self.required(condition, direction)
        force = np.zeros(model.m)
        if np.any(tau):                         # the furthest combination alone where the kept programmes tell it
            scale = authority_scale(tau, model.dof_index, model.authority)
            best = None if balance is None else balance.largest(variant, self.variant_profiles(variant), tau)
            multiple, force = (capability.reach_forces(tau / scale) if best is None
                               else capability.combination_forces(tau / scale, best))
            force = force * (scale / multiple) if multiple > 0.0 else np.zeros(model.m)
        uses = []
        for index, actuator in enumerate(variant.actuators):
            start = int(model.starts[index])
            if actuator.rotatable:
                fx, fy = force[start], force[start + 1]
                thrust, angle = float(math.hypot(fx, fy)), math.degrees(math.atan2(fy, fx))
                available = capability.available(actuator.name, math.atan2(fy, fx))
            else:
                thrust = float(force[start])
                angle = math.degrees(math.atan2(actuator.direction[1], actuator.direction[0]))
                available = actuator.thrust_max if thrust >= 0.0 else -actuator.thrust_min
            uses.append(ThrusterUse(actuator.name, thrust, angle, available))
        return tuple(uses)

    def notes(self) -> list[str]:
        """What the numbers rest on, for the output."""
        notes = [
            self.scope,
            f"Method {self.method}. The vehicle file gives each thruster's position, type and azimuth range; its "
            "thrust limits and forbidden sectors are replaced by the standard's thrust and [3.11.3] zones (a zone "
            "lifts when the thruster it protects has failed).",
            hull_note(self.particulars),
            "Thrusters (nominal thrust forward / reversed [kN], x [m] from Lpp/2, submergence [m]): "
            + "; ".join(thruster_note(self.particulars.thrusters[name], u.forward, u.reverse, u.x, u.submergence)
                        for name, u in self.actuators.items())
            + ".",
            "Zones intact: " + ("; ".join(f"{z.thruster} {math.degrees(z.sector[0]):.1f} to "
                                          f"{math.degrees(z.sector[1]):.1f} deg (flushing {z.flushed})"
                                          for z in self.zones()) or "none")
            + " (thrust angle in the body frame, 0 forward, 90 to starboard).",
            describe_losses({case: self.thrust_profiles(lost) for case, lost in self.cases().items()}),
            describe_rudders(self.rudders),
            "Redundancy groups (lost together: actuators, then power sources): "
            + "; ".join(f"{g}: {', '.join(m)}" for g, m in self.groups.items()) + ". " + POWER_READING,
            "Limiting wind speed: conditions between two numbers interpolated linearly; "
            f"at number {len(self.conditions) - 1} the table's {self.conditions[-1].wind:g} m/s (held at least "
            "that).",
        ]
        if self.capacities:
            cases = self.cases()
            notes.append("Power sources [3.12] (capacity, usable after the 10 % reserve; per case what its working "
                         "thrusters draw at full thrust, s P_B, and whether it can limit the balance): "
                         + "; ".join(source_note(source, self.capacities[source], {
                             case: self.source_demand(source, lost) for case, lost in cases.items()
                             if source not in lost}) for source in self.capacities) + ".")
        if self.uncontrolled:
            lost = ", ".join(DOF_NAMES[i] for i in self.uncontrolled)
            notes.append(f"Not controlled: {lost}; a load there is not held.")
        return notes


def _actuators(vehicle: Vehicle, particulars: Particulars) -> dict[str, _Actuator]:
    """Each thruster's Level 1 data joined to the vehicle file's geometry; refused naming the key
    when an actuator has no data, data names no actuator, or the two disagree on the type."""
    known = set(vehicle.names)
    for name in particulars.thrusters:
        if name not in known:
            raise ValueError(f"thrusters.{name}: no actuator of that name; the vehicle has {', '.join(vehicle.names)}")
    result = {}
    for actuator in (a for a in vehicle.actuators if not a.is_surface):          # rudders: rudder_pairs
        data = particulars.thrusters.get(actuator.name)
        if data is None:
            raise ValueError(f"thrusters.{actuator.name}: missing; Level 1 needs every thruster's Table A-3 data")
        if data.kind == "tunnel" and actuator.rotatable:
            raise ValueError(f"thrusters.{actuator.name}.kind: tunnel, but the vehicle file's actuator rotates")
        if data.kind == "azimuth" and not actuator.rotatable:
            raise ValueError(f"thrusters.{actuator.name}.kind: azimuth, but the vehicle file's actuator is fixed")
        x, _, z = actuator.position
        reversible = actuator.thrust_min < 0.0
        result[actuator.name] = _Actuator(
            config=actuator, x=particulars.frame.standard_x(x),
            submergence=particulars.hull.draught - particulars.frame.height(z),
            angle=math.atan2(actuator.direction[1], actuator.direction[0]),
            forward=nominal_thrust(data), reverse=nominal_thrust(data, reverse=True) if reversible else 0.0)
    return result

def level1(vehicle: Vehicle, particulars: Particulars, step_deg: float = 10.0,
           method: str | None = None) -> CapabilityResult:
    """DP capability Level 1 of a vehicle: every heading, intact and for each redundancy group."""
    return Level1(vehicle, particulars, method).run(step_deg)
