"""action_msgs and unique_identifier_msgs (Jazzy): goal ids, goal status and the cancel
service every ROS 2 action server offers."""

from __future__ import annotations

import uuid
from dataclasses import dataclass, field
from typing import ClassVar

from robomodel.runtime.msg._schema import Array, Message, Seq, Service
from robomodel.runtime.msg.builtin_interfaces import Time

__all__ = [
    "UUID",
    "CancelGoal",
    "CancelGoal_Request",
    "CancelGoal_Response",
    "GoalInfo",
    "GoalStatus",
    "GoalStatusArray",
]


@dataclass(slots=True)
class UUID(Message):
    """unique_identifier_msgs/UUID: 16 bytes."""

    uuid: list[int] = field(default_factory=lambda: [0] * 16)
    __typename__ = "unique_identifier_msgs/msg/UUID"
    __fields__ = (("uuid", Array("uint8", 16)),)

    @classmethod
    def random(cls) -> UUID:
        return cls(list(uuid.uuid4().bytes))


@dataclass(slots=True)
class GoalInfo(Message):
    goal_id: UUID = field(default_factory=UUID)
    stamp: Time = field(default_factory=Time)
    __typename__ = "action_msgs/msg/GoalInfo"
    __fields__ = (("goal_id", UUID), ("stamp", Time))


@dataclass(slots=True)
class GoalStatus(Message):
    STATUS_UNKNOWN: ClassVar[int] = 0
    STATUS_ACCEPTED: ClassVar[int] = 1
    STATUS_EXECUTING: ClassVar[int] = 2
    STATUS_CANCELING: ClassVar[int] = 3
    STATUS_SUCCEEDED: ClassVar[int] = 4
    STATUS_CANCELED: ClassVar[int] = 5
    STATUS_ABORTED: ClassVar[int] = 6

    goal_info: GoalInfo = field(default_factory=GoalInfo)
    status: int = 0
    __typename__ = "action_msgs/msg/GoalStatus"
    __fields__ = (("goal_info", GoalInfo), ("status", "int8"))


@dataclass(slots=True)
class GoalStatusArray(Message):
    status_list: list[GoalStatus] = field(default_factory=list)
    __typename__ = "action_msgs/msg/GoalStatusArray"
    __fields__ = (("status_list", Seq(GoalStatus)),)


@dataclass(slots=True)
class CancelGoal_Request(Message):
    """Cancel the goal of ``goal_info.goal_id``; a zero id cancels every goal accepted at or
    before ``goal_info.stamp`` (zero: all goals)."""

    goal_info: GoalInfo = field(default_factory=GoalInfo)
    __typename__ = "action_msgs/srv/CancelGoal_Request"
    __fields__ = (("goal_info", GoalInfo),)


@dataclass(slots=True)
class CancelGoal_Response(Message):
    ERROR_NONE: ClassVar[int] = 0
    ERROR_REJECTED: ClassVar[int] = 1
    ERROR_UNKNOWN_GOAL_ID: ClassVar[int] = 2
    ERROR_GOAL_TERMINATED: ClassVar[int] = 3

    return_code: int = 0
    goals_canceling: list[GoalInfo] = field(default_factory=list)
    __typename__ = "action_msgs/srv/CancelGoal_Response"
    __fields__ = (("return_code", "int8"), ("goals_canceling", Seq(GoalInfo)))


class CancelGoal(Service):
    __typename__ = "action_msgs/srv/CancelGoal"
    Request = CancelGoal_Request
    Response = CancelGoal_Response
