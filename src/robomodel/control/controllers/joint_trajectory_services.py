"""joint_trajectory_controller on the bus: its action and query services, its state topics.

FollowJointTrajectory is offered as two services (goal, then status polling/cancel) beside
humble's ``query_state`` service; ``~/controller_state`` and the legacy ``~/state`` carry what
humble's ``publish_state`` publishes.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import partial
from typing import TYPE_CHECKING, Any

from robomodel.control.controllers.joint_trajectory_goal import GoalHandle, GoalStatus
from robomodel.errors import RobomodelError
from robomodel.runtime.msg import (
    Header,
    JointTrajectory,
    JointTrajectoryControllerState,
    JointTrajectoryPoint,
    Time,
)

if TYPE_CHECKING:
    from robomodel.control.controllers.joint_trajectory import JointTrajectoryController
    from robomodel.control.controllers.trajectory import Sample

__all__ = ["describe", "publish_state", "service_handlers"]

Handler = Callable[[dict[str, Any]], dict[str, Any]]


def service_handlers(controller: JointTrajectoryController) -> dict[str, Handler]:
    """The controller's services by name under its node: goal, goal status, query state."""
    return {
        "follow_joint_trajectory": partial(follow_joint_trajectory, controller),
        "goal_status": partial(goal_status, controller),
        "query_state": partial(query_state, controller),
    }


def follow_joint_trajectory(
    controller: JointTrajectoryController, request: dict[str, Any]
) -> dict[str, Any]:
    """``{"trajectory": {...}, "path_tolerance": {joint: tol}, "goal_tolerance": {...},
    "goal_time_tolerance": s}`` -> ``{"goal_id": n, "status": ..., "error_string": ...}``."""
    from robomodel.runtime.msg import message_from_dict

    try:
        msg = message_from_dict(JointTrajectory, request.get("trajectory"))
    except RobomodelError as exc:
        return {"error": str(exc)}
    handle = controller.send_goal(
        msg,
        path_tolerance=dict(request.get("path_tolerance") or {}),
        goal_tolerance=dict(request.get("goal_tolerance") or {}),
        goal_time_tolerance_s=request.get("goal_time_tolerance"),
    )
    goal_id = len(controller._goals) + 1
    controller._goals[goal_id] = handle
    return {"goal_id": goal_id, **describe(handle)}


def query_state(controller: JointTrajectoryController, request: dict[str, Any]) -> dict[str, Any]:
    """humble ``query_state_service`` (control_msgs/QueryTrajectoryState): the running
    trajectory sampled at ``time`` (seconds, or ``{sec, nanosec}``); ``success`` only while
    the controller is active and the time lies within the trajectory; otherwise the
    measured state is returned with ``success: false`` and the reason in ``message``."""
    if not controller._active:
        return {"success": False, "message": "Can't sample trajectory. Controller is not active."}  # fmt: skip
    stamp = request.get("time", controller._now_s)
    try:
        if isinstance(stamp, dict):
            time_s = int(stamp.get("sec", 0)) + int(stamp.get("nanosec", 0)) * 1e-9
        else:
            time_s = float(stamp)
    except (TypeError, ValueError):
        return {"success": False, "message": f"time must be seconds or {{sec, nanosec}}, got {stamp!r}"}  # fmt: skip
    reply: dict[str, Any] = {
        "success": False,
        "message": "",
        "name": list(controller.joints),
        "position": list(controller._measured("position")),
        "velocity": list(controller._measured("velocity")),
        "acceleration": [],
    }
    traj = controller.trajectory
    sample = traj.sample(time_s) if traj is not None else None
    if traj is None:
        reply["message"] = "Currently there is no valid trajectory instance."
    elif sample is None:
        reply["message"] = "Requested sample time is earlier than the current trajectory start time."  # fmt: skip
    else:
        reply["position"] = list(sample.positions)
        reply["velocity"] = list(sample.velocities)
        reply["acceleration"] = list(sample.accelerations)
        if sample.segment >= len(traj.points):
            reply["message"] = "Requested sample time is after the current trajectory end time."  # fmt: skip
        else:
            reply["success"] = True
    return reply


def goal_status(controller: JointTrajectoryController, request: dict[str, Any]) -> dict[str, Any]:
    """``{"goal_id": n, "cancel": bool}`` -> the goal's status (canceling it first if asked)."""
    handle = controller._goals.get(int(request.get("goal_id", 0)))
    if handle is None:
        return {"error": f"unknown goal id {request.get('goal_id')!r}"}
    if request.get("cancel") and handle.status is GoalStatus.ACTIVE:
        controller.cancel_goal(handle)
    return describe(handle)


def describe(handle: GoalHandle) -> dict[str, Any]:
    """A goal as a service reply: ``status``, ``error_code`` and ``error_string``."""
    return {
        "status": handle.status.value,
        "error_code": handle.error_code,
        "error_string": handle.error_string,
    }


def publish_state(
    controller: JointTrajectoryController,
    time_s: float,
    sample: Sample,
    pos: Sequence[float],
    vel: Sequence[float],
    errors: Sequence[float],
) -> None:
    """humble ``publish_state``: the sampled reference, the measured feedback, their
    difference and what was written; ``~/state`` carries the same as desired/actual."""
    reference = JointTrajectoryPoint(
        positions=list(sample.positions),
        velocities=list(sample.velocities),
        accelerations=list(sample.accelerations),
    )
    feedback = JointTrajectoryPoint(positions=list(pos), velocities=list(vel))
    error = JointTrajectoryPoint(positions=list(errors))
    if vel and len(sample.velocities) == len(vel):
        error.velocities = [d - m for d, m in zip(sample.velocities, vel, strict=True)]
    output = JointTrajectoryPoint()
    for kind, interfaces in controller._cmd.items():
        values = [ci.get() for ci in interfaces]
        if kind == "position":
            output.positions = values
        elif kind == "velocity":
            output.velocities = values
        elif kind == "acceleration":
            output.accelerations = values
        elif kind == "effort":
            output.effort = values
    header = Header(stamp=Time.from_seconds(time_s))
    controller_state, legacy = controller._state_pubs
    controller_state.publish(
        JointTrajectoryControllerState(
            header, list(controller.joints), reference, feedback, error, output
        )
    )
    legacy.publish(
        JointTrajectoryControllerState(
            header, list(controller.joints), error=error, desired=reference, actual=feedback
        )
    )
