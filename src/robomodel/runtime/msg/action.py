"""Action types as rosidl derives them from an ``.action`` file's Goal, Result and Feedback.

For ``pkg/action/Name``: the service ``Name_SendGoal`` (request ``goal_id``
(unique_identifier_msgs/UUID) and ``goal``; response ``accepted`` and ``stamp``), the service
``Name_GetResult`` (request ``goal_id``; response ``status`` (int8) and ``result``) and the
message ``Name_FeedbackMessage`` (``goal_id`` and ``feedback``), all under ``pkg/action/``,
which is where their RIHS01 hashes and DDS names (``pkg::action::dds_::Name_SendGoal_``) come
from. Transcribed from rosidl_parser's ``Action`` (github:ros2/rosidl
rosidl_parser/rosidl_parser/definition.py, ``Action.__init__`` and the ``ACTION_*_SUFFIX``
constants, commit 95739d5).

robomodel's own actions (:mod:`.types.control_msgs`) register their classes by name; actions built
from an ``.action`` file (:mod:`._resolver`) are made with ``register=False``, so a package
path's definitions are forgotten when the package path changes.
"""

from __future__ import annotations

from robomodel.runtime.msg import schema
from robomodel.runtime.msg._from_definition import build_service_class, make_message_class
from robomodel.runtime.msg.schema import Action, Message, Service, Spec
from robomodel.runtime.msg.types.builtin_interfaces import Time
from robomodel.runtime.msg.types.unique_identifier_msgs import UUID

__all__ = ["make_action"]


def _message(typename: str, fields: tuple[tuple[str, Spec], ...], register: bool) -> type[Message]:
    cls = make_message_class(typename, fields, module=__name__)
    if register:
        schema.register(cls)
    return cls


def _service(
    typename: str, request: type[Message], response: type[Message], register: bool
) -> type[Service]:
    cls = build_service_class(typename, request, response, module=__name__)
    if register:
        schema.register(cls)
    return cls


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
        _message(f"{base}_SendGoal_Request", (("goal_id", UUID), ("goal", goal)), r),
        _message(f"{base}_SendGoal_Response", (("accepted", "bool"), ("stamp", Time)), r),
        r,
    )
    get_result = _service(
        f"{base}_GetResult",
        _message(f"{base}_GetResult_Request", (("goal_id", UUID),), r),
        _message(f"{base}_GetResult_Response", (("status", "int8"), ("result", result)), r),
        r,
    )
    feedback_message = _message(
        f"{base}_FeedbackMessage", (("goal_id", UUID), ("feedback", feedback)), r
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
