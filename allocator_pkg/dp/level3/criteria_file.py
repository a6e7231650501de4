"""The Level 3 criteria file (``--level3-criteria FILE``, ``config/level3/criteria.yaml``): a
YAML mapping of the keys of :data:`~.case.CRITERIA_KEYS`, each optional (its default then); an
unknown key, a value of the wrong kind or out of its range is refused naming the file and the key."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ...configuration.file_keys import INTEGER, NUMBER, check_keys, defaults, key_named
from ...configuration.yaml_file import read_mapping
from .case import CRITERIA_KEYS, Criteria, check_criterion


def criteria_from_mapping(data: Mapping[str, Any], where: str = "criteria") -> Criteria:
    """The :class:`Criteria` of ``data`` (keys of :data:`CRITERIA_KEYS`, the others at their
    defaults); ValueError naming ``where`` and the key."""
    check_keys(data, CRITERIA_KEYS, where)
    values = defaults(CRITERIA_KEYS)
    for name, value in data.items():
        key = key_named(CRITERIA_KEYS, name)
        try:
            check_criterion(key, value)
        except ValueError as error:
            raise ValueError(f"{where}: {error}") from None
        values[name] = float(value) if key.kind == NUMBER else int(value) if key.kind == INTEGER else value
    return Criteria(**values)


def read_criteria(path: str | Path | None, overrides: Mapping[str, Any] | None = None) -> Criteria:
    """The criteria of the file ``path`` (None: the defaults) with ``overrides`` (key: value, the
    command line's) in place of its values."""
    data = dict(read_mapping(path, "a Level 3 criteria file")) if path is not None else {}
    where = str(path) if path is not None else "criteria"
    data.update(overrides or {})
    return criteria_from_mapping(data, where)
