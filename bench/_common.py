"""Helpers shared by the benchmarks: robust timing and the example-robot-data location."""

from __future__ import annotations

import statistics
import sysconfig
import time
from collections.abc import Callable
from pathlib import Path


def example_robot_data(relative: str) -> Path:
    prefix = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix"
    return prefix / "share" / "example-robot-data" / "robots" / relative


def time_call(func: Callable[[], object], *, repeat: int = 7, min_time_s: float = 0.2) -> float:
    """Median over ``repeat`` rounds of the mean time per call [s]; each round >= min_time_s."""
    func()
    number = 1
    while True:
        start = time.perf_counter()
        for _ in range(number):
            func()
        elapsed = time.perf_counter() - start
        if elapsed >= min_time_s / 4:
            break
        number *= 2
    rounds = []
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(number):
            func()
        rounds.append((time.perf_counter() - start) / number)
    return statistics.median(rounds)
