"""joint_trajectory_controller on the bus: its FollowJointTrajectory action, its query_state
service and its state topics.

``~/follow_joint_trajectory`` is a real ROS 2 action (control_msgs/action/FollowJointTrajectory,
rcl_action's services and topics: see :mod:`robomodel.runtime.action_server`): a goal that
fails validation is rejected, as Humble's ``goal_received_callback`` rejects it; a new goal
preempts the running one; feedback (desired, actual, error) is published while it runs.
``~/query_state`` is control_msgs/srv/QueryTrajectoryState; ``~/controller_state`` carries
what Jazzy's ``publish_state`` publishes (no speed scaling here, so its factor is 1).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from robomodel.control.controllers.joint_trajectory_goal import GoalHandle, GoalStatus
from robomodel.runtime.msg import (
    Header,
    JointTrajectoryControllerState,
    JointTrajectoryPoint,
    Time,
)
from robomodel.runtime.msg.types.action_msgs import GoalStatus as ActionStatus
from robomodel.runtime.msg.types.control_msgs import (
    FollowJointTrajectory,
    FollowJointTrajectory_Feedback,
    FollowJointTrajectory_Goal,
    FollowJointTrajectory_Result,
    QueryTrajectoryState,
    QueryTrajectoryState_Request,
    QueryTrajectoryState_Response,
)

if TYPE_CHECKING:
    from robomodel.control.controllers.joint_trajectory import JointTrajectoryController
    from robomodel.control.controllers.trajectory import Sample

__all__ = ["accept_goal", "offer", "publish_state", "query_state"]

_STATUS = {
    GoalStatus.ACTIVE: ActionStatus.STATUS_EXECUTING,
    GoalStatus.SUCCEEDED: ActionStatus.STATUS_SUCCEEDED,
    GoalStatus.ABORTED: ActionStatus.STATUS_ABORTED,
    GoalStatus.CANCELED: ActionStatus.STATUS_CANCELED,
}


def _tolerances(items: Sequence[Any]) -> dict[str, float]:
    return {t.name: t.position for t in items}


class _Goal:
    """A FollowJointTrajectory goal as the action server sees it (runtime.ActionGoal)."""

    def __init__(self, controller: JointTrajectoryController, handle: GoalHandle) -> None:
        self.controller, self.handle = controller, handle

    def status(self) -> int:
        return _STATUS[self.handle.status]

    def result(self) -> FollowJointTrajectory_Result:
        return FollowJointTrajectory_Result(self.handle.error_code, self.handle.error_string)

    def feedback(self) -> FollowJointTrajectory_Feedback | None:
        controller = self.controller
        traj = controller.trajectory
        if traj is None or controller.goal is not self.handle:
            return None
        sample = traj.sample(controller._now_s)
        actual = JointTrajectoryPoint(
            positions=list(controller._measured("position")),
            velocities=list(controller._measured("velocity")),
        )
        desired = JointTrajectoryPoint()
        error = JointTrajectoryPoint()
        if sample is not None:
            desired.positions = list(sample.positions)
            desired.velocities = list(sample.velocities)
            error.positions = [
                d - a for d, a in zip(desired.positions, actual.positions, strict=False)
            ]
        header = Header(stamp=Time.from_seconds(controller._now_s))
        return FollowJointTrajectory_Feedback(
            header, list(controller.joints), desired, actual, error
        )

    def cancel(self) -> bool:
        self.controller.cancel_goal(self.handle)
        return True


def accept_goal(
    controller: JointTrajectoryController, goal: FollowJointTrajectory_Goal
) -> _Goal | None:
    """``goal_received_callback``: reject when inactive or invalid, else start it."""
    if not controller._active or controller.validate(goal.trajectory):
        return None
    tolerance = goal.goal_time_tolerance
    handle = controller.send_goal(
        goal.trajectory,
        path_tolerance=_tolerances(goal.path_tolerance),
        goal_tolerance=_tolerances(goal.goal_tolerance),
        goal_time_tolerance_s=(
            tolerance.to_seconds() if tolerance.sec or tolerance.nanosec else None
        ),
    )
    return _Goal(controller, handle)


def offer(controller: JointTrajectoryController) -> list[Any]:
    """The action server and the query_state service on the controller's node."""
    from robomodel.runtime.action_server import ActionServer

    node = controller.node
    assert node is not None
    server = ActionServer(
        node,
        FollowJointTrajectory,
        "~/follow_joint_trajectory",
        lambda g: accept_goal(controller, g),
    )
    query = node.create_service(
        QueryTrajectoryState, "~/query_state", lambda r: query_state(controller, r)
    )
    return [server, query]


def query_state(
    controller: JointTrajectoryController, request: QueryTrajectoryState_Request
) -> QueryTrajectoryState_Response:
    """humble ``query_state_service``: the running trajectory sampled at ``time``;
    ``success`` only while the controller is active and the time lies within the trajectory;
    otherwise the measured state is returned with ``success: false`` and the reason."""
    if not controller._active:
        return QueryTrajectoryState_Response(False, "Can't sample trajectory. Controller is not active.")  # fmt: skip
    time_s = request.time.to_seconds()
    reply = QueryTrajectoryState_Response(
        name=list(controller.joints),
        position=list(controller._measured("position")),
        velocity=list(controller._measured("velocity")),
    )
    traj = controller.trajectory
    sample = traj.sample(time_s) if traj is not None else None
    if traj is None:
        reply.message = "Currently there is no valid trajectory instance."
    elif sample is None:
        reply.message = "Requested sample time is earlier than the current trajectory start time."
    else:
        reply.position = list(sample.positions)
        reply.velocity = list(sample.velocities)
        reply.acceleration = list(sample.accelerations)
        if sample.segment >= len(traj.points):
            reply.message = "Requested sample time is after the current trajectory end time."
        else:
            reply.success = True
    return reply


def publish_state(
    controller: JointTrajectoryController,
    time_s: float,
    sample: Sample,
    pos: Sequence[float],
    vel: Sequence[float],
    errors: Sequence[float],
) -> None:
    """Jazzy's ``publish_state``: the sampled reference, the measured feedback, their
    difference and what was written."""
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
    controller._state_pub.publish(
        JointTrajectoryControllerState(
            header,
            list(controller.joints),
            reference,
            feedback,
            error,
            output,
            speed_scaling_factor=1.0,
        )
    )
