"""What runs between physics steps: callbacks at fixed step intervals, and how far to jump.

The simulation calls a callback every ``every_steps`` physics steps (a controller manager at its
``update_rate``, /clock, sensors, the bus tick). Between two due steps nothing in Python has
to happen, so the engine hands MuJoCo the whole stretch in one ``mj_step(nstep=k)`` call
(:meth:`StepSchedule.steps_to_next_due`), which is bit-for-bit the same as ``k`` single steps.

A callback can be gated by an ``active()`` predicate (gazebo_ros's model and link states, which
run at every world update only while the topic has subscribers): while it says False the
callback neither runs nor shortens the stretches, so an idle every-step callback costs nothing.
The predicate is asked at every due step, so it must be cheap (a cached subscriber count).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

__all__ = ["ActivePredicate", "ScheduledCallback", "StepCallback", "StepSchedule"]

StepCallback = Callable[[float], None]
ActivePredicate = Callable[[], bool]


@dataclass(frozen=True, slots=True, eq=False)
class ScheduledCallback:
    """``callback(time_s)`` at every step whose index is a multiple of ``every_steps`` (while
    ``active()`` says True, when given)."""

    every_steps: int
    callback: StepCallback
    order: int = 0
    active: ActivePredicate | None = None


class StepSchedule:
    """Callbacks by step interval, run in ``order`` then registration order within a step."""

    def __init__(self) -> None:
        self._items: list[ScheduledCallback] = []
        self.plan: tuple[tuple[int, StepCallback, ActivePredicate | None], ...] = ()
        """(every_steps, callback, active) in run order; rebuilt when a callback is added."""
        self._intervals: tuple[int, ...] = ()
        self._gated: tuple[tuple[int, ActivePredicate], ...] = ()

    def add(self, item: ScheduledCallback) -> None:
        if item.every_steps < 1:
            raise ValueError(f"every_steps must be >= 1, got {item.every_steps}")
        self._items.append(item)
        self._items.sort(key=lambda s: s.order)  # stable: registration order within an order
        self.plan = tuple((s.every_steps, s.callback, s.active) for s in self._items)
        self._intervals = tuple(sorted({s.every_steps for s in self._items if s.active is None}))
        self._gated = tuple((s.every_steps, s.active) for s in self._items if s.active is not None)

    @property
    def runs_every_step(self) -> bool:
        """Whether an ungated callback is due at every step (then there is nothing to jump
        over, ever); a gated one shortens the stretches only while active."""
        return bool(self._intervals) and self._intervals[0] == 1

    def run_due(self, step_index: int, time_s: float) -> None:
        """Call every (active) callback due at ``step_index``."""
        for every, callback, active in self.plan:
            if step_index % every == 0 and (active is None or active()):
                callback(time_s)

    def steps_to_next_due(self, step_index: int) -> int:
        """Steps from ``step_index`` to the next step (after it) at which a callback is due.

        With nothing scheduled there is no such step; the answer is then a large number and
        the caller bounds the jump by its own limits.
        """
        intervals = [*self._intervals, *(every for every, active in self._gated if active())]
        if not intervals:
            return 1 << 30
        return min(every - step_index % every for every in intervals)
