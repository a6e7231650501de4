"""matplotlib for every figure of the package: the Agg backend (no display), chosen in this one
place before pyplot is first imported. Every module that draws takes pyplot from :func:`pyplot`."""

from __future__ import annotations

from typing import Any


def pyplot() -> Any:
    """``matplotlib.pyplot`` on the Agg backend (imported on first use: a run that draws nothing
    never loads matplotlib)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
