"""Test timeouts that scale with the machine: ``scaled(seconds)``.

Every timeout, deadline and bounded wait in the tests goes through :func:`scaled`, so that a
test that needs 2 s on a quiet machine is given 2 s times the factor on a busy one (a loaded CI
runner, a laptop building something else, ``taskset -c 0``). The factor is

- ``ROBOMODEL_TEST_TIMEOUT_SCALE`` when set (a number >= 1, e.g. ``4``);
- else measured in each test process (again every 20 s): the larger of the load average per core and how much
  slower than a quiet reference machine a short piece of pure-Python work runs here (which is
  what a process pinned to one busy core sees), kept between 1 and ``MAX_SCALE``.

A timeout only bounds how long a failing test waits: scaling it up never makes a passing test
slower, because each test waits for a condition, not for the time: :func:`wait_until` is how.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from typing import TypeVar

__all__ = ["ENVIRONMENT_VARIABLE", "MAX_SCALE", "scale", "scale_source", "scaled", "wait_until"]

T = TypeVar("T")

ENVIRONMENT_VARIABLE = "ROBOMODEL_TEST_TIMEOUT_SCALE"
MAX_SCALE = 20.0
# Seconds the probe below takes on a quiet 2020s x86 core (measured: 14-15 ms); a machine that
# takes longer is slow or busy in proportion.
_REFERENCE_PROBE_S = 0.015


def _probe_s() -> float:
    """The best of three runs of a fixed piece of work [s] (the best, so one preemption
    does not count; a machine busy all the time still shows)."""
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        sum(i * i for i in range(200_000))
        best = min(best, time.perf_counter() - start)
    return best


_REMEASURE_AFTER_S = 20.0
_last: tuple[float, tuple[float, str]] | None = None  # (monotonic time, measurement)


def _measured() -> tuple[float, str]:
    """The factor and its source; measured again every ``_REMEASURE_AFTER_S``: a run that
    began on a quiet machine keeps up when the machine gets busy later (a test process lives
    for the whole run, and a factor taken at its start held 1.0 while the load reached 15)."""
    global _last
    now = time.monotonic()
    if _last is None or now - _last[0] > _REMEASURE_AFTER_S:
        _last = (now, _measure())
    return _last[1]


def _measure() -> tuple[float, str]:
    text = os.environ.get(ENVIRONMENT_VARIABLE, "").strip()
    if text:
        try:
            value = float(text)
        except ValueError:
            raise ValueError(
                f"{ENVIRONMENT_VARIABLE} must be a number >= 1, got '{text}'"
            ) from None
        if not value >= 1.0:
            raise ValueError(f"{ENVIRONMENT_VARIABLE} must be a number >= 1, got '{text}'")
        return value, f"{ENVIRONMENT_VARIABLE}={text}"
    load_per_core = os.getloadavg()[0] / (os.cpu_count() or 1)
    slowdown = _probe_s() / _REFERENCE_PROBE_S
    value = min(MAX_SCALE, max(1.0, load_per_core, slowdown))
    return value, f"measured: load {load_per_core:.2f}/core, probe {slowdown:.2f}x"


def scale() -> float:
    """The factor every test timeout is multiplied by (see the module docstring)."""
    return _measured()[0]


def scale_source() -> str:
    """Where :func:`scale` came from, for pytest's header."""
    return _measured()[1]


def scaled(seconds: float) -> float:
    """``seconds`` times the machine's timeout factor."""
    return seconds * scale()


def wait_until(
    predicate: Callable[[], T],
    timeout_s: float,
    *,
    what: str | Callable[[], str],
    interval_s: float = 0.05,
) -> T:
    """Call ``predicate`` until it returns a true value, and return that value.

    Fails with an ``AssertionError`` naming ``what`` (a callable is asked only then, so the
    message can show what the test saw last) after ``scaled(timeout_s)``. ``predicate`` is
    called once more at the deadline, so a slow last call still counts; it may raise to stop
    the wait early (a process it waits on has ended). ``interval_s`` is the pause between
    calls, not scaled: it sets how soon the condition is seen, not how long a test may take.
    """
    limit_s = scaled(timeout_s)
    deadline = time.monotonic() + limit_s
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            label = what() if callable(what) else what
            raise AssertionError(f"timed out after {limit_s:.1f} s waiting for {label}")
        time.sleep(interval_s)
