"""What one closed-loop run saw, sample by sample, and its metrics (``metrics.run_metrics``):
the vehicle's position and attitude, the set-point, the commanded thrusts and angles, the
saturation flag, power and supply voltage the node reported, and when a fault was in force."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..vehicle.config import Vehicle
from .metrics import heading_errors, position_errors, run_metrics


@dataclass
class Trace:
    names: list[str]
    period: float
    horizontal: bool
    time: list[float] = field(default_factory=list)
    position: list[list[float]] = field(default_factory=list)
    attitude: list[list[float]] = field(default_factory=list)
    setpoint: list[list[float]] = field(default_factory=list)
    setpoint_heading: list[float] = field(default_factory=list)
    thrust: list[list[float]] = field(default_factory=list)
    azimuth: list[list[float]] = field(default_factory=list)
    saturated: list[bool] = field(default_factory=list)
    power: list[float] = field(default_factory=list)
    faulted: list[bool] = field(default_factory=list)
    voltage: list[float] = field(default_factory=list)
    """The supply voltage the node's limits followed (NaN without voltage tables)."""

    def add(self, time: float, position, attitude, setpoint, setpoint_heading: float, thrust, azimuth,
            saturated: bool, power: float, faulted: bool, voltage: float = math.nan) -> None:
        self.time.append(time)
        self.position.append(list(position))
        self.attitude.append(list(attitude))
        self.setpoint.append(list(setpoint))
        self.setpoint_heading.append(setpoint_heading)
        self.thrust.append(list(thrust))
        self.azimuth.append(list(azimuth))
        self.saturated.append(bool(saturated))
        self.power.append(power)
        self.faulted.append(bool(faulted))
        self.voltage.append(voltage)

    def arrays(self) -> dict[str, np.ndarray]:
        return {name: np.array(getattr(self, name), dtype=float) for name in
                ("time", "position", "attitude", "setpoint", "setpoint_heading", "thrust", "azimuth", "saturated",
                 "power", "faulted", "voltage")}

    def position_errors(self) -> np.ndarray:
        return position_errors(np.array(self.position), np.array(self.setpoint), self.horizontal)

    def metrics(self, vehicle: Vehicle) -> dict[str, float]:
        """run_metrics, and the largest heading [deg] and depth [m] errors."""
        a = self.arrays()
        result = run_metrics(position=a["position"], position_setpoint=a["setpoint"], heading=a["attitude"][:, 2],
                             heading_setpoint=a["setpoint_heading"], horizontal=self.horizontal, thrust=a["thrust"],
                             angles=a["azimuth"], saturated=a["saturated"],
                             power_coefficients=np.array([x.power_coefficient for x in vehicle.actuators]),
                             thrust_scale=np.array([max(abs(x.thrust_min), abs(x.thrust_max)) for x in
                                                    vehicle.actuators]),
                             period=self.period)
        heading = heading_errors(a["attitude"][:, 2], a["setpoint_heading"])
        result["heading_error_max"] = float(np.degrees(np.max(np.abs(heading))))
        result["depth_error_max"] = 0.0 if self.horizontal else float(
            np.max(np.abs(a["position"][:, 2] - a["setpoint"][:, 2])))
        return result
