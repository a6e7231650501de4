"""What a scenario file may say, and whether its parts fit together: every key known at every
depth (an unknown one is named with the nearest known one), the vehicle file and the particulars
fit for the hull model, the method able to serve the vehicle, a supply voltage within the
vehicle's thrust tables, an environment the hull model takes and within what the sea gives, and
every event valid for that vehicle before the run starts."""

from __future__ import annotations

import difflib
from collections.abc import Sequence
from typing import Any, Protocol

from ..allocation.solve import check_method
from ..configuration.file_keys import EACH, FileKey
from ..configuration.schema import key_for
from ..hull.hull_file import HullFile
from ..methods import METHODS
from ..vehicle.config import Vehicle
from .scenario_keys import SCENARIO_KEYS
from .vessel import VesselParameters

MODEL_DOFS = {"dp_vessel": ("surge", "sway", "yaw"), "bluerov2_heavy": ("surge", "sway", "heave", "yaw")}
"""The DOFs each hull model needs its vehicle to control: the vessel moves in the horizontal
plane only; the ROV's station keeping holds depth and heading, its roll and pitch are
self-righting."""

PLANAR_DOFS = ("surge", "sway", "yaw")
SEA_LIMITS = {"wind": 70.0, "current": 10.0, "waves": 25.0}
"""The largest mean wind speed [m/s], current speed [m/s] and significant wave height [m] a
scenario may reach (with its weather ramps): above the sustained wind of the strongest
hurricanes (about 70 m/s), the fastest tidal races (about 20 knots) and the highest significant
wave heights measured (about 20 m). More is a slip of a unit or a digit, not weather."""
SUBMERGED_MODELS = ("bluerov2_heavy",)
"""Hull models under water: no wind or waves act on them, and their depth is at least 0."""


def nearest(word: str, choices: list[str]) -> str:
    """The known key a misspelt one most likely meant ('' when none is close)."""
    close = difflib.get_close_matches(word, choices, n=1, cutoff=0.6)
    if close:
        return close[0]
    abbreviated = [choice for choice in choices if choice.startswith(word)]
    return abbreviated[0] if abbreviated else ""


def unknown_keys(data: Any, known: Sequence[FileKey] = SCENARIO_KEYS, where: str = "") -> list[str]:
    """Every key of ``data`` that the table ``known`` (:data:`~.scenario_keys.SCENARIO_KEYS`)
    does not have, at any depth, each as 'path: unknown key; did you mean ...?'."""
    found: list[str] = []
    if not isinstance(data, dict):
        return found
    by_name = {key.name: key for key in known}
    for name, value in data.items():
        path = f"{where}.{name}" if where else str(name)
        key = by_name.get(name)
        if key is None:
            guess = nearest(str(name), list(by_name))
            found.append(f"{path}: unknown key" + (f"; did you mean {guess}?" if guess else
                                                    f" (known: {', '.join(by_name)})"))
        elif key.keys and key.item == EACH and isinstance(value, list):
            for index, item in enumerate(value):
                found += unknown_keys(item, key.keys, f"{path}[{index}]")
        elif key.keys and key.item.startswith("<") and isinstance(value, dict):
            for item_name, item in value.items():
                found += unknown_keys(item, key.keys, f"{path}.{item_name}")
        elif key.keys and key.item != EACH:
            found += unknown_keys(value, key.keys, path)
    return found


def check_vehicle(model: str, vehicle: Vehicle, name: str) -> None:
    """Raise ValueError when the vehicle file cannot drive the hull ``model``: a DOF the hull
    needs held that the vehicle does not control, or, for the horizontal-plane vessel, a DOF
    the vessel does not have."""
    missing = [dof for dof in MODEL_DOFS[model] if dof not in vehicle.dofs]
    if missing:
        raise ValueError(f"vehicle: {name} does not control {', '.join(missing)}, which the {model} model needs "
                         f"held (it controls {', '.join(vehicle.dofs)}); is it a vehicle file for {model}?")
    if model == "dp_vessel":
        extra = [dof for dof in vehicle.dofs if dof not in PLANAR_DOFS]
        if extra:
            raise ValueError(f"vehicle: {name} controls {', '.join(extra)}, which the dp_vessel model (surge, sway "
                             "and yaw only) does not have; is it a vehicle file for dp_vessel?")


def check_method_serves(method: str, vehicle: Vehicle) -> None:
    """Raise ValueError naming why ``method`` cannot run on ``vehicle`` (unknown, or unfit)."""
    if method not in METHODS:
        guess = nearest(method, list(METHODS))
        raise ValueError(f"method: '{method}' is not a method" + (f"; did you mean {guess}?" if guess else "")
                         + f" (methods: {', '.join(METHODS)})")
    check_method(method, vehicle)


def check_parameter(name: str, where: str) -> None:
    """Raise ValueError when ``name`` is not a parameter of the allocator that can change while
    the node runs."""
    key = key_for(name)
    if key is None:
        raise ValueError(f"{where}: '{name}' is not a parameter of the allocator (see docs/configuration.md)")
    if key.read_only:
        raise ValueError(f"{where}: '{name}' is read-only while the node runs")


def check_member(name: str, known: list[str], where: str, what: str) -> None:
    """Raise ValueError when ``name`` is not among the vehicle's ``known`` names of ``what``."""
    if name not in known:
        raise ValueError(f"{where}: '{name}' is not a {what} of the vehicle ("
                         + (", ".join(known) if known else "it has none") + ")")


def check_particulars(model: str, vehicle: Vehicle, hull_file: HullFile, name: str) -> None:
    """Raise ValueError when the particulars (``name``, the file) are not those of the hull
    ``model`` simulates or do not describe the vehicle's thrusters: the dp_vessel model is one
    hull (:class:`~.vessel.VesselParameters`), and the particulars name each actuator of its
    vehicle file among their thrusters."""
    if model != "dp_vessel":
        return
    hull = VesselParameters()
    vessel = hull_file.vessel
    given, simulated = (vessel.lpp, vessel.beam, vessel.draught), (hull.length, hull.beam, hull.draught)
    if any(abs(a - b) > 1e-6 * b for a, b in zip(given, simulated)):
        raise ValueError(f"particulars: {name} is a hull of {given[0]:g} x {given[1]:g} x {given[2]:g} m "
                         f"(length, beam, draught), not the dp_vessel model's {simulated[0]:g} x {simulated[1]:g} x "
                         f"{simulated[2]:g} m")
    if set(hull_file.thrusters) != set(vehicle.names):
        raise ValueError(f"vehicle: its actuators ({', '.join(vehicle.names)}) are not the thrusters of the "
                         f"dp_vessel's particulars {name} ({', '.join(hull_file.thrusters)}); is it a vehicle "
                         "file for dp_vessel?")


def check_voltage(vehicle: Vehicle, voltage: float, where: str) -> None:
    """Raise ValueError when the vehicle's thrust tables do not cover the supply ``voltage`` [V]
    (or it has none measured at several voltages): the allocator would refuse it and keep the
    limits of another voltage."""
    covered = vehicle.voltage_range
    if covered is None:
        raise ValueError(f"{where}: the vehicle has no thrust tables measured at several supply voltages, so a "
                         "voltage changes nothing; leave it out")
    if not covered[0] <= voltage <= covered[1]:
        raise ValueError(f"{where}: {voltage:g} V is outside the vehicle's thrust tables ({covered[0]:g} to "
                         f"{covered[1]:g} V)")


def check_environment(model: str, data: dict[str, Any], scale: float) -> None:
    """Raise ValueError when the environment section (``data``, as the file gives it) asks what
    the hull ``model`` does not take (wind and waves on a submerged one) or, at the largest
    scale the weather ramps reach (``scale``), more than :data:`SEA_LIMITS`."""
    if model in SUBMERGED_MODELS:
        for key in ("wind", "waves"):
            if key in data:
                raise ValueError(f"environment.{key}: the {model} model is submerged: no wind or waves act on it "
                                 "(its environment is the current)")
    for key, speed in (("wind", "speed"), ("current", "speed"), ("waves", "hs")):
        value = (data.get(key) or {}).get(speed, 0.0)
        if isinstance(value, (int, float)) and abs(value) * scale > SEA_LIMITS[key]:
            reached = f" ({scale:g} times {value:g} with the weather ramps)" if scale != 1.0 else ""
            raise ValueError(f"environment.{key}.{speed}: at most {SEA_LIMITS[key]:g} "
                             f"{'m' if key == 'waves' else 'm/s'}, not {abs(value) * scale:g}{reached}: no sea "
                             "gives it; is the unit or a digit wrong?")
    down = (data.get("current") or {}).get("down", 0.0)
    if isinstance(down, (int, float)) and abs(down) * scale > SEA_LIMITS["current"]:
        raise ValueError(f"environment.current.down: at most {SEA_LIMITS['current']:g} m/s, not {down!r}")


def check_depth(model: str, position: tuple[float, ...], where: str) -> None:
    """Raise ValueError when a position's down [m] does not fit the hull ``model``: a submerged
    one stays at or below the surface (down >= 0), the vessel floats on it (down 0)."""
    down = position[2]
    if model in SUBMERGED_MODELS and down < 0.0:
        raise ValueError(f"{where}: down {down:g} m is above the surface; the {model} model's depth is down >= 0")
    if model not in SUBMERGED_MODELS and down != 0.0:
        raise ValueError(f"{where}: down {down:g} m; the {model} model floats at the surface (down 0)")


class TimedEvent(Protocol):
    """What :func:`check_run` reads of a scenario's event (:class:`~.scenario.Event`)."""

    time: float
    kind: str
    value: Any


def check_run(model: str, vehicle: Vehicle, duration: float, voltage: float | None, events: Sequence[TimedEvent],
              environment_data: dict, positions: dict[str, tuple[float, ...]]) -> None:
    """Raise ValueError when the run would not be what the file says: an event at or after its
    end, a supply voltage (or a battery ramp's) outside the vehicle's thrust tables or without
    them, a ramp without a voltage to start from, an environment the hull model does not take
    or no sea gives, a position above the surface (the ROV) or off it (the vessel)."""
    for index, event in enumerate(events):
        if event.time >= duration:
            raise ValueError(f"events[{index}].time: {event.time:g} s is not within the run (0 to {duration:g} s); "
                             "the run ends before it")
        if event.kind == "battery_ramp":
            check_voltage(vehicle, float(event.value), f"events[{index}].battery_ramp.to")
            if voltage is None:
                raise ValueError(f"events[{index}].battery_ramp: needs battery.voltage, the voltage it starts from")
        if event.kind == "setpoint" and event.value.position is not None:
            check_depth(model, event.value.position, f"events[{index}].setpoint.position")
    if voltage is not None:
        check_voltage(vehicle, voltage, "battery.voltage")
    scale = max([1.0] + [float(e.value) for e in events if e.kind == "weather_ramp"])
    check_environment(model, environment_data, scale)
    for where, position in positions.items():
        check_depth(model, position, where)
