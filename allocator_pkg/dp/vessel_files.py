"""The input files of a DNV-ST-0111 Level 1 or 2 analysis, each read once before the analysis
runs: the vehicle params file, the particulars file (:mod:`.inputs.particulars`) with what its
comments state about each top-level value (its unit and where it comes from, for the report's
inputs table) and, at Level 2, a site environment file (:mod:`.inputs.site`)."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from ..configuration.parameters import load_vehicle
from ..vehicle.config import Vehicle
from .inputs.particulars import Particulars, read_particulars
from .inputs.site import SiteEnvironment, load_site

STATED = re.compile(r"^([a-z_]+):\s*([^#]*?)\s*#\s*(.+)$")
"""A top-level key of a particulars file, its value and the comment beside it."""


@dataclass(frozen=True)
class VesselFiles:
    """The paths as given, what they hold, and the particulars file's statement of each
    commented top-level value: (key, value, comment)."""

    vehicle_path: Path
    particulars_path: Path
    vehicle: Vehicle
    particulars: Particulars
    site: SiteEnvironment | None
    stated: tuple[tuple[str, str, str], ...]


def read_vessel_files(vehicle_path: str | Path, particulars_path: str | Path,
                      site_path: str | Path | None = None) -> VesselFiles:
    """Read the vehicle file, the particulars file and the site file if given, in that order; a
    ``ValueError`` (a ``ConfigError`` too) naming the file and the key when one is refused."""
    vehicle_path, particulars_path = Path(vehicle_path), Path(particulars_path)
    vehicle = load_vehicle(vehicle_path)
    particulars, text = read_particulars(particulars_path)
    site = load_site(site_path) if site_path else None
    return VesselFiles(vehicle_path, particulars_path, vehicle, particulars, site, stated_values(text))


def stated_values(text: str) -> tuple[tuple[str, str, str], ...]:
    """(key, value, comment) of each top-level key of a particulars file's text with a comment
    beside it: the file's statement of the unit and where the value comes from."""
    return tuple(match.groups() for line in text.splitlines() if (match := STATED.match(line)))
