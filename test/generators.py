"""Hypothesis strategies for vehicles nobody picked, their faults and request sequences.

- :func:`vehicles`: 1-12 actuators of every type and anything the schema allows (the property
  tests' broad draw);
- :func:`fixed_vehicles`: 4-10 fixed thrusters anywhere (off the others' plane too), any
  directions, unequal forward and reverse limits, weights, some rate limits;
- :func:`azimuth_vessels`: 2-8 azimuth units on a hull with or without forbidden sectors and
  rate limits, and 0-2 fixed tunnel thrusters;
- :func:`surface_vehicles`: stern thrusters with fins and rudders (as config/infante_auv.yaml),
  drawn with the speed they sail at;
- :func:`faults`: failed, degraded and stuck actuators;
- :func:`request_sequences`: held, stepped, smooth and past-capability requests, in units of
  each DOF's authority.

Every vehicle goes through the loader (``vehicle_from_parameters``); a draw the loader refuses
(a DOF out of reach, say) is rejected, so every vehicle drawn is one a user could load. Each
vehicle strategy returns ``(vehicle, parameters)``, the flat parameters for a params file.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume
from hypothesis import strategies as st

from allocator_pkg import Allocator, ConfigError, FaultMode, Vehicle, vehicle_from_parameters
from allocator_pkg.vehicle.config import DOF_NAMES, SATURATION_MODES

TYPES = ("fixed", "azimuth", "azimuth_vertical", "rudder", "fin")
FIXED_DIRECTIONS = ("fixed", "rudder", "fin")
SPEEDS = (0.5, 1.0, 2.0, 4.0)
"""[m/s] Speeds a control-surface vehicle is drawn at."""

finite = st.floats(min_value=-3.0, max_value=3.0, allow_nan=False)
unit_vector = st.tuples(finite, finite, finite).filter(lambda v: math.hypot(*v) > 0.1)


def loaded(parameters: dict) -> Vehicle:
    """The vehicle of ``parameters``; a draw the loader refuses is rejected."""
    try:
        return vehicle_from_parameters(parameters)
    except ConfigError:
        assume(False)
        raise


@st.composite
def actuator(draw, name: str, types: tuple[str, ...] = TYPES) -> dict:
    """One actuator of any type, with anything its keys allow."""
    kind = draw(st.sampled_from(types))
    keys = {"type": kind, "position": list(draw(st.tuples(finite, finite, finite)))}
    if kind in ("fixed", "azimuth", "azimuth_vertical"):
        keys["thrust_max"] = draw(st.floats(min_value=1.0, max_value=1e4))
        if draw(st.booleans()):
            keys["thrust_rate_max"] = draw(st.floats(min_value=0.5, max_value=1e5))
        keys["command_map"] = draw(st.sampled_from(("linear", "quadratic")))
    if kind in ("fixed", "rudder", "fin"):
        keys["direction"] = list(draw(unit_vector))
    if kind == "fixed":
        keys["thrust_min"] = -draw(st.floats(min_value=0.0, max_value=1.0)) * keys["thrust_max"]
    if kind in ("azimuth", "azimuth_vertical"):
        if draw(st.booleans()):
            keys["azimuth_rate_max"] = draw(st.floats(min_value=0.05, max_value=10.0))
        if draw(st.booleans()):
            low = draw(st.floats(min_value=-3.0, max_value=0.0))
            keys["azimuth_min"], keys["azimuth_max"] = low, low + draw(st.floats(min_value=0.5, max_value=3.0))
            keys["azimuth_initial"] = keys["azimuth_min"]
        elif draw(st.booleans()):
            start = draw(st.floats(min_value=0.5, max_value=2.5))
            keys["forbidden_sectors"] = [start, start + draw(st.floats(min_value=0.1, max_value=1.0))]
        if draw(st.booleans()):
            keys["reversible"] = True
            keys["thrust_min"] = -draw(st.floats(min_value=0.0, max_value=1.0)) * keys["thrust_max"]
    if kind in ("rudder", "fin"):
        keys.update(area=draw(st.floats(min_value=0.01, max_value=1.0)),
                    lift_coefficient=draw(st.floats(min_value=0.5, max_value=5.0)),
                    drag_coefficient=draw(st.floats(min_value=0.0, max_value=2.0)),
                    deflection_max=draw(st.floats(min_value=0.1, max_value=0.6)))
        if draw(st.booleans()):
            keys["deflection_rate_max"] = draw(st.floats(min_value=0.1, max_value=5.0))
    return {f"actuators.{name}.{key}": value for key, value in keys.items()}


@st.composite
def vehicles(draw, types: tuple[str, ...] = TYPES, saturation: tuple[str, ...] = SATURATION_MODES) -> Vehicle:
    """1-12 actuators of ``types``, any controlled DOFs, rate and saturation mode."""
    count = draw(st.integers(min_value=1, max_value=12))
    names = [f"a{i}" for i in range(count)]
    parameters = {"actuators.names": names, "rate_hz": draw(st.sampled_from([10.0, 50.0, 200.0])),
                  "dofs": draw(st.lists(st.sampled_from(DOF_NAMES), min_size=1, max_size=6, unique=True)),
                  "saturation": draw(st.sampled_from(saturation)),
                  "weights.minimax": draw(st.sampled_from([0.0, 0.0, 10.0]))}
    for name in names:
        parameters.update(draw(actuator(name, types)))
    return loaded(parameters)


def _dofs(draw, choices: tuple[str, ...] = DOF_NAMES) -> list[str]:
    """Every DOF of ``choices`` (most draws) or a subset of them."""
    if draw(st.booleans()):
        return list(choices)
    return draw(st.lists(st.sampled_from(choices), min_size=1, max_size=len(choices), unique=True))


@st.composite
def fixed_vehicles(draw, method: str = "qp") -> tuple[Vehicle, dict]:
    """4-10 fixed thrusters: positions anywhere in a 4 m box (z too), any directions, forward
    limits 1-2.5 times the reverse ones or the other way round, weights 0.5-3, some rate limits."""
    count = draw(st.integers(min_value=4, max_value=10))
    names = [f"t{i}" for i in range(count)]
    parameters: dict = {"actuators.names": names, "method": method, "rate_hz": draw(st.sampled_from([20.0, 50.0])),
                        "dofs": _dofs(draw)}
    coordinate = st.floats(min_value=-2.0, max_value=2.0)
    for name in names:
        thrust_max = draw(st.floats(min_value=20.0, max_value=500.0))
        ratio = draw(st.floats(min_value=0.4, max_value=2.5))
        keys = {"type": "fixed", "position": [draw(coordinate), draw(coordinate), draw(coordinate)],
                "direction": list(draw(unit_vector)), "thrust_max": thrust_max, "thrust_min": -thrust_max / ratio,
                "weight": draw(st.floats(min_value=0.5, max_value=3.0))}
        if draw(st.integers(min_value=0, max_value=3)) == 0:
            keys["thrust_rate_max"] = thrust_max * draw(st.floats(min_value=1.0, max_value=20.0))
        parameters.update({f"actuators.{name}.{key}": value for key, value in keys.items()})
    return loaded(parameters), parameters


@st.composite
def azimuth_vessels(draw, method: str = "qp", sectors: bool | None = None, rates: bool | None = None,
                    tunnels: int | None = None, units: tuple[int, int] = (2, 8)) -> tuple[Vehicle, dict]:
    """``units`` (2-8) azimuth units on a 20-80 m hull (surge, sway, yaw), each free or with one
    forbidden sector (``sectors``), with or without thrust and turn rate limits (``rates``), and
    0-2 fixed tunnel thrusters at the bow (``tunnels``); None draws each."""
    count = draw(st.integers(min_value=units[0], max_value=units[1]))
    tunnel_count = draw(st.integers(min_value=0, max_value=2)) if tunnels is None else tunnels
    length = draw(st.floats(min_value=20.0, max_value=80.0))
    names = [f"az{i}" for i in range(count)] + [f"tunnel{i}" for i in range(tunnel_count)]
    parameters: dict = {"actuators.names": names, "method": method, "rate_hz": 10.0,
                        "dofs": ["surge", "sway", "yaw"]}
    with_rates = draw(st.booleans()) if rates is None else rates
    for i in range(count):
        name = f"az{i}"
        thrust_max = draw(st.floats(min_value=1e5, max_value=1e6))
        keys: dict = {"type": "azimuth", "thrust_max": thrust_max,
                      "position": [draw(st.floats(min_value=-0.5, max_value=0.5)) * length,
                                   draw(st.floats(min_value=-0.1, max_value=0.1)) * length,
                                   draw(st.floats(min_value=0.0, max_value=8.0))],
                      "weight": draw(st.floats(min_value=0.5, max_value=2.0))}
        if draw(st.booleans()) if sectors is None else sectors:
            start = draw(st.floats(min_value=0.3, max_value=5.0))
            width = draw(st.floats(min_value=0.2, max_value=1.2))
            keys["forbidden_sectors"] = [start, min(start + width, 2.0 * math.pi - 0.05)]
        if with_rates:
            keys["thrust_rate_max"] = thrust_max * draw(st.floats(min_value=0.05, max_value=0.5))
            keys["azimuth_rate_max"] = draw(st.floats(min_value=0.1, max_value=0.6))
        parameters.update({f"actuators.{name}.{key}": value for key, value in keys.items()})
    for i in range(tunnel_count):
        thrust_max = draw(st.floats(min_value=5e4, max_value=4e5))
        keys = {"type": "fixed", "position": [(0.35 + 0.05 * i) * length, 0.0, 3.0], "direction": [0.0, 1.0, 0.0],
                "thrust_max": thrust_max, "thrust_min": -thrust_max}
        if with_rates:
            keys["thrust_rate_max"] = thrust_max * draw(st.floats(min_value=0.05, max_value=0.5))
        parameters.update({f"actuators.tunnel{i}.{key}": value for key, value in keys.items()})
    return loaded(parameters), parameters


@st.composite
def surface_vehicles(draw, method: str = "qp", drag: bool = True) -> tuple[Vehicle, dict, float]:
    """One or two stern thrusters, 2-4 fins and 1-2 rudders (some behind a propeller), controlled
    in surge and a drawn subset of heave, roll, pitch, yaw; with the speed it sails at. Without
    ``drag`` the surfaces have none (nothing for the thrusters to feed forward, (1.56))."""
    thrusters = draw(st.integers(min_value=1, max_value=2))
    fins = draw(st.integers(min_value=2, max_value=4))
    rudders = draw(st.integers(min_value=1, max_value=2))
    names = [f"prop{i}" for i in range(thrusters)] + [f"fin{i}" for i in range(fins)] + \
        [f"rudder{i}" for i in range(rudders)]
    turning = draw(st.lists(st.sampled_from(("heave", "roll", "pitch", "yaw")), min_size=1, max_size=4, unique=True))
    dofs = ["surge", *turning]
    parameters: dict = {"actuators.names": names, "method": method, "rate_hz": 20.0, "dofs": dofs}
    for i in range(thrusters):
        side = 0.0 if thrusters == 1 else (-0.3 if i == 0 else 0.3)
        thrust_max = draw(st.floats(min_value=100.0, max_value=600.0))
        parameters.update({f"actuators.prop{i}.{key}": value for key, value in {
            "type": "fixed", "position": [-2.0, side, 0.0], "direction": [1.0, 0.0, 0.0],
            "thrust_max": thrust_max, "thrust_min": -0.5 * thrust_max}.items()})
    for i in range(fins):
        side = -0.4 if i % 2 == 0 else 0.4
        keys = {"type": "fin", "position": [draw(st.sampled_from((1.2, -1.6))), side,
                                            draw(st.floats(min_value=-0.1, max_value=0.1))],
                "direction": [0.0, 0.0, -1.0 if side < 0 else 1.0],
                "area": draw(st.floats(min_value=0.05, max_value=0.15)),
                "lift_coefficient": draw(st.floats(min_value=2.0, max_value=4.0)),
                "drag_coefficient": draw(st.floats(min_value=0.0, max_value=1.0)) if drag else 0.0,
                "deflection_max": draw(st.floats(min_value=0.2, max_value=0.5))}
        if draw(st.booleans()):
            keys["deflection_rate_max"] = draw(st.floats(min_value=0.5, max_value=2.0))
        parameters.update({f"actuators.fin{i}.{key}": value for key, value in keys.items()})
    for i in range(rudders):
        keys = {"type": "rudder", "position": [-2.3, 0.0 if rudders == 1 else (-0.3 if i == 0 else 0.3),
                                               draw(st.floats(min_value=-0.2, max_value=0.2))],
                "area": draw(st.floats(min_value=0.04, max_value=0.1)), "lift_coefficient": 3.0,
                "drag_coefficient": draw(st.floats(min_value=0.0, max_value=1.0)) if drag else 0.0,
                "deflection_max": draw(st.floats(min_value=0.3, max_value=0.6))}
        if draw(st.booleans()):
            keys.update(flow="propeller_wake", wake_speed_factor=draw(st.floats(min_value=1.0, max_value=1.5)))
        parameters.update({f"actuators.rudder{i}.{key}": value for key, value in keys.items()})
    return loaded(parameters), parameters, draw(st.sampled_from(SPEEDS))


@st.composite
def faults(draw, vehicle: Vehicle, stuck: bool = True, at_most: int | None = None) -> dict:
    """{actuator: (mode, efficiency, angle)}: failed, degraded (5-100 %), stuck at an angle
    it can take (rotatable thrusters and control surfaces); at most ``at_most`` of them."""
    result = {}
    modes = [None, None, FaultMode.FAILED, FaultMode.DEGRADED] + ([FaultMode.STUCK] if stuck else [])
    for a in vehicle.actuators:
        if at_most is not None and len(result) >= at_most:
            break
        mode = draw(st.sampled_from(modes))
        if mode == FaultMode.DEGRADED:
            result[a.name] = (mode, draw(st.floats(min_value=0.05, max_value=1.0)), 0.0)
        elif mode == FaultMode.STUCK and (a.rotatable or a.is_surface):
            if a.rotatable:
                low, high = (-math.pi, math.pi) if a.rotation.continuous else (a.rotation.azimuth_min,
                                                                               a.rotation.azimuth_max)
                angle = draw(st.floats(min_value=low, max_value=high))
            else:
                angle = draw(st.floats(min_value=-1.0, max_value=1.0)) * a.surface.deflection_max
            result[a.name] = (mode, 1.0, angle)
        elif mode == FaultMode.FAILED:
            result[a.name] = (mode, 0.0, 0.0)
    return result


requests = st.lists(st.tuples(*[st.one_of(st.just(0.0), st.floats(min_value=-1e3, max_value=1e3),
                                          st.floats(min_value=-1e9, max_value=1e9))] * 6),
                    min_size=1, max_size=4)
"""Short sequences of raw requests from zero to 1e9 in any DOF."""

SEQUENCE_KINDS = ("held", "stepped", "smooth", "past capability")


@st.composite
def request_sequences(draw, vehicle: Vehicle, samples: int, kinds: tuple[str, ...] = SEQUENCE_KINDS,
                      scale: float = 0.8) -> tuple[str, np.ndarray]:
    """(kind, samples x 6 requests) in units of each controlled DOF's authority: ``held`` one
    request (each DOF uniform in +-scale of its authority); ``stepped`` two to four such
    requests, each held for an equal share; ``smooth`` a sinusoid of period 40-200 samples
    about one; ``past capability`` one request of 1.5-4 times the authority in some DOF."""
    kind = draw(st.sampled_from(kinds))
    authority = Allocator(vehicle).model.authority
    rows = list(vehicle.dof_indices)
    unit = st.floats(min_value=-1.0, max_value=1.0)

    def one(size: float) -> np.ndarray:
        tau = np.zeros(6)
        tau[rows] = np.array([draw(unit) for _ in rows]) * size * authority
        return tau

    if kind == "held":
        return kind, np.tile(one(scale), (samples, 1))
    if kind == "past capability":
        tau = one(scale)
        k = draw(st.integers(min_value=0, max_value=len(rows) - 1))
        tau[rows[k]] = draw(st.sampled_from((-1.0, 1.0))) * draw(st.floats(min_value=1.5, max_value=4.0)) * \
            authority[k]
        return kind, np.tile(tau, (samples, 1))
    if kind == "stepped":
        levels = [one(scale) for _ in range(draw(st.integers(min_value=2, max_value=4)))]
        share = -(-samples // len(levels))
        return kind, np.vstack([np.tile(level, (share, 1)) for level in levels])[:samples]
    centre, amplitude = one(0.5 * scale), one(0.5 * scale)
    period = draw(st.floats(min_value=40.0, max_value=200.0))
    phase = np.sin(2.0 * math.pi * np.arange(samples) / period)[:, None]
    return kind, centre + phase * amplitude
