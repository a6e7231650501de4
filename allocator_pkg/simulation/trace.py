"""What one closed-loop run saw, sample by sample, and its metrics (``metrics.run_metrics``)
over the whole run or a window of it, and the figures of each set-point step
(``step_response``): the vehicle's position and attitude, the set-point, the commanded
thrusts and angles, the saturation flag, power and supply voltage the node reported, and when
a fault was in force."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..vehicle.config import Vehicle
from .metrics import heading_errors, position_errors, run_metrics
from .setpoint import Step
from .step_response import StepFigures, step_figures

WINDOW_TOLERANCE = 1e-9
"""[s] A sample at a window's start belongs to it, one at its end does not."""


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

    def metrics(self, vehicle: Vehicle, start: float = -math.inf, end: float = math.inf) -> dict[str, float]:
        """run_metrics, and the largest heading [deg] and depth [m] errors, over the samples in
        [start, end) [s] (default: all)."""
        a = self.arrays()
        keep = (a["time"] >= start - WINDOW_TOLERANCE) & (a["time"] < end - WINDOW_TOLERANCE)
        if not keep.any():
            raise ValueError(f"no sample in [{start:g}, {end:g}) s")
        a = {name: values[keep] for name, values in a.items()}
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

    def step_response(self, step: Step) -> StepFigures:
        """The figures of a set-point step: the position's movement along the step (the
        horizontal plane for a vessel), or the heading's change."""
        a = self.arrays()
        if step.channel == "heading":
            response = (a["attitude"][:, 2] - step.start[0] + math.pi) % (2.0 * math.pi) - math.pi
            size = float(step.end[0] - step.start[0])
        else:
            dofs = slice(0, 2) if self.horizontal else slice(0, 3)
            change = (step.end - step.start)[dofs]
            size = float(np.linalg.norm(change))
            if size == 0.0:
                return StepFigures(None, 0.0, None)
            response = (a["position"][:, dofs] - step.start[dofs]) @ (change / size)
        return step_figures(a["time"], response, step.time, size, step.until)
