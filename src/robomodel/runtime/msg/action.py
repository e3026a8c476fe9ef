"""Action types as rosidl derives them from an ``.action`` file's Goal, Result and Feedback.

For ``pkg/action/Name``: the service ``Name_SendGoal`` (request ``goal_id``
(unique_identifier_msgs/UUID) and ``goal``; response ``accepted`` and ``stamp``), the service
``Name_GetResult`` (request ``goal_id``; response ``status`` (int8) and ``result``) and the
message ``Name_FeedbackMessage`` (``goal_id`` and ``feedback``), all under ``pkg/action/``,
which is where their RIHS01 hashes and DDS names (``pkg::action::dds_::Name_SendGoal_``) come
from. Transcribed from rosidl_parser's ``Action`` (github:ros2/rosidl
rosidl_parser/rosidl_parser/definition.py, ``Action.__init__`` and the ``ACTION_*_SUFFIX``
constants, commit 95739d5).

robomodel's own actions (control_msgs_actions) register their classes by name; actions built
from an ``.action`` file (:mod:`._resolver`) are made with ``register=False``, so a package
path's definitions are forgotten when the package path changes.
"""

from __future__ import annotations

from dataclasses import field, make_dataclass
from typing import Any

from robomodel.runtime.msg import schema
from robomodel.runtime.msg.schema import Action, Message, Service
from robomodel.runtime.msg.types.builtin_interfaces import Time
from robomodel.runtime.msg.types.unique_identifier_msgs import UUID

__all__ = ["make_action"]


def _named(cls: Any, typename: str, register: bool) -> Any:
    """``cls`` named ``typename``; entered in the registry of robomodel's own types if
    ``register`` (the base classes' ``__init_subclass__`` registers a class that has its
    ``__typename__`` when it is created, so an unregistered one gets it afterwards)."""
    cls.__typename__ = typename
    if register:
        schema.register(cls)
    return cls


def _message(typename: str, fields: list[tuple[str, Any, Any]], register: bool) -> type[Message]:
    """A message class with ``fields`` (name, spec, default factory)."""
    name = typename.rsplit("/", 1)[-1]
    cls = make_dataclass(
        name,
        [(n, Any, field(default_factory=factory)) for n, _, factory in fields],
        bases=(Message,),
        slots=True,
        namespace={"__fields__": tuple((n, s) for n, s, _ in fields)},
    )
    return _named(cls, typename, register)  # type: ignore[no-any-return]


def _service(
    typename: str, request: type[Message], response: type[Message], register: bool
) -> type[Service]:
    name = typename.rsplit("/", 1)[-1]
    cls = type(name, (Service,), {"Request": request, "Response": response})
    return _named(cls, typename, register)  # type: ignore[no-any-return]


def make_action(
    typename: str,
    goal: type[Message],
    result: type[Message],
    feedback: type[Message],
    *,
    register: bool = True,
) -> type[Action]:
    """The action ``typename`` (``pkg/action/Name``) of these Goal, Result and Feedback; its
    derived types are entered in the registry of robomodel's own types if ``register``."""
    base, r = typename, register
    send_goal = _service(
        f"{base}_SendGoal",
        _message(f"{base}_SendGoal_Request", [("goal_id", UUID, UUID), ("goal", goal, goal)], r),
        _message(
            f"{base}_SendGoal_Response", [("accepted", "bool", bool), ("stamp", Time, Time)], r
        ),
        r,
    )
    get_result = _service(
        f"{base}_GetResult",
        _message(f"{base}_GetResult_Request", [("goal_id", UUID, UUID)], r),
        _message(
            f"{base}_GetResult_Response", [("status", "int8", int), ("result", result, result)], r
        ),
        r,
    )
    feedback_message = _message(
        f"{base}_FeedbackMessage", [("goal_id", UUID, UUID), ("feedback", feedback, feedback)], r
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
    if register:
        _ACTIONS[typename] = action
    return action


# Hand-written actions by name (pkg/action/Name).
_ACTIONS: dict[str, type[Action]] = {}
