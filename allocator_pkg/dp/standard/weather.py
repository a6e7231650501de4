"""The environmental conditions of DNV-ST-0111 Table 2-1 (one per DP capability number 0-11),
between them (:func:`condition_at`), and the search of a heading's number and limiting wind speed
(:func:`limit`): the highest number held with every lower one [2.2.2], then bisection toward the
next. Edition December 2021, as transcribed in WilliamBoland1/Prosjektoppgave_Collab
(``dp_capability/standard.py``); not verified by DNV.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, fields

BISECTION_STEPS = 14
"""Halvings of the interval between two capability numbers for the limiting wind speed."""


@dataclass(frozen=True)
class WeatherCondition:
    """One environmental condition: wind [m/s], Hs [m], Tp [s], current [m/s]."""

    wind: float
    hs: float
    tp: float
    current: float


WEATHER_CONDITIONS = (
    WeatherCondition(0.0, 0.0, 0.0, 0.0),
    WeatherCondition(1.5, 0.1, 3.5, 0.25),
    WeatherCondition(3.4, 0.4, 4.5, 0.50),
    WeatherCondition(5.4, 0.8, 5.5, 0.75),
    WeatherCondition(7.9, 1.3, 6.5, 0.75),
    WeatherCondition(10.7, 2.1, 7.5, 0.75),
    WeatherCondition(13.8, 3.1, 8.5, 0.75),
    WeatherCondition(17.1, 4.2, 9.0, 0.75),
    WeatherCondition(20.7, 5.7, 10.0, 0.75),
    WeatherCondition(24.4, 7.4, 10.5, 0.75),
    WeatherCondition(28.4, 9.5, 11.5, 0.75),
    WeatherCondition(32.6, 12.1, 12.0, 0.75),
)
"""The conditions of DP capability numbers 0 to 11 (index = number)."""
TOP = len(WEATHER_CONDITIONS) - 1


def condition_at(level: float,
                 conditions: tuple[WeatherCondition, ...] = WEATHER_CONDITIONS) -> WeatherCondition:
    """The condition at a fractional capability number in [0, top] of ``conditions`` (Table 2-1
    unless a site's), each quantity linear between the two numbers around it."""
    top = len(conditions) - 1
    if not 0.0 <= level <= top:
        raise ValueError(f"a capability number between 0 and {top}, not {level}")
    low = min(math.floor(level), top - 1)
    t = level - low
    a, b = conditions[low], conditions[low + 1]
    return WeatherCondition(*((1.0 - t) * getattr(a, f.name) + t * getattr(b, f.name)
                              for f in fields(WeatherCondition)))


def limit(balanced: Callable[[float], bool],
          conditions: tuple[WeatherCondition, ...] = WEATHER_CONDITIONS) -> tuple[int, float]:
    """(capability number, limiting wind speed) from a test of a fractional number: the highest
    number held with every lower one, then bisection toward the next (over ``conditions``)."""
    top = len(conditions) - 1
    number = 0
    while number < top and balanced(number + 1):
        number += 1
    if number == top:
        return number, conditions[top].wind
    low, high = float(number), float(number + 1)
    for _ in range(BISECTION_STEPS):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if balanced(middle) else (low, middle)
    return number, condition_at(low, conditions).wind
