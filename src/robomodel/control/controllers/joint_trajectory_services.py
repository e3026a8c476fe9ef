"""joint_trajectory_controller on the bus: its FollowJointTrajectory action, its query_state
service and its state topics.

``~/follow_joint_trajectory`` is a real ROS 2 action (control_msgs/action/FollowJointTrajectory,
rcl_action's services and topics: see :mod:`robomodel.runtime.action_server`): a goal that
fails validation is rejected, as Humble's ``goal_received_callback`` rejects it; a new goal
preempts the running one; feedback (desired, actual, error) is published while it runs. On a
ROS 1 graph the same goals also come through actionlib's ``~/follow_joint_trajectory``
(:mod:`robomodel.runtime.ros1_action_server`), as ROS 1's controller serves them; a refused
goal is rejected there with INVALID_GOAL and the reason (:func:`rejection`).
``~/query_state`` is control_msgs/srv/QueryTrajectoryState; ``~/controller_state`` carries
what Jazzy's ``publish_state`` publishes (no speed scaling here, so its factor is 1).

The adapter reads the controller only through
:class:`~.joint_trajectory_snapshot.TrajectoryControllerSnapshot` and acts on it only through
its public goal methods (:class:`TrajectoryGoalTarget`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.control.controllers.joint_trajectory_goal import GoalHandle, GoalStatus
from robomodel.control.controllers.joint_trajectory_snapshot import TrajectoryControllerSnapshot
from robomodel.runtime.msg import (
    Header,
    JointTrajectory,
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
    from robomodel.control.controllers.trajectory import Sample
    from robomodel.runtime.node import Node
    from robomodel.runtime.ros1_action_server import Ros1ActionServer

__all__ = [
    "TrajectoryControllerBus",
    "TrajectoryGoalTarget",
    "accept_goal",
    "query_state",
    "state_message",
]

_STATUS = {
    GoalStatus.ACTIVE: ActionStatus.STATUS_EXECUTING,
    GoalStatus.SUCCEEDED: ActionStatus.STATUS_SUCCEEDED,
    GoalStatus.ABORTED: ActionStatus.STATUS_ABORTED,
    GoalStatus.CANCELED: ActionStatus.STATUS_CANCELED,
}


class TrajectoryGoalTarget(Protocol):
    """What the adapter needs of a joint trajectory controller: its public goal interface."""

    def snapshot(self) -> TrajectoryControllerSnapshot: ...

    def validate(self, msg: JointTrajectory) -> str: ...

    def send_goal(
        self,
        msg: JointTrajectory,
        *,
        path_tolerance: dict[str, float] | None = None,
        goal_tolerance: dict[str, float] | None = None,
        goal_time_tolerance_s: float | None = None,
    ) -> GoalHandle: ...

    def cancel_goal(self, handle: GoalHandle) -> None: ...


def _tolerances(items: Sequence[Any]) -> dict[str, float]:
    return {t.name: t.position for t in items}


class _Goal:
    """A FollowJointTrajectory goal as the action server sees it (runtime.ActionGoal)."""

    def __init__(self, controller: TrajectoryGoalTarget, handle: GoalHandle) -> None:
        self.controller, self.handle = controller, handle

    def status(self) -> int:
        return _STATUS[self.handle.status]

    def result(self) -> FollowJointTrajectory_Result:
        return FollowJointTrajectory_Result(self.handle.error_code, self.handle.error_string)

    def feedback(self) -> FollowJointTrajectory_Feedback | None:
        state = self.controller.snapshot()
        traj = state.trajectory
        if traj is None or state.goal is not self.handle:
            return None
        sample = traj.sample(state.time_s)
        actual = JointTrajectoryPoint(
            positions=list(state.positions), velocities=list(state.velocities)
        )
        desired = JointTrajectoryPoint()
        error = JointTrajectoryPoint()
        if sample is not None:
            desired.positions = list(sample.positions)
            desired.velocities = list(sample.velocities)
            error.positions = [
                d - a for d, a in zip(desired.positions, actual.positions, strict=False)
            ]
        header = Header(stamp=Time.from_seconds(state.time_s))
        return FollowJointTrajectory_Feedback(header, list(state.joints), desired, actual, error)

    def cancel(self) -> bool:
        self.controller.cancel_goal(self.handle)
        return True


def refusal(controller: TrajectoryGoalTarget, goal: FollowJointTrajectory_Goal) -> str:
    """Why ``goal`` is refused (inactive controller, invalid trajectory), or ``""``."""
    if not controller.snapshot().active:
        return "the controller is not active"
    return controller.validate(goal.trajectory)


def accept_goal(controller: TrajectoryGoalTarget, goal: FollowJointTrajectory_Goal) -> _Goal | None:
    """``goal_received_callback``: reject when inactive or invalid, else start it."""
    if refusal(controller, goal):
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


def rejection(
    controller: TrajectoryGoalTarget, goal: FollowJointTrajectory_Goal
) -> FollowJointTrajectory_Result:
    """The result of a goal ``accept_goal`` refused, as ROS 1's joint_trajectory_controller
    sets it: INVALID_GOAL with the reason."""
    return FollowJointTrajectory_Result(
        FollowJointTrajectory_Result.INVALID_GOAL, refusal(controller, goal)
    )


def query_state(
    state: TrajectoryControllerSnapshot, request: QueryTrajectoryState_Request
) -> QueryTrajectoryState_Response:
    """humble ``query_state_service``: the running trajectory sampled at ``time``;
    ``success`` only while the controller is active and the time lies within the trajectory;
    otherwise the measured state is returned with ``success: false`` and the reason."""
    if not state.active:
        return QueryTrajectoryState_Response(False, "Can't sample trajectory. Controller is not active.")  # fmt: skip
    time_s = request.time.to_seconds()
    reply = QueryTrajectoryState_Response(
        name=list(state.joints), position=list(state.positions), velocity=list(state.velocities)
    )
    traj = state.trajectory
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


def state_message(
    state: TrajectoryControllerSnapshot, sample: Sample, errors: Sequence[float]
) -> JointTrajectoryControllerState:
    """Jazzy's ``publish_state``: the sampled reference, the measured feedback, their
    difference (``errors``: the position errors the controller acted on) and what was written."""
    reference = JointTrajectoryPoint(
        positions=list(sample.positions),
        velocities=list(sample.velocities),
        accelerations=list(sample.accelerations),
    )
    vel = state.velocities
    feedback = JointTrajectoryPoint(positions=list(state.positions), velocities=list(vel))
    error = JointTrajectoryPoint(positions=list(errors))
    if vel and len(sample.velocities) == len(vel):
        error.velocities = [d - m for d, m in zip(sample.velocities, vel, strict=True)]
    output = JointTrajectoryPoint()
    for kind, values in state.commands.items():
        if kind == "position":
            output.positions = list(values)
        elif kind == "velocity":
            output.velocities = list(values)
        elif kind == "acceleration":
            output.accelerations = list(values)
        elif kind == "effort":
            output.effort = list(values)
    return JointTrajectoryControllerState(
        Header(stamp=Time.from_seconds(state.time_s)),
        list(state.joints),
        reference,
        feedback,
        error,
        output,
        speed_scaling_factor=1.0,
    )


class TrajectoryControllerBus:
    """The controller's action server, ``~/query_state`` service and ``~/controller_state``
    publisher on its node, made in ``on_configure`` and destroyed in ``on_cleanup``."""

    def __init__(self, node: Node, controller: TrajectoryGoalTarget) -> None:
        from robomodel.runtime.action_server import ActionServer

        self._action = ActionServer(
            node,
            FollowJointTrajectory,
            "~/follow_joint_trajectory",
            lambda g: accept_goal(controller, g),
        )
        self._ros1_action: Ros1ActionServer | None = None
        if node.context.transport.name == "ros1":  # and actionlib's, as ROS 1's controller
            from robomodel.runtime.ros1_action_server import Ros1ActionServer

            self._ros1_action = Ros1ActionServer(
                node,
                "control_msgs/FollowJointTrajectory",
                "~/follow_joint_trajectory",
                lambda g: accept_goal(controller, g),
                rejected=lambda g: rejection(controller, g),
            )
        self._query = node.create_service(
            QueryTrajectoryState,
            "~/query_state",
            lambda r: query_state(controller.snapshot(), r),
        )
        self._state = node.create_publisher(JointTrajectoryControllerState, "~/controller_state", 1)

    def publish_state(
        self, state: TrajectoryControllerSnapshot, sample: Sample, errors: Sequence[float]
    ) -> None:
        """Publish ``~/controller_state`` (see :func:`state_message`)."""
        self._state.publish(state_message(state, sample, errors))

    def destroy(self) -> None:
        for part in (self._action, self._ros1_action, self._query, self._state):
            if part is not None:
                part.destroy()
