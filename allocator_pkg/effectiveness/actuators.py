"""Actuator models: force-to-command maps (1.3), (1.4) and control-surface lift and drag (1.48), (1.49).

The allocator works in forces; these models turn a force into the set-point an actuator
driver takes (rpm, PWM, deflection) and tell which forces the set-point range allows.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..vehicle.config import CommandMapConfig, SurfaceConfig


@dataclass(frozen=True)
class LinearMap:
    """F = k u (1.3), with its own k for negative force; no force for a command smaller in
    magnitude than ``deadband`` (the propeller does not turn)."""

    gain: float
    gain_reverse: float
    command_min: float
    command_max: float
    deadband: float = 0.0

    def force(self, command: float) -> float:
        if abs(command) < self.deadband:
            return 0.0
        return self.gain * command if command >= 0.0 else self.gain_reverse * command

    def command(self, force: float) -> float:
        return force / self.gain if force >= 0.0 else force / self.gain_reverse

    def force_range(self) -> tuple[float, float]:
        return self.force(self.command_min), self.force(self.command_max)


@dataclass(frozen=True)
class QuadraticMap:
    """F = k |u| u (1.4); its inverse u = sign(F) sqrt(|F| / k); no force for a command
    smaller in magnitude than ``deadband``."""

    gain: float
    gain_reverse: float
    command_min: float
    command_max: float
    deadband: float = 0.0

    def force(self, command: float) -> float:
        if abs(command) < self.deadband:
            return 0.0
        gain = self.gain if command >= 0.0 else self.gain_reverse
        return gain * abs(command) * command

    def command(self, force: float) -> float:
        gain = self.gain if force >= 0.0 else self.gain_reverse
        return math.copysign(math.sqrt(abs(force) / gain), force)

    def force_range(self) -> tuple[float, float]:
        return self.force(self.command_min), self.force(self.command_max)


FLAT_WIDTH = 1e-9
"""Forces within this fraction of a curve's range of a flat stretch's force count as that
force: the inverse is one interpolation through points that step across the stretch."""


class TableMap:
    """Piecewise-linear map through measured (command, force) pairs, e.g. a published
    thruster curve. A flat stretch of the curve (a dead band) inverts to its middle, so zero
    force commands the neutral set-point, and any other force to a set-point that makes it."""

    def __init__(self, command: Sequence[float], thrust: Sequence[float], command_min: float, command_max: float):
        self._command = np.asarray(command, dtype=float)
        self._thrust = np.asarray(thrust, dtype=float)
        self.command_min = max(command_min, float(self._command[0]))
        self.command_max = min(command_max, float(self._command[-1]))
        # The inverse: the curve's points, each flat stretch at force F (commands a to b)
        # replaced by (F - e, a'), (F, middle), (F + e, b'), with a' and b' on the curve's
        # neighbouring pieces: a force met exactly by the stretch maps to its middle, any other
        # to the set-point that makes it (exactly so beyond e of the stretch).
        forces, first = np.unique(self._thrust, return_index=True)
        last = len(self._thrust) - 1 - np.unique(self._thrust[::-1], return_index=True)[1]
        width = FLAT_WIDTH * max(float(np.max(np.abs(self._thrust))), 1e-300)
        ends = [(force, self._command[a], self._command[b]) for force, a, b in zip(forces, first, last)]
        points: list[tuple[float, float]] = []
        for k, (force, a, b) in enumerate(ends):
            if a == b:
                points.append((force, a))
                continue
            before = a if k == 0 else a + (ends[k - 1][2] - a) * width / (force - ends[k - 1][0])
            after = b if k == len(ends) - 1 else b + (ends[k + 1][1] - b) * width / (ends[k + 1][0] - force)
            points += [(force - width, before), (force, 0.5 * (a + b)), (force + width, after)]
        self._inverse_force = np.array([force for force, _ in points])
        self._inverse_command = np.array([command for _, command in points])

    def force(self, command: float) -> float:
        return float(np.interp(command, self._command, self._thrust))

    def command(self, force: float) -> float:
        return float(self.commands(np.array([force]))[0])

    def commands(self, force: np.ndarray) -> np.ndarray:
        """Set-points of several forces at once."""
        return np.interp(force, self._inverse_force, self._inverse_command)

    def force_range(self) -> tuple[float, float]:
        return self.force(self.command_min), self.force(self.command_max)


CommandMap = LinearMap | QuadraticMap | TableMap


def thrust_row(config: CommandMapConfig, voltage: float | None) -> np.ndarray:
    """A table's thrust at each of its set-points at a supply voltage: linear between the
    two measured voltages around it (the only row of a table without voltages, whatever the
    voltage; None: that row, or the table's first voltage)."""
    rows = np.array(config.thrust_rows, dtype=float)
    if len(rows) == 1 or voltage is None:
        return rows[0]
    position = float(np.interp(voltage, config.table_voltage, np.arange(len(rows))))
    below = min(int(position), len(rows) - 2)
    share = position - below
    return (1.0 - share) * rows[below] + share * rows[below + 1]


def command_map(config: CommandMapConfig, voltage: float | None = None) -> CommandMap:
    """The map a thruster's configuration describes (a voltage-indexed table at ``voltage``)."""
    if config.kind == "table":
        return TableMap(config.table_command, thrust_row(config, voltage), config.command_min, config.command_max)
    kind = QuadraticMap if config.kind == "quadratic" else LinearMap
    return kind(config.gain, config.gain_reverse, config.command_min, config.command_max, config.deadband)


def deadband_forces(config: CommandMapConfig) -> tuple[float, float]:
    """The forces at the dead band's edges of a linear or quadratic map, (negative, positive):
    the smallest force either way that a turning propeller gives ((0, 0) without a dead band)."""
    if config.kind == "table" or config.deadband <= 0.0:
        return 0.0, 0.0
    band = config.deadband
    if config.kind == "quadratic":
        return -config.gain_reverse * band * band, config.gain * band * band
    return -config.gain_reverse * band, config.gain * band


class CommandMaps:
    """Commands of every actuator at once: vectorised for linear and quadratic maps.

    ``surfaces`` are control surfaces, whose command is the deflection delta = L / k_L
    (1.48); their lift gains come with each call because they change with speed.
    """

    def __init__(self, maps: Sequence[CommandMap | None], reversed_: Sequence[bool] = ()):
        self.maps = list(maps)
        # A reversed thruster's command is mirrored about its set-point of zero force.
        self._reversed = np.array([i for i, flag in enumerate(reversed_) if flag], dtype=int)
        self._neutral = np.array([maps[i].command(0.0) for i in self._reversed])
        self._linear = np.array([i for i, m in enumerate(maps) if isinstance(m, LinearMap)], dtype=int)
        self._quadratic = np.array([i for i, m in enumerate(maps) if isinstance(m, QuadraticMap)], dtype=int)
        tables: dict[int, list[int]] = {}
        for i, m in enumerate(maps):
            if isinstance(m, TableMap):
                tables.setdefault(id(m), []).append(i)
        self._tables = [(maps[group[0]], np.array(group)) for group in tables.values()]
        self._surfaces = np.array([i for i, m in enumerate(maps) if m is None], dtype=int)
        gains = np.array([m.gain if isinstance(m, (LinearMap, QuadraticMap)) else 1.0 for m in maps])
        reverse = np.array([m.gain_reverse if isinstance(m, (LinearMap, QuadraticMap)) else 1.0 for m in maps])
        self._gain = gains
        self._gain_reverse = reverse
        self._low = np.array([m.command_min if m is not None else -np.inf for m in maps])
        self._high = np.array([m.command_max if m is not None else np.inf for m in maps])
        # Shortcuts for the common vehicles: one measured curve for every actuator (a table
        # clamps at its ends itself), or quadratic maps alike both ways.
        self._one_table = maps[0] if len(self._tables) == 1 and len(self._tables[0][1]) == len(maps) else None
        self._symmetric_quadratic = (len(self._quadratic) == len(maps) and np.array_equal(gains, reverse))
        self._clip = bool(np.isfinite(self._low).any() or np.isfinite(self._high).any())

    def commands(self, force: np.ndarray, efficiency: np.ndarray | None, lift_gain: np.ndarray) -> np.ndarray:
        """Set-points giving ``force``; a DEGRADED actuator (efficiency e < 1) is commanded
        for force / e so that it still produces ``force`` (None: every actuator nominal)."""
        command = self._commands(force, efficiency, lift_gain)
        if self._reversed.size:
            command[self._reversed] = 2.0 * self._neutral - command[self._reversed]
        return command

    def _commands(self, force: np.ndarray, efficiency: np.ndarray | None, lift_gain: np.ndarray) -> np.ndarray:
        nominal = force if efficiency is None else force / efficiency
        if self._one_table is not None:
            return self._one_table.commands(nominal)
        if self._symmetric_quadratic:
            command = np.copysign(np.sqrt(np.abs(nominal) / self._gain), nominal)
            return np.minimum(np.maximum(command, self._low), self._high) if self._clip else command
        command = np.zeros(force.shape)
        if self._linear.size or self._quadratic.size:
            gain = np.where(nominal >= 0.0, self._gain, self._gain_reverse)
            if self._linear.size:
                idx = self._linear
                command[idx] = nominal[idx] / gain[idx]
            if self._quadratic.size:
                idx = self._quadratic
                command[idx] = np.sign(nominal[idx]) * np.sqrt(np.abs(nominal[idx]) / gain[idx])
        for table, idx in self._tables:
            command[idx] = table.commands(nominal[idx])
        idx = self._surfaces
        if idx.size:
            k = lift_gain[idx]
            command[idx] = np.divide(force[idx], k, out=np.zeros(idx.size), where=k > 0.0)
        return np.minimum(np.maximum(command, self._low), self._high)


def flow_speed(surface: SurfaceConfig, speed: float) -> float:
    """u_f of (1.48): the surge speed, scaled by the wake factor behind a propeller."""
    return speed * surface.wake_speed_factor if surface.flow == "propeller_wake" else speed


def lift_gain(surface: SurfaceConfig, water_density: float, speed: float) -> float:
    """k_L = 1/2 rho_w A u_f^2 C_L, lift per radian (1.48), (1.52); zero below the
    surface's minimum control speed (the surface is then unavailable)."""
    u_f = flow_speed(surface, speed)
    if u_f < surface.min_control_speed or u_f <= 0.0:
        return 0.0
    return 0.5 * water_density * surface.area * u_f * u_f * surface.lift_coefficient


def drag_gain(surface: SurfaceConfig, water_density: float, speed: float) -> float:
    """k_D = 1/2 rho_w A u_f^2 C_D, drag per squared radian (1.49), (1.58)."""
    u_f = flow_speed(surface, speed)
    if u_f < surface.min_control_speed or u_f <= 0.0:
        return 0.0
    return 0.5 * water_density * surface.area * u_f * u_f * surface.drag_coefficient
