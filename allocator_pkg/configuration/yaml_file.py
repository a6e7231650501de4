"""The one reader of this package's YAML input files that are not ROS params files (particulars,
site, scenario, Level 3 criteria): a mapping, with the file's path named in every error."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml


def read_mapping(path: str | Path, what: str) -> Mapping[str, Any]:
    """The top-level mapping of the YAML file ``path``; a ``ValueError`` that names the path when
    the file cannot be read, is not YAML or is not a mapping (``what`` names the kind of file)."""
    return read_yaml(path, what)[0]


def read_yaml(path: str | Path, what: str) -> tuple[Mapping[str, Any], str]:
    """:func:`read_mapping` and the file's text, from one read (for a caller that also reads
    what the file's comments say)."""
    path = Path(path)
    try:
        text = path.read_text()
        data = yaml.safe_load(text)
    except (OSError, yaml.YAMLError) as error:
        raise ValueError(f"{path}: {error}") from error
    if not isinstance(data, Mapping):
        raise ValueError(f"{path}: {what} is a mapping of keys to values")
    return data, text
