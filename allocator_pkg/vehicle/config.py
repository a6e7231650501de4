"""Vehicle configuration types: frozen, validated dataclasses and the names they use.

Nothing here reads files or checks values: :mod:`allocator_pkg.configuration.parameters` builds these
from ROS parameters (and says what is wrong), and every other module only reads them. A field
holds the parameter of its name (:mod:`allocator_pkg.configuration.fields`), whose default and
range only the schema gives (:mod:`allocator_pkg.configuration.schema`).
"""

from __future__ import annotations

from dataclasses import dataclass

from .angles import ANGLE_TOLERANCE, TWO_PI

DOF_NAMES = ("surge", "sway", "heave", "roll", "pitch", "yaw")
"""The components of tau = [X, Y, Z, K, M, N], body frame x forward, y starboard, z down."""

FIXED = "fixed"
AZIMUTH = "azimuth"
AZIMUTH_VERTICAL = "azimuth_vertical"
RUDDER = "rudder"
FIN = "fin"
ACTUATOR_TYPES = (FIXED, AZIMUTH, AZIMUTH_VERTICAL, RUDDER, FIN)
ROTATABLE_TYPES = (AZIMUTH, AZIMUTH_VERTICAL)
SURFACE_TYPES = (RUDDER, FIN)
THRUSTER_TYPES = (FIXED, AZIMUTH, AZIMUTH_VERTICAL)

METHOD_NAMES = ("qp", "pseudoinverse", "nonlinear", "lp", "dynamic", "svd_filter", "explicit")
"""The allocation methods a configuration may name, in the order of the registry
:data:`allocator_pkg.methods.METHODS` (which holds their implementations)."""
SATURATION_MODES = ("weighted", "preserve_direction", "direct")
COMMAND_MAPS = ("linear", "quadratic", "table")
FLOW_MODELS = ("free", "propeller_wake")
FLUSHING_ZONES = ("none", "dnv")


class ConfigError(ValueError):
    """An invalid configuration; ``problems`` lists (parameter name, reason) pairs."""

    def __init__(self, problems: list[tuple[str, str]]):
        self.problems = list(problems)
        super().__init__("; ".join(f"{name}: {reason}" for name, reason in self.problems))


@dataclass(frozen=True)
class CommandMapConfig:
    """Force-to-command map of a thruster (1.3), (1.4) or a measured table.

    A table measured at several supply voltages holds one thrust row per voltage in
    ``table_voltage`` (strictly increasing), flattened into ``table_thrust`` row after row;
    without voltages it has one row. ``deadband`` is the smallest command magnitude that
    turns the propeller of a linear or quadratic map (0: none); ``reversed`` flips the sign of
    the command about the set-point of zero force (a thruster wired or propped backwards). A
    linear or quadratic map has no table."""

    kind: str
    gain: float
    gain_reverse: float
    command_min: float
    command_max: float
    deadband: float
    reversed: bool
    table_command: tuple[float, ...] = ()
    table_thrust: tuple[float, ...] = ()
    table_voltage: tuple[float, ...] = ()

    @property
    def thrust_rows(self) -> tuple[tuple[float, ...], ...]:
        """The table's thrust rows, one per voltage (one row without voltages)."""
        n = len(self.table_command)
        return tuple(self.table_thrust[k:k + n] for k in range(0, len(self.table_thrust), n)) if n else ()


@dataclass(frozen=True)
class RotationConfig:
    """Limits of a rotatable thruster; angles in radians. ``protects`` names, per forbidden
    sector, the thruster it keeps this one from flushing: the sector is in force only while that
    one works ('' or none: always)."""

    azimuth_min: float
    azimuth_max: float
    rate_max: float
    forbidden_sectors: tuple[tuple[float, float], ...]
    reversible: bool
    initial: float
    protects: tuple[str, ...] = ()

    @property
    def continuous(self) -> bool:
        """True when the feasible sector is the whole circle (free rotation, angles wrap)."""
        return self.azimuth_max - self.azimuth_min >= TWO_PI - ANGLE_TOLERANCE


@dataclass(frozen=True)
class SurfaceConfig:
    """Hydrofoil data of a rudder or fin, (1.48), (1.49)."""

    area: float
    lift_coefficient: float
    drag_coefficient: float
    deflection_max: float
    deflection_rate_max: float
    flow: str
    wake_speed_factor: float
    min_control_speed: float


@dataclass(frozen=True)
class ActuatorConfig:
    """One actuator. ``direction`` is the unit force (or lift) direction of fixed
    thrusters and control surfaces; rotatable thrusters take theirs from the angle. The thrust
    range and ``command`` are a thruster's (a control surface has none: zero), ``rotation`` a
    rotatable thruster's and ``surface`` a control surface's. ``feeds`` are the power sources a
    thruster draws from and ``feed_shares`` the share of its power from each (Table A-5 of
    DNV-ST-0111), read by the allocation's power budget and the DP capability analysis.
    ``power_coefficient`` P_i prices its forward thrust (1.44), ``reverse_power_coefficient`` its
    negative thrust (None: P_i), and ``drive_limit`` [kW] caps what its drive draws (None: no
    cap). ``diameter``, ``ducted`` and ``tunnel`` place it among the flushing zones
    (DNV-ST-0111 [3.11.3], [3.11.4])."""

    name: str
    type: str
    position: tuple[float, float, float]
    direction: tuple[float, float, float]
    weight: float
    power_coefficient: float
    thrust_min: float = 0.0
    thrust_max: float = 0.0
    thrust_rate_max: float = 0.0
    command: CommandMapConfig | None = None
    rotation: RotationConfig | None = None
    surface: SurfaceConfig | None = None
    feeds: tuple[str, ...] = ()
    feed_shares: tuple[float, ...] = ()
    diameter: float = 0.0
    ducted: bool = False
    tunnel: bool = False
    reverse_power_coefficient: float | None = None
    drive_limit: float | None = None

    @property
    def rotatable(self) -> bool:
        return self.type in ROTATABLE_TYPES

    @property
    def is_surface(self) -> bool:
        return self.type in SURFACE_TYPES


@dataclass(frozen=True)
class Weights:
    """``slack`` is empty when not configured (the allocator then derives Q per DOF)."""

    slack: tuple[float, ...]
    minimax: float
    azimuth_change: float


@dataclass(frozen=True)
class SolverSettings:
    """Iteration limits and tolerances of the QP solver, as fractions of each variable's range."""

    eps_abs: float
    eps_rel: float
    max_iter: int
    time_limit: float


@dataclass(frozen=True)
class BiasSettings:
    """Thrust bias (docs/theory.md, thrust bias): with ``enabled``, each pair of rotatable
    thrusters in ``pairs`` pushes toward each other with ``thrust`` [N] on top of what the
    request needs, in full below a load of ``fade_start`` and not at all above ``fade_end``
    (shares of the authority of the most loaded DOF), the load filtered with the time constant
    ``fade_time_constant`` [s]."""

    enabled: bool
    pairs: tuple[tuple[str, str], ...]
    thrust: float
    fade_start: float
    fade_end: float
    fade_time_constant: float


@dataclass(frozen=True)
class PowerSource:
    """A switchboard or prime mover that feeds thrusters (a column of DNV-ST-0111 Table A-5):
    ``capacity`` [kW] the power it can deliver."""

    name: str
    capacity: float


@dataclass(frozen=True)
class RedundancyGroup:
    """What one single failure takes away together (DNV-ST-0111 [2.4.8]): power sources and
    actuators, by name."""

    name: str
    sources: tuple[str, ...]
    actuators: tuple[str, ...]


@dataclass(frozen=True)
class BusTie:
    """A bus-tie breaker between two power sources (switchboards): while ``closed`` the two
    are one bus, whose thrusters draw on the power of both; open, each feeds its own."""

    name: str
    sources: tuple[str, str]
    closed: bool


@dataclass(frozen=True)
class Vehicle:
    """A validated vehicle configuration: the actuators and how to allocate over them."""

    actuators: tuple[ActuatorConfig, ...]
    dofs: tuple[str, ...]
    method: str
    saturation: str
    rate_hz: float
    weights: Weights
    singularity_rho: float
    singularity_epsilon: float
    azimuth_polygon_sides: int
    nonlinear_max_iterations: int
    solver: SolverSettings
    water_density: float
    dynamic_gain: float
    svd_filter_time_constant: float
    svd_filter_damping_threshold: float
    priorities: tuple[int, ...]
    nominal_voltage: float | None
    explicit_regions: str
    bias: BiasSettings
    flushing_zones: str
    power_phase_back: bool
    power_restore_ramp: float = 0.0
    power_sources: tuple[PowerSource, ...] = ()
    redundancy_groups: tuple[RedundancyGroup, ...] = ()
    bus_ties: tuple[BusTie, ...] = ()

    @property
    def priority_levels(self) -> tuple[tuple[int, ...], ...]:
        """Indices into ``dofs`` of each priority level, highest first; empty without
        priorities or when every DOF has the same one (nothing to order)."""
        levels = sorted(set(self.priorities))
        if len(levels) < 2:
            return ()
        return tuple(tuple(k for k, p in enumerate(self.priorities) if p == level) for level in levels)

    @property
    def voltage_range(self) -> tuple[float, float] | None:
        """The supply voltages every voltage-indexed table covers, or None without such tables."""
        tables = [a.command.table_voltage for a in self.actuators if a.command is not None and a.command.table_voltage]
        if not tables:
            return None
        return max(t[0] for t in tables), min(t[-1] for t in tables)

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(a.name for a in self.actuators)

    @property
    def dof_indices(self) -> tuple[int, ...]:
        return tuple(DOF_NAMES.index(d) for d in self.dofs)

    @property
    def has_surfaces(self) -> bool:
        return any(a.is_surface for a in self.actuators)

    @property
    def has_rotatable(self) -> bool:
        return any(a.rotatable for a in self.actuators)

    def actuator(self, name: str) -> ActuatorConfig:
        for actuator in self.actuators:
            if actuator.name == name:
                return actuator
        raise KeyError(name)
