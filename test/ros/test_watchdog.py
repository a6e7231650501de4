"""The stale-input watchdog on nanosecond stamps."""

from allocator_pkg.ros.watchdog import Watchdog

S = 10**9


def test_stale_before_any_input_after_the_timeout_and_never_when_disabled():
    watchdog = Watchdog(0.5)
    assert watchdog.check(1 * S, None) == (True, ("info", "waiting for wrench_command: commanding zero thrust"))
    assert watchdog.check(2 * S, None) == (True, None)                     # said once per change
    assert watchdog.check(2 * S, 2 * S) == (False, ("info", "wrench input resumed"))
    assert watchdog.check(2 * S + S // 2, 2 * S) == (False, None)         # exactly the timeout: not yet
    assert watchdog.check(2 * S + S // 2 + 1, 2 * S) == \
        (True, ("warn", "no valid wrench for 0.5 s: commanding zero thrust"))
    watchdog.timeout = 0.0
    assert watchdog.check(100 * S, 2 * S) == (False, ("info", "wrench input resumed"))


def test_is_stale_answers_without_changing_what_check_reports():
    watchdog = Watchdog(0.5)
    assert watchdog.is_stale(1 * S, None) and watchdog.is_stale(2 * S + 1, S + S // 2)
    assert not watchdog.is_stale(2 * S, S + S // 2)
    assert watchdog.check(1 * S, None) == (True, ("info", "waiting for wrench_command: commanding zero thrust"))
