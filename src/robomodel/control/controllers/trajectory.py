"""Joint trajectories: sampling with linear, cubic or quintic segments.

ros2_controllers joint_trajectory_controller/src/trajectory.cpp (``Trajectory::sample``,
``interpolate_between_points``): the state at reception is the implicit point before the
first waypoint; the segment degree follows the fields both ends have (positions → linear,
+velocities → cubic Hermite, +accelerations → quintic); after the last waypoint its position is
held with zero velocity and acceleration.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

__all__ = ["Sample", "Trajectory", "TrajectoryPoint", "interpolate"]


@dataclass(frozen=True, slots=True)
class TrajectoryPoint:
    """A waypoint ``time_from_start_s`` after the trajectory's start; empty tuples = not given."""

    time_from_start_s: float
    positions: tuple[float, ...]
    velocities: tuple[float, ...] = ()
    accelerations: tuple[float, ...] = ()


@dataclass(frozen=True, slots=True)
class Sample:
    positions: tuple[float, ...]
    velocities: tuple[float, ...]
    accelerations: tuple[float, ...]
    segment: int  # index of the waypoint ahead (len(points) once past the end)


def _segment(
    p0: float,
    v0: float,
    a0: float,
    p1: float,
    v1: float,
    a1: float,
    T: float,
    s: float,
    degree: int,
) -> tuple[float, float, float]:
    if degree == 1 or T <= 0.0:
        if T <= 0.0:
            return p1, 0.0, 0.0
        slope = (p1 - p0) / T
        return p0 + slope * s, slope, 0.0
    if degree == 3:
        T2, T3 = T * T, T * T * T
        c2 = (-3.0 * p0 + 3.0 * p1 - 2.0 * v0 * T - v1 * T) / T2
        c3 = (2.0 * p0 - 2.0 * p1 + v0 * T + v1 * T) / T3
        return (
            p0 + v0 * s + c2 * s * s + c3 * s**3,
            v0 + 2.0 * c2 * s + 3.0 * c3 * s * s,
            2.0 * c2 + 6.0 * c3 * s,
        )
    T2, T3, T4, T5 = T**2, T**3, T**4, T**5
    c2 = a0 / 2.0
    c3 = (-20 * p0 + 20 * p1 - 3 * a0 * T2 + a1 * T2 - 12 * v0 * T - 8 * v1 * T) / (2 * T3)
    c4 = (30 * p0 - 30 * p1 + 3 * a0 * T2 - 2 * a1 * T2 + 16 * v0 * T + 14 * v1 * T) / (2 * T4)
    c5 = (-12 * p0 + 12 * p1 - a0 * T2 + a1 * T2 - 6 * v0 * T - 6 * v1 * T) / (2 * T5)
    return (
        p0 + v0 * s + c2 * s**2 + c3 * s**3 + c4 * s**4 + c5 * s**5,
        v0 + 2 * c2 * s + 3 * c3 * s**2 + 4 * c4 * s**3 + 5 * c5 * s**4,
        2 * c2 + 6 * c3 * s + 12 * c4 * s**2 + 20 * c5 * s**3,
    )


def interpolate(
    t0_s: float, a: TrajectoryPoint, t1_s: float, b: TrajectoryPoint, t_s: float
) -> tuple[tuple[float, ...], tuple[float, ...], tuple[float, ...]]:
    """State at ``t_s`` between ``a`` (at ``t0_s``) and ``b`` (at ``t1_s``)."""
    n = len(b.positions)
    T = t1_s - t0_s
    s = min(max(t_s - t0_s, 0.0), T)
    has_v = bool(a.velocities) and bool(b.velocities)
    has_a = has_v and bool(a.accelerations) and bool(b.accelerations)
    degree = 5 if has_a else 3 if has_v else 1
    zero = (0.0,) * n
    av, bv = a.velocities or zero, b.velocities or zero
    aa, ba = a.accelerations or zero, b.accelerations or zero
    out = [
        _segment(a.positions[k], av[k], aa[k], b.positions[k], bv[k], ba[k], T, s, degree)
        for k in range(n)
    ]
    return tuple(o[0] for o in out), tuple(o[1] for o in out), tuple(o[2] for o in out)


class Trajectory:
    """A trajectory received at ``time_before_s`` in state ``state_before`` and starting at ``start_s``.

    Args:
        start_s: Absolute start time (the message stamp, or the reception time when zero).
        points: The waypoints.
        time_before_s: When the trajectory was received.
        state_before: The state then (positions, and velocities/accelerations when known).
    """

    def __init__(
        self,
        start_s: float,
        points: Sequence[TrajectoryPoint],
        time_before_s: float,
        state_before: TrajectoryPoint,
    ) -> None:
        self.start_s = start_s
        self.points = tuple(points)
        self.time_before_s = time_before_s
        first = self.points[0]
        n = len(first.positions)
        # fill_partial / same degree: zero-fill what the first waypoint has (trajectory.cpp)
        vel = state_before.velocities or ((0.0,) * n if first.velocities else ())
        acc = state_before.accelerations or ((0.0,) * n if first.accelerations else ())
        self.state_before = TrajectoryPoint(
            0.0,
            state_before.positions,
            vel if first.velocities else (),
            acc if first.accelerations and first.velocities else (),
        )

    @property
    def end_s(self) -> float:
        return self.start_s + self.points[-1].time_from_start_s

    def sample(self, t_s: float) -> Sample | None:
        """The state at ``t_s``; ``None`` before the reception time."""
        if t_s < self.time_before_s:
            return None
        first = self.points[0]
        t_first = self.start_s + first.time_from_start_s
        if t_s < t_first:
            p, v, a = interpolate(self.time_before_s, self.state_before, t_first, first, t_s)
            return Sample(p, v, a, 0)
        for i in range(len(self.points) - 1):
            t_next = self.start_s + self.points[i + 1].time_from_start_s
            if t_s < t_next:
                t_i = self.start_s + self.points[i].time_from_start_s
                p, v, a = interpolate(t_i, self.points[i], t_next, self.points[i + 1], t_s)
                return Sample(p, v, a, i + 1)
        last = self.points[-1]
        n = len(last.positions)
        return Sample(
            last.positions,
            last.velocities or (0.0,) * n,
            last.accelerations or (0.0,) * n,
            len(self.points),
        )
