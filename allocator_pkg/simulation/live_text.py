"""The live table's text, as ``allocator-ctl echo`` and the closed loop print it: parts joined
into lines no wider than a terminal's usual width."""

from __future__ import annotations

WIDTH = 120
"""[characters] The live table's lines are at most this wide (unless one part alone is wider)."""


def wrapped(parts: list[str], first: str = "") -> list[str]:
    """``parts`` joined by ' | ' into lines of at most :data:`WIDTH` characters, the first
    starting with ``first``, each later one with '  | '."""
    lines = [first + parts[0]]
    for part in parts[1:]:
        if len(lines[-1]) + 3 + len(part) <= WIDTH:
            lines[-1] += " | " + part
        else:
            lines.append("  | " + part)
    return lines
