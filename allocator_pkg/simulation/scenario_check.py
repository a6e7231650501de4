"""What a scenario file may say, and whether its parts fit together: every key known at every
depth (an unknown one is named with the nearest known one), the vehicle file fit for the hull
model, the method able to serve the vehicle, and every event valid for that vehicle before the
run starts."""

from __future__ import annotations

import difflib
from collections.abc import Sequence
from typing import Any

from ..allocation.solve import check_method
from ..configuration.file_keys import EACH, FileKey
from ..configuration.schema import key_for
from ..methods import METHODS
from ..vehicle.config import Vehicle
from .scenario_keys import SCENARIO_KEYS

MODEL_DOFS = {"dp_vessel": ("surge", "sway", "yaw"), "bluerov2_heavy": ("surge", "sway", "heave", "yaw")}
"""The DOFs each hull model needs its vehicle to control: the vessel moves in the horizontal
plane only; the ROV's station keeping holds depth and heading, its roll and pitch are
self-righting."""

PLANAR_DOFS = ("surge", "sway", "yaw")


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
