"""Actuator thrust of DNV-ST-0111 Level 1 [3.9]: nominal thrust and the thrust loss factors.

T_effective = T_nominal beta_T [3.9.1], T_nominal = eta1 eta2 (D P)^(2/3) [N] with D [m] and
P = P_B eta_M [kW] [3.9.2] (eta1 Table 3-1, eta2 Tables 3-2 and 3-3, eta_M Table 3-4),
beta_T = beta_misc beta_vent [3.9.5] with beta_misc = 0.9 [3.9.3] and the ventilation loss
beta_vent of [3.9.4] (:func:`ventilation_factor`).

Rows are chosen as the public transcription (repository WilliamBoland1/Prosjektoppgave_Collab,
``dp_capability/models/Descriptions/thrust.md``) reads the tables: tunnels and cycloidals have
their own eta1; a ducted contra-rotating unit has no row and is refused; a tunnel's eta2 is its
inlet's in both directions, a cycloidal's 1.0 both ways; any permanent-magnet actuator other
than a cycloidal takes the rim-driven eta_M. Water jets are outside the tables ([3.8.1]: the
maker's data) and refused. Not verified by DNV.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ...configuration.file_keys import BOOLEAN, NUMBER, TEXT, FileKey, key_named
from .loads import TZ_FROM_TP

KINDS = ("azimuth", "pod", "shaft_line", "tunnel", "cycloidal")
"""Actuator types of Tables 3-1 to 3-4."""
PITCHES = ("FPP", "CPP")
TUNNEL_INLETS = {"broken": 1.0, "rounded": 1.07, "other": 0.93}
"""Table 3-2: eta2 of a tunnel thruster by inlet (Figure 3-4): broken with alpha in [20, 50] deg
and b > 0.1 D; rounded with r > 0.05 D; any other."""
REVERSED_ETA2 = {("FPP", False): 0.9, ("FPP", True): 0.7, ("CPP", False): 0.65, ("CPP", True): 0.5}
"""Table 3-3: eta2 of reversed thrust by (pitch, ducted); forward thrust 1.0."""
ETA_M = {"cycloidal": 0.91, "tunnel": 0.93, "azimuth": 0.93, "shaft_line": 0.97, "pod": 0.98}
"""Table 3-4 by type; permanent-magnet cycloidal 0.97, other permanent-magnet (rim-driven) 0.995."""
ETA_M_PM_CYCLOIDAL = 0.97
ETA_M_RIM_DRIVEN = 0.995
BETA_MISC = 0.9
"""[3.9.3]."""
K_V = (2.0, 1.5, 15.2, 0.85, 0.38)
"""k_V1 ... k_V5 of [3.9.4]."""
THRUSTER_KEYS = (
    FileKey("kind", TEXT, "the actuator type of Tables 3-1 to 3-4", required=True, choices=KINDS),
    FileKey("diameter", NUMBER, "D of [3.9.2], [3.11]", unit="m", minimum=0.0, exclusive_minimum=True,
            default_doc="the vehicle file's `actuators.<actuator>.diameter`"),
    FileKey("power", NUMBER, "P_B of [3.9.2]", required=True, unit="kW", minimum=0.0, exclusive_minimum=True),
    FileKey("pitch", TEXT, "Table 3-3", default="FPP", choices=PITCHES),
    FileKey("ducted", BOOLEAN, "Tables 3-1, 3-3, [3.11.4]",
            default_doc="the vehicle file's `actuators.<actuator>.ducted` (default false)"),
    FileKey("contra_rotating", BOOLEAN, "Table 3-1", default=False),
    FileKey("permanent_magnet", BOOLEAN, "Table 3-4", default=False),
    FileKey("tunnel_inlet", TEXT, "Table 3-2, tunnels only", choices=tuple(TUNNEL_INLETS)),
)
"""An actuator's row of Table A-3 in a particulars file (``thrusters.<actuator>``); the defaults
of :class:`ThrusterData`."""


@dataclass(frozen=True)
class ThrusterData:
    """One actuator's row of Table A-3. ``power`` is P_B [kW]: the MCR brake power available in
    DP mode with the power and torque limits taken into account; ``diameter`` D [m] as [3.9.2]
    defines it per type. ``diameter`` and ``ducted`` None: not given here, the vehicle file's
    (:func:`~..inputs.particulars.with_vehicle_geometry`)."""

    name: str
    kind: str
    diameter: float | None
    power: float
    pitch: str = key_named(THRUSTER_KEYS, "pitch").default
    ducted: bool | None = False
    """False: not ducted; the particulars' reader gives None when the file leaves it to the vehicle file."""
    contra_rotating: bool = key_named(THRUSTER_KEYS, "contra_rotating").default
    permanent_magnet: bool = key_named(THRUSTER_KEYS, "permanent_magnet").default
    tunnel_inlet: str | None = key_named(THRUSTER_KEYS, "tunnel_inlet").default

    def __post_init__(self) -> None:
        key = f"thrusters.{self.name}"
        if self.kind == "water_jet":
            raise ValueError(f"{key}.kind: water jets are outside Tables 3-1 to 3-4 ([3.8.1]: the maker's data)")
        if self.kind not in KINDS:
            raise ValueError(f"{key}.kind: one of {', '.join(KINDS)}, not {self.kind!r}")
        for field in ("diameter", "power"):
            value = getattr(self, field)
            if value is None and field == "diameter":
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                    math.isfinite(value) and value > 0.0):
                raise ValueError(f"{key}.{field}: a finite number > 0, not {value!r}")
        if self.pitch not in PITCHES:
            raise ValueError(f"{key}.pitch: FPP or CPP, not {self.pitch!r}")
        for field in ("ducted", "contra_rotating", "permanent_magnet"):
            if not isinstance(getattr(self, field), bool) and not (field == "ducted" and self.ducted is None):
                raise ValueError(f"{key}.{field}: true or false, not {getattr(self, field)!r}")
        if self.kind == "tunnel" and self.tunnel_inlet not in TUNNEL_INLETS:
            raise ValueError(f"{key}.tunnel_inlet: one of {', '.join(TUNNEL_INLETS)} for a tunnel "
                             f"(Table 3-2), not {self.tunnel_inlet!r}")
        if self.kind != "tunnel" and self.tunnel_inlet is not None:
            raise ValueError(f"{key}.tunnel_inlet: only for a tunnel thruster")
        if self.kind not in ("tunnel", "cycloidal") and self.ducted and self.contra_rotating:
            raise ValueError(f"{key}: Table 3-1 has no row for a ducted contra-rotating propeller")


def eta1(data: ThrusterData) -> float:
    """Table 3-1."""
    if data.kind in ("tunnel", "cycloidal"):
        return 900.0
    if data.ducted:
        return 1200.0
    return 950.0 if data.contra_rotating else 800.0


def eta2(data: ThrusterData, reverse: bool = False) -> float:
    """Table 3-2 (tunnels, by inlet, either direction) or Table 3-3."""
    if data.kind == "tunnel":
        return TUNNEL_INLETS[data.tunnel_inlet]
    if not reverse or data.kind == "cycloidal":
        return 1.0
    return REVERSED_ETA2[(data.pitch, data.ducted)]


def eta_m(data: ThrusterData) -> float:
    """Table 3-4."""
    if data.permanent_magnet:
        return ETA_M_PM_CYCLOIDAL if data.kind == "cycloidal" else ETA_M_RIM_DRIVEN
    return ETA_M[data.kind]


def nominal_thrust(data: ThrusterData, reverse: bool = False) -> float:
    """T_nominal [N] of [3.9.2]: eta1 eta2 (D P_B eta_M)^(2/3), forward or reversed."""
    return eta1(data) * eta2(data, reverse) * (data.diameter * data.power * eta_m(data)) ** (2.0 / 3.0)


def normal_cdf(value: float) -> float:
    """Phi, the standard normal distribution function."""
    return 0.5 * (1.0 + math.erf(value / math.sqrt(2.0)))


def ventilation_factor(data: ThrusterData, x: float, submergence: float, lpp: float, hs: float, tp: float,
                       direction: float, reverse: bool = False) -> float:
    """beta_vent of [3.9.4] for an actuator at ``x`` [m forward of Lpp/2] whose centre is
    ``submergence`` xi [m] below the waterline, in a sea of ``hs`` [m], ``tp`` [s] from
    ``direction`` [rad, 0 head on]:

    beta_vent = Phi(k_V1 2 xi / D - k_V2 sigma),
    sigma = 0.25 (A Hs min(T0, 1) + max(sqrt(|T_nominal| / D^3) / k_V3 - 1, 0)),
    A = k_V4 B C, B = 1 + k_V5 dir / pi up to pi/2 and (1 + k_V5) - k_V5 dir / pi beyond (the
    standard's second range read as the union of [-pi, -pi/2] and [pi/2, pi]), C = 1 forward
    of Lpp/2 and 1 + 0.4 x / Lpp aft, T0 = 0.64 sqrt(Lpp) / Tz, Tz = Tp / 1.4049, dir = |direction|
    in [0, pi]; T_nominal in N, of the direction pushed. A calm sea leaves the load term."""
    k1, k2, k3, k4, k5 = K_V
    folded = abs(math.remainder(direction, 2.0 * math.pi))
    spread = 1.0 + k5 * folded / math.pi if folded <= math.pi / 2 else (1.0 + k5) - k5 * folded / math.pi
    aft = 1.0 if x >= 0.0 else 1.0 + 0.4 * x / lpp
    waves = 0.0
    if hs != 0.0:
        waves = k4 * spread * aft * hs * min(0.64 * math.sqrt(lpp) / (tp / TZ_FROM_TP), 1.0)
    load = math.sqrt(abs(nominal_thrust(data, reverse)) / data.diameter ** 3) / k3
    sigma = 0.25 * (waves + max(load - 1.0, 0.0))
    return normal_cdf(k1 * 2.0 * submergence / data.diameter - k2 * sigma)
