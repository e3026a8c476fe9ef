"""What runs between physics steps: callbacks at fixed step intervals, and how far to jump.

The simulation calls a callback every ``every_steps`` physics steps (a controller manager at its
``update_rate``, /clock, sensors, the bus tick). Between two due steps nothing in Python has
to happen, so the engine hands MuJoCo the whole stretch in one ``mj_step(nstep=k)`` call
(:meth:`StepSchedule.steps_to_next_due`), which is bit-for-bit the same as ``k`` single steps.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

__all__ = ["ScheduledCallback", "StepCallback", "StepSchedule"]

StepCallback = Callable[[float], None]


@dataclass(frozen=True, slots=True, eq=False)
class ScheduledCallback:
    """``callback(time_s)`` at every step whose index is a multiple of ``every_steps``."""

    every_steps: int
    callback: StepCallback
    order: int = 0


class StepSchedule:
    """Callbacks by step interval, run in ``order`` then registration order within a step."""

    def __init__(self) -> None:
        self._items: list[ScheduledCallback] = []
        self.plan: tuple[tuple[int, StepCallback], ...] = ()
        """(every_steps, callback) in run order; rebuilt when a callback is added."""
        self._intervals: tuple[int, ...] = ()

    def add(self, item: ScheduledCallback) -> None:
        if item.every_steps < 1:
            raise ValueError(f"every_steps must be >= 1, got {item.every_steps}")
        self._items.append(item)
        self._items.sort(key=lambda s: s.order)  # stable: registration order within an order
        self.plan = tuple((s.every_steps, s.callback) for s in self._items)
        self._intervals = tuple(sorted({s.every_steps for s in self._items}))

    @property
    def runs_every_step(self) -> bool:
        """Whether a callback is due at every step (then there is nothing to jump over)."""
        return bool(self._intervals) and self._intervals[0] == 1

    def run_due(self, step_index: int, time_s: float) -> None:
        """Call every callback due at ``step_index``."""
        for every, callback in self.plan:
            if step_index % every == 0:
                callback(time_s)

    def steps_to_next_due(self, step_index: int) -> int:
        """Steps from ``step_index`` to the next step (after it) at which a callback is due.

        With nothing scheduled there is no such step; the answer is then a large number and
        the caller bounds the jump by its own limits.
        """
        if not self._intervals:
            return 1 << 30
        return min(every - step_index % every for every in self._intervals)
