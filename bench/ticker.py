"""A bare periodic loop: the host's own share of late ticks, for ``make soak`` to compare with.

It sleeps to deadlines every 1/rate seconds, skips the deadlines it has passed (as an ROS
timer does), records when it woke, and counts missed periods exactly as the benchmarks count
the node's (``figures.MISSED_FACTOR``): no ROS node, no allocation, nothing in its way, so what
it misses is what the machine's scheduling costs any process with a deadline. Prints one JSON
object.

    .venv/bin/python bench/ticker.py SECONDS [RATE_HZ]
"""

import json
import math
import sys
import time

import numpy as np
from figures import MISSED_FACTOR


def tick(seconds: float, rate_hz: float) -> list[float]:
    """Wake times [s] of a loop with deadlines every 1/rate_hz s for ``seconds``: deadline k
    is start + k / rate_hz, counted by its integer index (a float deadline grown by adding the
    period drifts, and ten periods could give eleven deadlines before the end)."""
    period = 1.0 / rate_hz
    count = round(seconds * rate_hz)
    start = time.monotonic()
    woke: list[float] = []
    k = 1
    while k <= count:
        time.sleep(max(0.0, start + k * period - time.monotonic()))
        now = time.monotonic()
        woke.append(now)
        k = max(k + 1, math.floor((now - start) / period) + 1)
    return woke


def missed(woke: list[float], rate_hz: float) -> dict:
    """Missed periods, counted like the node's, and the longest interval between wake-ups."""
    period = 1.0 / rate_hz
    intervals = np.diff(woke)
    late = intervals[intervals > MISSED_FACTOR * period]
    count = int(np.sum(np.round(late / period) - 1))
    expected = max(1, round(float(np.sum(intervals)) / period))
    return {"rate_hz": rate_hz, "ticks": len(woke), "missed": count,
            "missed_percent": round(100.0 * count / expected, 2),
            "longest_interval_ms": round(float(np.max(intervals, initial=0.0)) * 1e3, 2)}


if __name__ == "__main__":
    rate = float(sys.argv[2]) if len(sys.argv) > 2 else 500.0
    print(json.dumps(missed(tick(float(sys.argv[1]), rate), rate)))
