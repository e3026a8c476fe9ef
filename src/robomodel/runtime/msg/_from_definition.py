"""Message and service classes built from a field definition at run time.

The definition is what :mod:`.definition` parses from ``.msg`` text (or what rosbags' type
stores hold, or a peer's type description gives). The class built here is of the same kind as
robomodel's own (generated) ones (a ``@dataclass(slots=True)`` :class:`Message` with
``__typename__`` and ``__fields__``), so the generated CDR and ROS 1 codecs, YAML, RIHS01 hashes
and bag schemas work on it unchanged.

The classes are not entered in the registry of robomodel's own types: the resolver keeps them
(:mod:`._resolver`), so robomodel's own class always wins over one built from a definition.
"""

from __future__ import annotations

from dataclasses import field, make_dataclass
from typing import Any, Protocol

from robomodel.runtime.msg._dataclass_methods import add_init_and_repr
from robomodel.runtime.msg.definition import PLACEHOLDER, FieldDef, Lookup, field_specs
from robomodel.runtime.msg.schema import (
    Array,
    Message,
    Seq,
    Service,
    Spec,
    default_for,
    is_byte_array,
)

__all__ = [
    "PLACEHOLDER",
    "FieldDef",
    "MessageFlavour",
    "build_message_class",
    "build_service_class",
    "make_message_class",
]


def _annotation(spec: Spec) -> Any:
    if is_byte_array(spec):
        return bytes
    if isinstance(spec, (Seq, Array)):
        return list[Any]
    if isinstance(spec, str):
        return type(default_for(spec.partition("<=")[0]))
    return spec


def _field_default(spec: Spec) -> Any:
    if isinstance(spec, str):
        return field(default=default_for(spec.partition("<=")[0]))
    return field(default_factory=lambda: default_for(spec))


class MessageFlavour(Protocol):
    """How a family of classes other than robomodel's own dataclasses looks to its users: the
    rosidl-generated classes of rclpy, the genpy-generated ones of rospy
    (:mod:`robomodel.clientlibs.messages`). The class is still a :class:`Message` with the same
    ``__typename__`` and ``__fields__``, so every codec takes it; its nested specs name the same
    flavour's classes. A flavoured class may define ``__from_fields__``: the codecs' decoders
    build instances through it (field values in wire order, or by name) instead of the
    class's own constructor."""

    def class_name(self, name: str) -> str:
        """The Python name of the class of type ``name`` (``pkg/kind/Name``)."""
        ...

    def class_body(
        self,
        name: str,
        specs: tuple[tuple[str, Spec], ...],
        constants: tuple[tuple[str, str, Any], ...],
    ) -> tuple[tuple[type, ...], dict[str, Any]]:
        """The bases (before :class:`Message`) and the namespace of the class."""
        ...

    def finish(self, cls: type[Message]) -> None:
        """Complete the class once made (the code generated for its fields)."""
        ...


def make_message_class(
    name: str,
    specs: tuple[tuple[str, Spec], ...],
    constants: tuple[tuple[str, str, Any], ...] = (),
    *,
    module: str = __name__,
    flavour: MessageFlavour | None = None,
    defaults: dict[str, Any] | None = None,
) -> type[Message]:
    """The message class of type ``name`` (``pkg/kind/Name``) with fields ``specs`` (``(name,
    spec)`` in wire order) and ``constants`` (``(name, type, value)``, also class attributes, as
    rosidl's Python classes have them): the one place a class is made at run time, for a
    definition (:func:`build_message_class`), for the types rosidl derives from an action
    (:func:`.action.make_action`) and for the client libraries' faces of every type
    (``flavour``: see :class:`MessageFlavour`; ``defaults``: the values a definition's default
    annotations give primitive fields, ``float64 w 1``, kept as ``__field_defaults__`` for it).
    Not registered: the caller decides (:func:`.schema.register`)."""
    namespace: dict[str, Any] = {c_name: value for c_name, _, value in constants}
    namespace["__fields__"] = specs
    namespace["__constants__"] = tuple(constants)
    cls: type[Message]
    if flavour is not None:
        namespace["__field_defaults__"] = dict(defaults or {})
        bases, body = flavour.class_body(name, specs, constants)
        cls = type(flavour.class_name(name), (*bases, Message), {**namespace, **body})
    else:
        cls = make_dataclass(
            name.rsplit("/", 1)[-1],
            [(n, _annotation(s), _field_default(s)) for n, s in specs],
            bases=(Message,),
            namespace=namespace,
            slots=True,
            init=False,  # dataclasses' own take time quadratic in the fields (_dataclass_methods)
            repr=False,
        )
        add_init_and_repr(cls)
    # Set after creation: Message.__init_subclass__ registers only robomodel's own classes.
    cls.__typename__ = name
    cls.__module__ = module
    if flavour is not None:
        flavour.finish(cls)
    return cls


def build_message_class(
    name: str, definition: FieldDef, lookup: Lookup, *, ros1: bool = False
) -> type[Message]:
    """A message class for type ``name`` (``pkg/msg/Name``) from its field definition.

    Nested types are taken from ``lookup`` (robomodel's own classes where it has them, so
    that a generated ``sensor_msgs/msg/Image`` holds robomodel's own ``std_msgs/msg/Header``).
    ``ros1``: the definition is a ROS 1 one (:func:`.definition.field_spec`).
    """
    specs = field_specs(name, definition, lookup, ros1=ros1)
    constants = tuple((str(c_name), str(c_type), value) for c_name, c_type, value in definition[0])
    return make_message_class(name, specs, constants)


def build_service_class(
    name: str, request: type[Message], response: type[Message], *, module: str = __name__
) -> type[Service]:
    """A service class ``pkg/srv/Name`` from its request and response message classes (not
    registered)."""
    cls: type[Service] = type(
        name.rsplit("/", 1)[-1], (Service,), {"Request": request, "Response": response}
    )
    cls.__typename__ = name
    cls.__module__ = module
    return cls
