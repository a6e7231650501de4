"""The hull keys of a particulars file, the part the simulation's load model reads
(:class:`~allocator_pkg.hull.environment_loads.VesselParticulars`); the DP capability analysis
reads the whole file (:mod:`allocator_pkg.dp.inputs.particulars`), these keys included.

Keys (lengths [m], areas [m^2], x positions in the vehicle file's body frame, forward positive):
``lpp``, ``beam``, ``draught``, ``wind_area_frontal``, ``wind_area_lateral`` (> 0),
``wind_centre_x`` (centre of the lateral wind area), ``underwater_centre_x`` (centre of the
lateral underwater area) and ``coefficients`` (:class:`~.environment_loads.LoadCoefficients`).
Other keys of the file are the DP analysis' and are not read here."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import fields
from pathlib import Path
from typing import Any

from ..configuration.yaml_file import read_mapping
from .environment_loads import LoadCoefficients, VesselParticulars

HULL_KEYS = ("lpp", "beam", "draught", "wind_area_frontal", "wind_area_lateral", "wind_centre_x",
             "underwater_centre_x")
"""The hull's numbers; the first five are required."""


def finite_number(data: Mapping[str, Any], key: str, prefix: str = "") -> float:
    """``data[key]`` as a finite float, or a ``ValueError`` naming ``prefix + key``."""
    value = data[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{prefix}{key}: a finite number, not {value!r}")
    return float(value)


def load_coefficients(coefficients: Any) -> LoadCoefficients:
    """The ``coefficients`` mapping of a particulars file."""
    if not isinstance(coefficients, Mapping):
        raise ValueError("coefficients: a mapping of coefficient names to numbers")
    names = {f.name for f in fields(LoadCoefficients)}
    bad = sorted(set(coefficients) - names)
    if bad:
        raise ValueError(f"coefficients: unknown key(s) {', '.join(bad)}; known: {', '.join(sorted(names))}")
    return LoadCoefficients(**{key: finite_number(coefficients, key, "coefficients.") for key in coefficients})


def hull_from_mapping(data: Mapping[str, Any]) -> VesselParticulars:
    """The hull of a mapping with the keys of a particulars file."""
    missing = [key for key in HULL_KEYS[:5] if key not in data]
    if missing:
        raise ValueError(f"missing key(s): {', '.join(missing)}")
    numbers = {key: finite_number(data, key) for key in HULL_KEYS if key in data}
    return VesselParticulars(**numbers, coefficients=load_coefficients(data.get("coefficients") or {}))


def load_hull(path: str | Path) -> VesselParticulars:
    """The hull of a particulars file (YAML); every error names the path."""
    data = read_mapping(path, "a particulars file")
    try:
        return hull_from_mapping(data)
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from error
