"""What a run's simulated electric power plant (:mod:`.electric_plant`) did, for metrics.json:
per switchboard the lowest frequency of its bus and how long it was below ``UNDER_FREQUENCY``,
the generator sets the frequency relays tripped, and the run's three bounded figures
(:data:`~.metrics.PLANT_METRICS`)."""

from __future__ import annotations

import numpy as np

from .electric_plant import RELAY, PlantRecord

UNDER_FREQUENCY = 0.95
"""[pu] A bus below this frequency counts in ``time_under_frequency``."""


def plant_report(record: PlantRecord, sources: tuple[str, ...], period: float) -> dict:
    """``power_plant`` of metrics.json: per switchboard, its lowest frequency [pu] and time
    under UNDER_FREQUENCY [s]; the sets that went off (time, name, why); and the run's
    metrics of :data:`~.metrics.PLANT_METRICS`."""
    frequency = np.asarray(record.frequency, dtype=float).reshape(-1, len(sources))
    under = frequency < UNDER_FREQUENCY
    per_board = {name: {"lowest_frequency": float(np.min(frequency[:, j])) if len(frequency) else 1.0,
                        "time_under_frequency": float(np.count_nonzero(under[:, j]) * period)}
                 for j, name in enumerate(sources)}
    metrics = {"frequency_dip": float(1.0 - np.min(frequency)) if len(frequency) else 0.0,
               "time_under_frequency": float(np.count_nonzero(under.any(axis=1)) * period),
               "generator_sets_tripped": float(sum(1 for _, _, why in record.trips if why == RELAY))}
    return {"switchboards": per_board, "generator_sets_off": [
        {"time": time, "generator_set": name, "why": why} for time, name, why in record.trips], "metrics": metrics}
