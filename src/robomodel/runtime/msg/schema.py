"""Message type machinery: field specifications, the message, service and action base classes
and the registry of robomodel's own types.

A message class declares ``__fields__`` as ``(name, spec)`` pairs, where a spec is a primitive
name (``"float64"``, ``"string"``, ...), another message class, ``Seq(spec)`` for an unbounded
sequence or ``Array(spec, n)`` for a fixed-size array, exactly as the ``.msg`` file does. A
service class names its ``Request`` and ``Response`` message classes, as the ``.srv`` file's two
halves.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar, TypeAlias

from robomodel.errors import RobomodelError

__all__ = [
    "BYTE_ITEMS",
    "PRIMITIVES",
    "Action",
    "Array",
    "DefinitionResolver",
    "Message",
    "MessageTypeError",
    "Seq",
    "Service",
    "Spec",
    "canonical_service_name",
    "canonical_type_name",
    "default_for",
    "get_message_type",
    "get_service_type",
    "import_package",
    "install_definition_resolver",
    "is_byte_array",
    "message_type_names",
    "register",
    "service_type_names",
]

# name -> (struct code, size in bytes, Python default)
PRIMITIVES: dict[str, tuple[str, int, Any]] = {
    "bool": ("?", 1, False),
    "byte": ("B", 1, 0),
    "char": ("B", 1, 0),
    "int8": ("b", 1, 0),
    "uint8": ("B", 1, 0),
    "int16": ("h", 2, 0),
    "uint16": ("H", 2, 0),
    "int32": ("i", 4, 0),
    "uint32": ("I", 4, 0),
    "int64": ("q", 8, 0),
    "uint64": ("Q", 8, 0),
    "float32": ("f", 4, 0.0),
    "float64": ("d", 8, 0.0),
    "string": ("", 0, ""),
}


@dataclass(frozen=True, slots=True)
class Seq:
    """A sequence ``T[]``, or ``T[<=bound]`` when ``bound`` is given (the same on the wire)."""

    item: Spec
    bound: int | None = None


@dataclass(frozen=True, slots=True)
class Array:
    """A fixed-size array ``T[n]``."""

    item: Spec
    size: int


Spec: TypeAlias = "str | type[Message] | Seq | Array"

# Items whose arrays are held as ``bytes``: one struct code "B" each on the wire. rospy gives
# ``uint8[]``/``char[]`` as bytes (genpy), rclpy ``uint8[]`` as array('B'); a list of ints
# costs ~10 us per 1,000 values to build and to turn back into bytes for an image or a cloud.
BYTE_ITEMS = frozenset({"uint8", "byte", "char"})


def is_byte_array(spec: Spec) -> bool:
    """Whether a field is a ``uint8``/``byte``/``char`` sequence or array, held as ``bytes``."""
    return isinstance(spec, (Seq, Array)) and isinstance(spec.item, str) and spec.item in BYTE_ITEMS


class MessageTypeError(RobomodelError):
    """An unknown message type name, or a value that does not fit a message type."""


class Message:
    """Base class of all message types.

    Subclasses are ``@dataclass(slots=True)`` classes whose fields mirror the ``.msg`` file,
    with ``__typename__`` (``pkg/msg/Name``) and ``__fields__`` (``(name, spec)`` pairs in
    declaration order, which is also the wire order). Defining one registers it.
    """

    __slots__ = ()
    __fields__: ClassVar[tuple[tuple[str, Spec], ...]] = ()
    __typename__: ClassVar[str] = ""
    # the definition's constants as (name, type, value): ``int8 STATUS_UNKNOWN=0``
    __constants__: ClassVar[tuple[tuple[str, str, Any], ...]] = ()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.__typename__ and "__typename__" in cls.__dict__:
            _REGISTRY[cls.__typename__] = cls

    @classmethod
    def field_names(cls) -> tuple[str, ...]:
        return tuple(name for name, _ in cls.__fields__)


_REGISTRY: dict[str, type[Message]] = {}


class Service:
    """Base class of all service types.

    Subclasses set ``__typename__`` (``pkg/srv/Name``) and their ``Request`` and ``Response``
    message classes (``pkg/srv/Name_Request``, ``pkg/srv/Name_Response``). Defining one
    registers it.
    """

    __typename__: ClassVar[str] = ""
    Request: ClassVar[type[Message]]
    Response: ClassVar[type[Message]]

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.__typename__ and "__typename__" in cls.__dict__:
            _SERVICES[cls.__typename__] = cls


_SERVICES: dict[str, type[Service]] = {}


class Action:
    """Base class of action types (``pkg/action/Name``), as rosidl derives them from an
    ``.action`` file: the Goal, Result and Feedback messages, the ``SendGoal`` and
    ``GetResult`` services and the ``FeedbackMessage`` (see :func:`msg.action.make_action`)."""

    __typename__: ClassVar[str] = ""
    # Derived classes are made at run time (make_action), hence Any for the type checker.
    Goal: ClassVar[Any]
    Result: ClassVar[Any]
    Feedback: ClassVar[Any]
    SendGoal: ClassVar[Any]
    GetResult: ClassVar[Any]
    FeedbackMessage: ClassVar[Any]


def register(cls: type[Message] | type[Service]) -> None:
    """Enter a class whose ``__typename__`` was set after it was made (the derived types of an
    action, :func:`msg.action.make_action`) in the registry of robomodel's own types."""
    if issubclass(cls, Message):
        _REGISTRY[cls.__typename__] = cls
    else:
        _SERVICES[cls.__typename__] = cls


def default_for(spec: Spec) -> Any:
    """A fresh default value for a field (a new list or message each time)."""
    if isinstance(spec, str):
        return PRIMITIVES[spec][2]
    if is_byte_array(spec):
        return bytes(spec.size if isinstance(spec, Array) else 0)
    if isinstance(spec, Seq):
        return []
    if isinstance(spec, Array):
        return [default_for(spec.item) for _ in range(spec.size)]
    return spec()


def canonical_type_name(name: str) -> str:
    """``std_msgs/Float64`` and ``std_msgs/msg/Float64`` both become ``std_msgs/msg/Float64``."""
    parts = name.strip().strip("/").split("/")
    if len(parts) == 2:
        return f"{parts[0]}/msg/{parts[1]}"
    return "/".join(parts)


def import_package(key: str) -> None:
    """Import robomodel's module of the package of type ``key`` (``pkg/kind/Name``), if it has
    one: ``robomodel.runtime.msg.types.<pkg>``, whose classes register themselves. Imported when
    a type of the package is first asked for by name (``robomodel topic pub``, a type in the
    graph), so that importing the message package stays cheap."""
    import importlib
    import importlib.util

    package = key.split("/", 1)[0]
    if not package.isidentifier():
        return
    module = f"robomodel.runtime.msg.types.{package}"
    if importlib.util.find_spec(module) is not None:
        importlib.import_module(module)


@dataclass(frozen=True, slots=True)
class DefinitionResolver:
    """Builds the class of a type robomodel has no class of its own for, from its definition
    (``message(key, name)``, ``service(key, name)``: the canonical key and what the user wrote).
    :mod:`robomodel.runtime.msg._resolver` installs it when the package is imported, so that
    this registry does not import the builder that registers into it."""

    message: Callable[[str, str], type[Message]]
    service: Callable[[str, str], type[Service]]


_RESOLVER: list[DefinitionResolver] = []


def install_definition_resolver(resolver: DefinitionResolver) -> None:
    """Make ``resolver`` the one that lookups of unknown types fall back to."""
    _RESOLVER[:] = [resolver]


def _definition_resolver() -> DefinitionResolver:
    if not _RESOLVER:
        raise MessageTypeError("no definition resolver installed (import robomodel.runtime.msg)")
    return _RESOLVER[0]


def get_message_type(name: str) -> type[Message]:
    """Look up a message class by ROS name (``pkg/msg/Name`` or ``pkg/Name``): robomodel's own
    class if it has one, else one built from the type's definition (:mod:`._resolver`)."""
    key = canonical_type_name(name)
    if key not in _REGISTRY:
        import_package(key)
    found = _REGISTRY.get(key)
    if found is not None:
        return found
    # Not one of robomodel's own: built from its definition (stores, packages, peers; see _resolver).
    return _definition_resolver().message(key, name)


def message_type_names() -> tuple[str, ...]:
    """Every message type robomodel has a class of its own for (its packages' modules are
    imported for this: a listing, not a look-up)."""
    _import_every_package()
    return tuple(sorted(_REGISTRY))


@functools.cache
def _import_every_package() -> None:
    """Import every module of ``robomodel.runtime.msg.types``, whose classes register (once:
    the folder is robomodel's own, fixed at install)."""
    import importlib
    import pkgutil

    from robomodel.runtime.msg import types

    for module in pkgutil.iter_modules(types.__path__):
        importlib.import_module(f"{types.__name__}.{module.name}")


def canonical_service_name(name: str) -> str:
    """``std_srvs/Empty`` and ``std_srvs/srv/Empty`` both become ``std_srvs/srv/Empty``."""
    parts = name.strip().strip("/").split("/")
    if len(parts) == 2:
        return f"{parts[0]}/srv/{parts[1]}"
    return "/".join(parts)


def get_service_type(name: str) -> type[Service]:
    """Look up a service class by ROS name (``pkg/srv/Name`` or ``pkg/Name``)."""
    key = canonical_service_name(name)
    if key not in _SERVICES:
        import_package(key)
    found = _SERVICES.get(key)
    if found is not None:
        return found
    return _definition_resolver().service(key, name)


def service_type_names() -> tuple[str, ...]:
    """Every service type robomodel has a class of its own for (see message_type_names)."""
    _import_every_package()
    return tuple(sorted(_SERVICES))
