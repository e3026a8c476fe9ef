"""joint_trajectory_controller's position errors and tolerance checks (ros2_controllers
``tolerances.hpp``, humble).

Pure functions over the controller's configured tolerances, a goal's overrides and the
current errors; :class:`~.joint_trajectory.JointTrajectoryController` acts on their verdicts.
Tolerances are in the joints' units ([rad] or [m], velocities per second); 0 disables one.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from robomodel.control.controllers.joint_position import shortest_angular_distance
from robomodel.control.controllers.joint_trajectory_goal import GoalHandle

__all__ = [
    "effective_tolerance",
    "goal_reached",
    "goal_time_s",
    "path_violation",
    "position_errors",
]


def position_errors(
    desired: Sequence[float], measured: Sequence[float], wraparound: Sequence[bool]
) -> list[float]:
    """Desired minus measured position per joint, the short way round where ``wraparound``
    (continuous joints: ``angle_wraparound``)."""
    return [
        shortest_angular_distance(measured[i], desired[i])
        if wraparound[i]
        else desired[i] - measured[i]
        for i in range(len(wraparound))
    ]


def effective_tolerance(joint: str, default: float, overrides: Mapping[str, float]) -> float:
    """A goal's tolerance for ``joint``: its override when positive, none (0) when it is -1,
    else the controller's ``default`` (FollowJointTrajectory's convention)."""
    value = overrides.get(joint, 0.0)
    if value > 0.0:
        return value
    return 0.0 if value == -1.0 else default


def path_violation(
    joints: Sequence[str],
    tolerance_by_joint: Mapping[str, float],
    overrides: Mapping[str, float],
    position_errors: Sequence[float],
) -> str | None:
    """The first joint whose position error exceeds its path tolerance, or None."""
    for i, joint in enumerate(joints):
        tol = effective_tolerance(joint, tolerance_by_joint[joint], overrides)
        if tol > 0.0 and abs(position_errors[i]) > tol:
            return joint
    return None


def goal_reached(
    joints: Sequence[str],
    tolerance_by_joint: Mapping[str, float],
    overrides: Mapping[str, float],
    position_errors: Sequence[float],
    stopped_velocity_tolerance: float,
    desired_velocities: Sequence[float],
    measured_velocities: Sequence[float],
) -> bool:
    """Every joint within its goal tolerance and, when velocities are measured, stopped.

    The goal velocity tolerance is ``stopped_velocity_tolerance`` (tolerances.hpp), on the
    velocity error, whatever the position tolerance.
    """
    ok = True
    for i, joint in enumerate(joints):
        tol = effective_tolerance(joint, tolerance_by_joint[joint], overrides)
        if tol > 0.0 and abs(position_errors[i]) > tol:
            ok = False
        if (
            measured_velocities
            and stopped_velocity_tolerance > 0.0
            and abs(desired_velocities[i] - measured_velocities[i]) > stopped_velocity_tolerance
        ):
            ok = False
    return ok


def goal_time_s(default_s: float, goal: GoalHandle | None) -> float:
    """How long after the trajectory's end the goal may still be reached [s] (0: forever):
    the goal's ``goal_time_tolerance`` when set and non-zero (negative means 0), else the
    controller's ``constraints.goal_time``."""
    if (
        goal is not None
        and goal.goal_time_tolerance_s is not None
        and goal.goal_time_tolerance_s != 0.0
    ):
        return max(goal.goal_time_tolerance_s, 0.0)
    return default_s
