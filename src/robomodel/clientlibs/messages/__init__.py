"""Message, service and action classes as the client libraries' generators make them, for every
type robomodel knows: the **rosidl** flavour (rclpy's classes, rosidl_generator_py's shape) and
the **genpy** flavour (rospy's classes, genpy's shape).

Each flavoured class is made by robomodel's one class factory
(:func:`robomodel.runtime.msg._from_definition.make_message_class` with a ``flavour``) from the
fields of robomodel's class of the type, once per (flavour, type): a :class:`Message` with the
same ``__typename__`` and ``__fields__``, whose nested fields are the same flavour's classes.
robomodel's CDR and ROS 1 codecs, YAML and type hashes take it as it is, and decode into it.

Which flavour a process gets (:func:`flavour`): ``ROBOMODEL_MESSAGE_FLAVOUR`` (``rosidl`` or
``genpy``, which ``robomodel run`` and ``launch`` set); else genpy once ``rospy`` is imported,
rosidl once ``rclpy`` is; else the one whose library the ``__main__`` script imports; else rosidl.

genpy's own names for rospy's ``genpy`` module: :class:`GenpyMessage` (genpy's ``Message``, the
base of every genpy-flavoured class), its exceptions and :func:`strify_message`; genpy's
``Time`` and ``Duration`` are the genpy flavour's classes of ``builtin_interfaces/msg/Time`` and
``Duration`` (``message_class("builtin_interfaces/msg/Time", "genpy")``).
"""

from __future__ import annotations

import os
import re
import sys
import threading
from collections.abc import Callable
from typing import Any, Literal, TypeVar, cast

from robomodel.clientlibs.messages._genpy import (
    DeserializationError,
    GenpyMessage,
    MessageException,
    SerializationError,
    strify_message,
)
from robomodel.errors import RobomodelError
from robomodel.runtime.msg.schema import Action, Array, Message, Seq, Service, Spec

__all__ = [
    "FLAVOURS",
    "DeserializationError",
    "Flavour",
    "FlavourError",
    "GenpyMessage",
    "MessageException",
    "SerializationError",
    "action_class",
    "flavour",
    "flavoured",
    "flavoured_action",
    "flavoured_service",
    "message_class",
    "service_class",
    "strify_message",
]

Flavour = Literal["rosidl", "genpy"]
FLAVOURS: tuple[Flavour, ...] = ("rosidl", "genpy")
ENV = "ROBOMODEL_MESSAGE_FLAVOUR"

_lock = threading.RLock()
_faces: dict[tuple[str, type[Any]], type[Any]] = {}
_T = TypeVar("_T", bound=type)


class FlavourError(RobomodelError):
    """An unknown message flavour (``ROBOMODEL_MESSAGE_FLAVOUR`` or an argument)."""


def flavour() -> Flavour:
    """The flavour of the message classes this process gets (see the module's docstring)."""
    chosen = os.environ.get(ENV, "").strip().lower()
    if chosen:
        return _checked(chosen, f"{ENV}={chosen!r}")
    if "rospy" in sys.modules or "robomodel.clientlibs.rospy" in sys.modules:
        return "genpy"
    if "rclpy" in sys.modules or "robomodel.clientlibs.rclpy" in sys.modules:
        return "rosidl"
    return _main_script_flavour() or "rosidl"


def _checked(name: str, where: str) -> Flavour:
    if name not in FLAVOURS:
        raise FlavourError(f"unknown message flavour {where}; flavours are: {', '.join(FLAVOURS)}")
    return name


_IMPORT = re.compile(r"^\s*(?:import|from)\s+(rospy|rclpy)\b", re.MULTILINE)


def _main_script_flavour() -> Flavour | None:
    """The flavour of the client library the ``__main__`` script imports first, if any."""
    path = getattr(sys.modules.get("__main__"), "__file__", None)
    if not path:
        return None
    try:
        with open(path, encoding="utf-8", errors="replace") as file:
            found = _IMPORT.search(file.read())
    except OSError:
        return None
    if found is None:
        return None
    return "genpy" if found[1] == "rospy" else "rosidl"


def _flavour_object(name: str) -> Any:
    if name == "rosidl":
        from robomodel.clientlibs.messages._rosidl import FLAVOUR

        return FLAVOUR
    from robomodel.clientlibs.messages._genpy import FLAVOUR as GENPY
    from robomodel.clientlibs.messages._genpy_time import DURATION_FACE

    if not DURATION_FACE:
        DURATION_FACE.append(lambda: message_class("builtin_interfaces/msg/Duration", "genpy"))
    return GENPY


def _module_of(typename: str) -> str:
    package, kind, _ = typename.split("/")
    return f"{package}.{kind}"


def flavoured(cls: type[Message], name: str | None = None) -> type[Message]:
    """The ``name`` flavour's class (default: :func:`flavour`) of the type of ``cls`` (any
    :class:`Message` class of it: robomodel's own, or another flavour's)."""
    chosen = _checked(name, repr(name)) if name is not None else flavour()
    base = _robomodel_class(cls)
    return _face((chosen, base), lambda: _make_message(base, chosen))


def _make_message(base: type[Message], chosen: Flavour) -> type[Message]:
    from robomodel.runtime.msg._from_definition import make_message_class

    specs = tuple((n, _flavoured_spec(s, chosen)) for n, s in base.__fields__)
    found = make_message_class(
        base.__typename__,
        specs,
        base.__constants__,
        module=_module_of(base.__typename__),
        flavour=_flavour_object(chosen),
        defaults=_primitive_defaults(base),
    )
    found.__robomodel_class__ = base  # type: ignore[attr-defined]
    return found


def _face(key: tuple[Flavour, type], make: Callable[[], _T]) -> _T:
    """The class cached under ``key``, made by ``make`` once (under the lock: nested types
    are made while their parent is)."""
    found = _faces.get(key)
    if found is None:
        with _lock:
            found = _faces.get(key)
            if found is None:
                found = _faces[key] = make()
    return cast("_T", found)


def _primitive_defaults(base: type[Message]) -> dict[str, Any]:
    """The primitive fields whose default is not their type's zero: a definition's default
    annotation (``geometry_msgs/Quaternion``'s ``float64 w 1``), as robomodel's class has it."""
    from robomodel.runtime.msg.schema import default_for

    sample = base()
    return {
        name: getattr(sample, name)
        for name, spec in base.__fields__
        if isinstance(spec, str) and getattr(sample, name) != default_for(spec.partition("<=")[0])
    }


def _robomodel_class(cls: type[Message]) -> type[Message]:
    return cls.__dict__.get("__robomodel_class__", cls)  # type: ignore[no-any-return]


def _flavoured_spec(spec: Spec, name: Flavour) -> Spec:
    if isinstance(spec, Seq):
        return Seq(_flavoured_spec(spec.item, name), spec.bound)
    if isinstance(spec, Array):
        return Array(_flavoured_spec(spec.item, name), spec.size)
    if isinstance(spec, str):
        return spec
    return flavoured(spec, name)


def message_class(typename: str, name: str | None = None) -> type[Message]:
    """The flavoured class of message type ``typename`` (``pkg/msg/Name`` or ``pkg/Name``)."""
    from robomodel.runtime.msg.schema import get_message_type

    return flavoured(get_message_type(typename), name)


def flavoured_service(cls: type[Service], name: str | None = None) -> type[Service]:
    """The flavoured class of the service type of ``cls``: rosidl's has ``Request``,
    ``Response`` and ``Event``; genpy's ``_request_class`` and ``_response_class`` too, and
    halves named ``NameRequest``/``NameResponse``."""
    chosen = _checked(name, repr(name)) if name is not None else flavour()
    base = cls.__dict__.get("__robomodel_class__", cls)
    return _face((chosen, base), lambda: _make_service(base, chosen))


def _make_service(base: type[Service], name: Flavour) -> type[Service]:
    from robomodel.runtime.msg._from_definition import build_service_class

    request, response = flavoured(base.Request, name), flavoured(base.Response, name)
    package, _, short = base.__typename__.split("/")
    service = build_service_class(base.__typename__, request, response, module=f"{package}.srv")
    service.__robomodel_class__ = base  # type: ignore[attr-defined]
    if name == "genpy":
        service._type = f"{package}/{short}"  # type: ignore[attr-defined]
        service._request_class = request  # type: ignore[attr-defined]
        service._response_class = response  # type: ignore[attr-defined]
        from robomodel.clientlibs.messages._genpy import _Ros1Attribute

        service._md5sum = _Ros1Attribute("md5sum")  # type: ignore[attr-defined]
        for half in (request, response):
            half._service_class = service  # type: ignore[attr-defined]
    else:
        service.Event = _service_event(base, request, response)  # type: ignore[attr-defined]
        setattr(service, "__init__", _no_instances("Service"))  # noqa: B010
    return service


def _service_event(base: type[Service], request: type[Message], response: type[Message]) -> Any:
    """rosidl's ``Name_Event`` (service introspection): info, then at most one request and one
    response; None where ``service_msgs`` is unknown."""
    from robomodel.runtime.msg._from_definition import make_message_class
    from robomodel.runtime.msg.schema import MessageTypeError, get_message_type

    try:
        info = flavoured(get_message_type("service_msgs/msg/ServiceEventInfo"), "rosidl")
    except MessageTypeError:
        return None
    package = base.__typename__.split("/", 1)[0]
    specs: tuple[tuple[str, Spec], ...] = (
        ("info", info),
        ("request", Seq(request, 1)),
        ("response", Seq(response, 1)),
    )
    return make_message_class(
        f"{base.__typename__}_Event",
        specs,
        module=f"{package}.srv",
        flavour=_flavour_object("rosidl"),
    )


def _no_instances(kind: str) -> Any:
    def __init__(self: Any) -> None:
        raise NotImplementedError(f"{kind} classes can not be instantiated")

    return __init__


def service_class(typename: str, name: str | None = None) -> type[Service]:
    """The flavoured class of service type ``typename`` (``pkg/srv/Name``)."""
    from robomodel.runtime.msg.schema import get_service_type

    return flavoured_service(get_service_type(typename), name)


def flavoured_action(cls: type[Action], name: str | None = None) -> type[Action]:
    """The flavoured class of the action type of ``cls``: ``Goal``, ``Result``, ``Feedback``,
    robomodel's ``SendGoal``/``GetResult``/``FeedbackMessage`` and rosidl's ``Impl``
    (``SendGoalService``, ``GetResultService``, ``FeedbackMessage``, ``CancelGoalService``,
    ``GoalStatusMessage``), all of the flavour."""
    chosen = _checked(name, repr(name)) if name is not None else flavour()
    base = cls.__dict__.get("__robomodel_class__", cls)
    return _face((chosen, base), lambda: _make_action(base, chosen))


def _make_action(base: type[Action], name: Flavour) -> type[Action]:
    from robomodel.runtime.msg.schema import get_message_type, get_service_type

    parts: dict[str, Any] = {
        "__typename__": base.__typename__,
        "__module__": _module_of(base.__typename__),
        "__robomodel_class__": base,
        "Goal": flavoured(base.Goal, name),
        "Result": flavoured(base.Result, name),
        "Feedback": flavoured(base.Feedback, name),
        "SendGoal": flavoured_service(base.SendGoal, name),
        "GetResult": flavoured_service(base.GetResult, name),
        "FeedbackMessage": flavoured(base.FeedbackMessage, name),
    }
    impl = type(
        "Impl",
        (),
        {
            "SendGoalService": parts["SendGoal"],
            "GetResultService": parts["GetResult"],
            "FeedbackMessage": parts["FeedbackMessage"],
            "CancelGoalService": flavoured_service(
                get_service_type("action_msgs/srv/CancelGoal"), name
            ),
            "GoalStatusMessage": flavoured(
                get_message_type("action_msgs/msg/GoalStatusArray"), name
            ),
        },
    )
    parts["Impl"] = impl
    parts["__init__"] = _no_instances("Action")
    return type(base.__typename__.rsplit("/", 1)[-1], (Action,), parts)


def action_class(typename: str, name: str | None = None) -> type[Action]:
    """The flavoured class of action type ``typename`` (``pkg/action/Name``)."""
    from robomodel.runtime.msg._resolver import resolve_action

    return flavoured_action(resolve_action(typename, typename), name)
