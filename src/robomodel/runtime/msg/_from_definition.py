"""Message and service classes built from a definition at run time.

A definition is what rosbags' type system makes of ``.msg`` text, an IDL file or its type
stores: per type, its constants and its fields as ``(name, (node type, details))``. The class
built here is of the same kind as robomodel's own (generated) ones (a ``@dataclass(slots=True)``
:class:`Message` with ``__typename__`` and ``__fields__``), so the generated CDR and ROS 1
codecs, YAML, RIHS01 hashes and bag schemas work on it unchanged.

The classes are not entered in the registry of robomodel's own types: the resolver keeps them
(:mod:`._resolver`), so robomodel's own class always wins over one built from a definition.
"""

from __future__ import annotations

import keyword
from collections.abc import Callable, Sequence
from dataclasses import field, make_dataclass
from typing import Any

from robomodel.runtime.msg.schema import (
    PRIMITIVES,
    Array,
    Message,
    MessageTypeError,
    Seq,
    Service,
    Spec,
    default_for,
    is_byte_array,
)

__all__ = ["FieldDef", "build_message_class", "build_service_class", "spec_of"]

# rosbags' Nodetype values (rosbags.typesys.base.Nodetype), kept as ints so that this module
# does not import rosbags.
_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4
# rosidl's member of a message without fields; robomodel's classes leave it out (the codecs
# and the hash add it back).
PLACEHOLDER = "structure_needs_at_least_one_member"

FieldDef = tuple[Sequence[tuple[str, str, Any]], Sequence[tuple[str, Any]]]
Lookup = Callable[[str], type[Message]]


def spec_of(desc: Any, lookup: Lookup, *, where: str) -> Spec:
    """The robomodel field spec of a rosbags field description.

    Args:
        desc: ``(node type, details)`` as in rosbags' ``fielddefs``.
        lookup: Gives the message class of a nested type name (``pkg/msg/Name``).
        where: ``type.field``, for the error message.
    """
    kind, rest = int(desc[0]), desc[1]
    if kind == _BASE:
        name, bound = rest
        name = "byte" if name == "octet" else str(name)
        if name == "string":
            return f"string<={bound}" if bound else "string"
        if name not in PRIMITIVES:
            raise MessageTypeError(f"{where}: robomodel has no codec for the field type '{name}'")
        return name
    if kind == _NAME:
        return lookup(str(rest))
    item, size = rest
    inner = spec_of(item, lookup, where=where)
    if kind == _ARRAY:
        return Array(inner, int(size))
    return Seq(inner, int(size) or None)


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


def build_message_class(name: str, definition: FieldDef, lookup: Lookup) -> type[Message]:
    """A message class for type ``name`` (``pkg/msg/Name``) from its rosbags definition.

    Nested types are taken from ``lookup`` (robomodel's own classes where it has them, so
    that a generated ``sensor_msgs/msg/Image`` holds robomodel's own ``std_msgs/msg/Header``).
    Constants become class attributes, as rosidl's Python classes have them.
    """
    constants, fields = definition
    specs: list[tuple[str, Spec]] = []
    for field_name, desc in fields:
        if field_name == PLACEHOLDER and len(fields) == 1:
            break
        if not field_name.isidentifier() or keyword.iskeyword(field_name):
            raise MessageTypeError(f"{name}: field name '{field_name}' is not usable in Python")
        specs.append((field_name, spec_of(desc, lookup, where=f"{name}.{field_name}")))
    namespace: dict[str, Any] = {c_name: value for c_name, _, value in constants}
    namespace["__fields__"] = tuple(specs)
    namespace["__constants__"] = tuple(
        (c_name, c_type, value) for c_name, c_type, value in constants
    )
    cls: type[Message] = make_dataclass(
        name.rsplit("/", 1)[-1],
        [(n, _annotation(s), _field_default(s)) for n, s in specs],
        bases=(Message,),
        namespace=namespace,
        slots=True,
    )
    # Set after creation: Message.__init_subclass__ registers only robomodel's own classes.
    cls.__typename__ = name
    cls.__module__ = __name__
    return cls


def build_service_class(
    name: str, request: type[Message], response: type[Message]
) -> type[Service]:
    """A service class ``pkg/srv/Name`` from its request and response message classes."""
    cls: type[Service] = type(
        name.rsplit("/", 1)[-1], (Service,), {"Request": request, "Response": response}
    )
    cls.__typename__ = name
    cls.__module__ = __name__
    return cls
