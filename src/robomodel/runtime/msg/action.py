"""Action types as rosidl derives them from an ``.action`` file's Goal, Result and Feedback.

For ``pkg/action/Name``: the service ``Name_SendGoal`` (request ``goal_id``
(unique_identifier_msgs/UUID) and ``goal``; response ``accepted`` and ``stamp``), the service
``Name_GetResult`` (request ``goal_id``; response ``status`` (int8) and ``result``) and the
message ``Name_FeedbackMessage`` (``goal_id`` and ``feedback``), all under ``pkg/action/``,
which is where their RIHS01 hashes and DDS names (``pkg::action::dds_::Name_SendGoal_``) come
from.
"""

from __future__ import annotations

from dataclasses import field, make_dataclass
from typing import Any

from robomodel.runtime.msg._schema import Action, Message, Service
from robomodel.runtime.msg.action_msgs import UUID
from robomodel.runtime.msg.builtin_interfaces import Time

__all__ = ["make_action"]


def _message(typename: str, fields: list[tuple[str, Any, Any]]) -> type[Message]:
    """A message class with ``fields`` (name, spec, default factory)."""
    name = typename.rsplit("/", 1)[-1]
    return make_dataclass(
        name,
        [(n, Any, field(default_factory=factory)) for n, _, factory in fields],
        bases=(Message,),
        slots=True,
        namespace={"__typename__": typename, "__fields__": tuple((n, s) for n, s, _ in fields)},
    )


def _service(typename: str, request: type[Message], response: type[Message]) -> type[Service]:
    name = typename.rsplit("/", 1)[-1]
    return type(
        name, (Service,), {"__typename__": typename, "Request": request, "Response": response}
    )


def make_action(
    typename: str, goal: type[Message], result: type[Message], feedback: type[Message]
) -> type[Action]:
    """The action ``typename`` (``pkg/action/Name``) of these Goal, Result and Feedback."""
    base = typename
    send_goal = _service(
        f"{base}_SendGoal",
        _message(f"{base}_SendGoal_Request", [("goal_id", UUID, UUID), ("goal", goal, goal)]),
        _message(f"{base}_SendGoal_Response", [("accepted", "bool", bool), ("stamp", Time, Time)]),
    )
    get_result = _service(
        f"{base}_GetResult",
        _message(f"{base}_GetResult_Request", [("goal_id", UUID, UUID)]),
        _message(
            f"{base}_GetResult_Response", [("status", "int8", int), ("result", result, result)]
        ),
    )
    feedback_message = _message(
        f"{base}_FeedbackMessage", [("goal_id", UUID, UUID), ("feedback", feedback, feedback)]
    )
    name = typename.rsplit("/", 1)[-1]
    action: type[Action] = type(
        name,
        (Action,),
        {
            "__typename__": typename,
            "Goal": goal,
            "Result": result,
            "Feedback": feedback,
            "SendGoal": send_goal,
            "GetResult": get_result,
            "FeedbackMessage": feedback_message,
        },
    )
    return action
