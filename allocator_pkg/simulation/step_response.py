"""Step-response figures of a set-point step, from the sampled response (Ogata, Modern
Control Engineering, section 5-3, the transient-response specifications):

- ``rise_time`` [s]: from 10 % to 90 % of the step, each the first crossing, interpolated
  linearly between samples;
- ``overshoot`` [% of the step]: the largest excursion beyond the new set-point (0 when the
  response never passes it);
- ``settling_time`` [s after the step]: from when the response stays within
  +-SETTLING_BAND of the step around the new set-point until the step's window ends.

A figure the response does not reach within its window (the channel's next change or the
end of the run) is None, never an estimate.

The band is 5 %, not the textbook's 2 %: the 2 % band is meant for a response free of
disturbances, and on station in wind, current and waves the position wanders by the
station-keeping error (0.47 m rms in ``dp_station_keeping``), as much as 2 % of a 25 m step.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

SETTLING_BAND = 0.05
"""Half-width of the settling band, as a share of the step."""


@dataclass(frozen=True)
class StepFigures:
    rise_time: float | None
    """[s], 10 % to 90 %"""
    overshoot: float
    """[% of the step]"""
    settling_time: float | None
    """[s] after the step, into +-SETTLING_BAND"""

    def as_dict(self) -> dict[str, float | None]:
        return asdict(self)


def _crossing(time: np.ndarray, share: np.ndarray, level: float) -> float | None:
    """The first time ``share`` reaches ``level``, interpolated between samples."""
    above = np.nonzero(share >= level)[0]
    if above.size == 0:
        return None
    k = int(above[0])
    if k == 0:
        return float(time[0])
    t0, t1, s0, s1 = time[k - 1], time[k], share[k - 1], share[k]
    return float(t0 + (level - s0) / (s1 - s0) * (t1 - t0))


def step_figures(time: np.ndarray, response: np.ndarray, step_time: float, size: float,
                 until: float = math.inf, band: float = SETTLING_BAND) -> StepFigures:
    """The figures of a step of ``size`` at ``step_time`` [s], from ``response`` (the output's
    change from its value before the step, in the step's units, at each ``time``), over the
    samples from ``step_time`` up to ``until`` [s]."""
    if size == 0.0:
        raise ValueError("step_figures: a step of size 0 has no figures")
    time, response = np.asarray(time, dtype=float), np.asarray(response, dtype=float)
    inside = (time >= step_time - 1e-9) & (time < until - 1e-9)
    t, share = time[inside], response[inside] / size
    if t.size == 0:
        return StepFigures(None, 0.0, None)
    t10, t90 = _crossing(t, share, 0.1), _crossing(t, share, 0.9)
    rise = t90 - t10 if t10 is not None and t90 is not None else None
    overshoot = max(0.0, float(np.max(share)) - 1.0) * 100.0
    outside = np.nonzero(np.abs(share - 1.0) > band)[0]
    if outside.size == 0:
        settling = 0.0
    elif outside[-1] == t.size - 1:
        settling = None
    else:
        k = int(outside[-1])
        e0, e1 = abs(share[k] - 1.0), abs(share[k + 1] - 1.0)
        settling = float(t[k] + (e0 - band) / (e0 - e1) * (t[k + 1] - t[k]) - step_time)
    return StepFigures(rise, overshoot, settling)
