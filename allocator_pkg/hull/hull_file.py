"""The hull keys of a particulars file (:data:`HULL_KEYS`), the part the simulation's load model
reads (:class:`~allocator_pkg.hull.environment_loads.VesselParticulars`); the DP capability
analysis reads the whole file (:mod:`allocator_pkg.dp.inputs.particulars`), these keys included.
Other keys of the file are the DP analysis' and are not read here."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..configuration.file_keys import MAPPING, NUMBER, FileKey, check_keys, check_required, finite_number
from ..configuration.yaml_file import read_mapping
from .environment_loads import COEFFICIENT_KEYS, LoadCoefficients, VesselParticulars

HULL_KEYS = (
    FileKey("lpp", NUMBER, "Lpp", required=True, unit="m", minimum=0.0, exclusive_minimum=True),
    FileKey("beam", NUMBER, "B at the waterline", required=True, unit="m", minimum=0.0, exclusive_minimum=True),
    FileKey("draught", NUMBER, "T", required=True, unit="m", minimum=0.0, exclusive_minimum=True),
    FileKey("wind_area_frontal", NUMBER, "A_F,wind", required=True, unit="m^2", minimum=0.0,
            exclusive_minimum=True),
    FileKey("wind_area_lateral", NUMBER, "A_L,wind", required=True, unit="m^2", minimum=0.0,
            exclusive_minimum=True),
    FileKey("wind_centre_x", NUMBER, "centre of A_L,wind (x_L,air), body frame", default=0.0, unit="m",
            range_doc="finite"),
    FileKey("underwater_centre_x", NUMBER, "centre of the lateral underwater area (x_L,current), body frame",
            default=0.0, unit="m", range_doc="finite"),
    FileKey("coefficients", MAPPING, "the closed-loop simulation's load model only (environment_loads.py), "
            "not Level 1", default_doc="the defaults below", keys=COEFFICIENT_KEYS),
)
"""The hull's keys (lengths [m], areas [m^2], x positions in the vehicle file's body frame, forward positive)."""


def load_coefficients(coefficients: Any) -> LoadCoefficients:
    """The ``coefficients`` mapping of a particulars file."""
    if not isinstance(coefficients, Mapping):
        raise ValueError("coefficients: a mapping of coefficient names to numbers")
    check_keys(coefficients, COEFFICIENT_KEYS, "coefficients", sort_known=True)
    return LoadCoefficients(**{key: finite_number(value, f"coefficients.{key}") for key, value in coefficients.items()})


def hull_from_mapping(data: Mapping[str, Any]) -> VesselParticulars:
    """The hull of a mapping with the keys of a particulars file."""
    check_required(data, HULL_KEYS)
    numbers = {key.name: finite_number(data[key.name], key.name) if key.name in data else key.default
               for key in HULL_KEYS if key.kind == NUMBER}
    return VesselParticulars(**numbers, coefficients=load_coefficients(data.get("coefficients") or {}))


@dataclass(frozen=True)
class HullFile:
    """What the simulation reads of a particulars file: the hull, and the names of the thrusters
    the file describes (to tell whether it is the vehicle file's vessel)."""

    vessel: VesselParticulars
    thrusters: tuple[str, ...]


def read_hull(path: str | Path) -> HullFile:
    """The hull of a particulars file (YAML) and its thrusters' names; every error names the path."""
    data = read_mapping(path, "a particulars file")
    thrusters = data.get("thrusters")
    try:
        return HullFile(hull_from_mapping(data), tuple(str(name) for name in thrusters)
                        if isinstance(thrusters, Mapping) else ())
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from error
