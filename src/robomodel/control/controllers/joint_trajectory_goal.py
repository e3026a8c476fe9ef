"""joint_trajectory_controller goals: their status and whether a trajectory is acceptable.

A :class:`GoalHandle` is the in-process FollowJointTrajectory goal (status, ``error_code``,
per-goal tolerances); :func:`validate_trajectory` is humble's ``validate_trajectory_msg``, the
check every trajectory passes before it replaces the running one (topic and action alike).
"""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from robomodel.runtime.msg import JointTrajectory

__all__ = ["GoalHandle", "GoalStatus", "validate_trajectory"]


class GoalStatus(enum.Enum):
    ACTIVE = "active"
    SUCCEEDED = "succeeded"
    ABORTED = "aborted"
    CANCELED = "canceled"


@dataclass
class GoalHandle:
    """A FollowJointTrajectory goal: its status and ``error_code`` / ``error_string``."""

    status: GoalStatus = GoalStatus.ACTIVE
    error_code: int = 0  # control_msgs: SUCCESSFUL 0, INVALID_GOAL -1, PATH_TOLERANCE_VIOLATED -4, GOAL_TOLERANCE_VIOLATED -5
    error_string: str = ""
    path_tolerance: dict[str, float] = field(default_factory=dict)
    goal_tolerance: dict[str, float] = field(default_factory=dict)
    goal_time_tolerance_s: float | None = None


def validate_trajectory(
    msg: JointTrajectory,
    *,
    joints: Sequence[str],
    allow_partial_joints_goal: bool,
    allow_nonzero_velocity_at_trajectory_end: bool,
    now_s: float,
) -> str:
    """Why a controller of ``joints`` rejects ``msg`` (humble ``validate_trajectory_msg``), or
    ``""``.

    ``now_s`` (the controller's clock) matters only for a stamped trajectory that passed every
    other check: whether it ends in the past.
    """
    if not msg.joint_names or not msg.points:
        return "empty joint names or points"
    unknown = [j for j in msg.joint_names if j not in joints]
    if unknown:
        return f"unknown joints {unknown}"
    if len(msg.joint_names) != len(joints) and not allow_partial_joints_goal:
        return "the trajectory must name every joint (allow_partial_joints_goal is false)"
    previous = -math.inf
    for point in msg.points:
        t = point.time_from_start.sec + point.time_from_start.nanosec * 1e-9
        if t <= previous:
            return "time_from_start must be strictly increasing"
        previous = t
        n = len(msg.joint_names)
        if len(point.positions) != n:
            return "every point needs one position per joint"
        for arr in (point.velocities, point.accelerations):
            if arr and len(arr) != n:
                return "velocities/accelerations must be empty or one per joint"
        if point.effort:
            return "effort in trajectory points is not supported (humble)"
        if not all(
            math.isfinite(v) for v in (*point.positions, *point.velocities, *point.accelerations)
        ):
            return "non-finite values"
    last = msg.points[-1]
    if (
        not allow_nonzero_velocity_at_trajectory_end
        and last.velocities
        and any(v != 0.0 for v in last.velocities)
    ):
        return "non-zero velocity at the end (allow_nonzero_velocity_at_trajectory_end is false)"
    stamp = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
    if stamp != 0.0 and stamp + t < now_s:
        return "the trajectory ends in the past"
    return ""
