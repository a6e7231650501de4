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
from .metrics import (
    alarm_metrics,
    heading_errors,
    position_errors,
    power_metrics,
    run_metrics,
    settled_samples,
    source_figures,
)
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
    sources: list[str] = field(default_factory=list)
    """The power sources, in the order of ``source_power`` and ``source_available``."""
    position_limit: float = 5.0
    """[m] The position is lost beyond this error (the scenario's ``position_limit``)."""
    source_power: list[list[float]] = field(default_factory=list)
    """[kW] drawn from each source, as the status reports it."""
    source_available: list[list[float]] = field(default_factory=list)
    """[kW] each source of the simulated power plant could give."""
    consequence_alarm: list[bool] = field(default_factory=list)

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

    def add_power(self, source_power, source_available, consequence_alarm: bool) -> None:
        """The power and the consequence alarm of the sample :meth:`add` wrote last."""
        self.source_power.append([] if source_power is None else list(source_power))
        self.source_available.append(list(source_available))
        self.consequence_alarm.append(bool(consequence_alarm))

    def power_arrays(self) -> dict[str, np.ndarray]:
        """``source_power``, ``source_available`` (n x sources, kW) and ``consequence_alarm``
        of every sample (none drawn and no alarm where :meth:`add_power` wrote nothing)."""
        n, count = len(self.time), len(self.sources)
        complete = len(self.consequence_alarm) == n
        power = np.array(self.source_power, dtype=float) if complete and count else np.zeros((n, count))
        available = np.array(self.source_available, dtype=float) if complete and count else np.zeros((n, count))
        alarm = np.array(self.consequence_alarm if complete else [False] * n, dtype=bool)
        return {"source_power": power.reshape(n, count), "source_available": available.reshape(n, count),
                "consequence_alarm": alarm}

    def arrays(self) -> dict[str, np.ndarray]:
        return {name: np.array(getattr(self, name), dtype=float) for name in
                ("time", "position", "attitude", "setpoint", "setpoint_heading", "thrust", "azimuth", "saturated",
                 "power", "faulted", "voltage")}

    def position_errors(self) -> np.ndarray:
        return position_errors(np.array(self.position), np.array(self.setpoint), self.horizontal)

    def metrics(self, vehicle: Vehicle, start: float = -math.inf, end: float = math.inf) -> dict[str, float]:
        """run_metrics, and the largest heading [deg] and depth [m] errors, over the samples in
        [start, end) [s] (default: all)."""
        a = self.arrays() | self.power_arrays()
        a["counted"] = settled_samples(a["setpoint"], self.position_errors(), self.position_limit)
        keep = self._kept(a["time"], start, end)
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
        result |= power_metrics(a["source_power"], a["source_available"], self.period)
        result |= alarm_metrics(a["time"], a["consequence_alarm"],
                                position_errors(a["position"], a["setpoint"], self.horizontal), self.position_limit,
                                a["counted"])
        return result

    def source_figures(self, start: float = -math.inf, end: float = math.inf) -> dict[str, dict[str, float]]:
        """Per power source, its peak power, least available power [kW] and time over it [s]
        (``metrics.source_figures``) over the samples in [start, end) [s]."""
        a = self.power_arrays()
        keep = self._kept(np.array(self.time), start, end)
        return source_figures(self.sources, a["source_power"][keep], a["source_available"][keep], self.period)

    @staticmethod
    def _kept(time: np.ndarray, start: float, end: float) -> np.ndarray:
        keep = (time >= start - WINDOW_TOLERANCE) & (time < end - WINDOW_TOLERANCE)
        if not keep.any():
            raise ValueError(f"no sample in [{start:g}, {end:g}) s")
        return keep

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
