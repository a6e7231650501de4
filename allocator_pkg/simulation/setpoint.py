"""The set-point over a run: where the vehicle is to be and which way it is to head at each
sim time. It starts at the scenario's ``setpoint``; each set-point event moves the position,
the heading or both, as a step (at once) or as a ramp (at a given speed [m/s] along the
straight line, at a given rate [rad/s] the short way round). The position and the heading
change independently: an event that names only one leaves a ramp of the other running. An
event starts from the set-point in force at its time (a ramp may be under way)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from ..vehicle.angles import wrap

EVENT_TOLERANCE = 1e-9
"""[s] An event at time t applies to the sample at t (as every event of a run does)."""


@dataclass(frozen=True)
class SetpointTarget:
    """What one set-point event asks for: a position NED [m] and/or a heading [rad], each
    reached at once (``speed`` / ``heading_rate`` None) or at that speed [m/s] / rate [rad/s]."""

    position: tuple[float, float, float] | None = None
    heading: float | None = None
    speed: float | None = None
    heading_rate: float | None = None

    def scaled(self, factor: float) -> SetpointTarget:
        """The same change in a run whose times are ``factor`` times as long: ramps take
        ``factor`` times as long (their speed and rate divided by it)."""
        return replace(self, speed=None if self.speed is None else self.speed / factor,
                       heading_rate=None if self.heading_rate is None else self.heading_rate / factor)


@dataclass(frozen=True)
class Segment:
    """From ``time`` [s]: from ``start`` toward ``end`` at ``rate`` per second (inf: a step)."""

    time: float
    start: np.ndarray
    end: np.ndarray
    rate: float

    @cached_property
    def distance(self) -> float:
        """|end - start| [m or rad]."""
        return float(np.linalg.norm(self.end - self.start))

    def at(self, t: float) -> np.ndarray:
        distance = self.distance
        if distance == 0.0 or math.isinf(self.rate):
            return self.end.copy()
        share = min(1.0, self.rate * max(0.0, t - self.time) / distance)
        return self.start + share * (self.end - self.start)


@dataclass(frozen=True)
class Step:
    """A set-point step (no ramp) of one channel, ``position`` [m] or ``heading`` [rad], at
    ``time`` [s], from ``start`` to ``end``, in force until ``until`` [s] (the channel's next
    change or the end of the run)."""

    channel: str
    time: float
    start: np.ndarray
    end: np.ndarray
    until: float

    @property
    def size(self) -> float:
        """The step's length [m] or angle [rad]."""
        return float(np.linalg.norm(self.end - self.start))


class SetpointSchedule:
    """The set-point at any sim time, from the initial one and the events ``(time, target)``
    (any order)."""

    def __init__(self, position, heading: float, changes: list[tuple[float, SetpointTarget]]):
        initial_position, initial_heading = np.array(position, dtype=float), np.array([heading], dtype=float)
        self._position = [Segment(-math.inf, initial_position, initial_position, math.inf)]
        self._heading = [Segment(-math.inf, initial_heading, initial_heading, math.inf)]
        for time, target in sorted(changes, key=lambda change: change[0]):
            if target.position is not None:
                start = self._channel(self._position, time)
                self._position.append(Segment(time, start, np.array(target.position, dtype=float),
                                              math.inf if target.speed is None else target.speed))
            if target.heading is not None:
                start = self._channel(self._heading, time)
                end = start + wrap(target.heading - float(start[0]))
                self._heading.append(Segment(time, start, end, math.inf if target.heading_rate is None
                                             else target.heading_rate))

    @staticmethod
    def _channel(segments: list[Segment], t: float) -> np.ndarray:
        current = segments[0]
        for segment in segments[1:]:
            if segment.time <= t + EVENT_TOLERANCE:
                current = segment
        return current.at(t)

    def at(self, t: float) -> tuple[np.ndarray, float]:
        """(position NED [m], heading [rad] in (-pi, pi]) at ``t`` [s]."""
        return self._channel(self._position, t), wrap(float(self._channel(self._heading, t)[0]))

    def steps(self, duration: float) -> list[Step]:
        """Every step (not ramp) of a run of ``duration`` [s] that changes its channel."""
        found = []
        for channel, segments in (("position", self._position), ("heading", self._heading)):
            for k, segment in enumerate(segments[1:], start=1):
                until = segments[k + 1].time if k + 1 < len(segments) else duration
                if math.isinf(segment.rate) and np.any(segment.end != segment.start) and segment.time < duration:
                    found.append(Step(channel, segment.time, segment.start, segment.end, min(until, duration)))
        return sorted(found, key=lambda step: step.time)
