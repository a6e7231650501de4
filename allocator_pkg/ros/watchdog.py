"""The stale-input watchdog: whether the wrench input is stale, and what to say when that changes.

Plain logic on nanosecond stamps of the node's clock (simulated time works alike), so that it
is tested without a node."""

from __future__ import annotations


class Watchdog:
    """Input is stale when no valid wrench came for ``timeout`` seconds (0 disables), or none
    has come yet. :meth:`check` returns the state and, on a change only, a log line and its
    severity (``info`` or ``warn``)."""

    def __init__(self, timeout: float):
        self.timeout = timeout
        self.stale = False

    def is_stale(self, now_ns: int, last_ns: int | None) -> bool:
        """Whether the input, last valid at ``last_ns`` (None: never), is stale at ``now_ns``;
        no state changes."""
        return self.timeout > 0.0 and (last_ns is None or now_ns - last_ns > round(self.timeout * 1e9))

    def check(self, now_ns: int, last_ns: int | None) -> tuple[bool, tuple[str, str] | None]:
        stale = self.is_stale(now_ns, last_ns)
        if stale == self.stale:
            return stale, None
        self.stale = stale
        if stale and last_ns is None:
            return stale, ("info", "waiting for wrench_command: commanding zero thrust")
        if stale:
            return stale, ("warn", f"no valid wrench for {self.timeout:g} s: commanding zero thrust")
        return stale, ("info", "wrench input resumed")
