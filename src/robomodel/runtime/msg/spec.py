"""A message type as plain data, with everything ROS derives from its definition: its ``.msg``
text in ROS 2's and ROS 1's dialects, the full definition with every nested type (rosbag2's
``ros2msg`` schema, ROS 1's ``message_definition``), the RIHS01 type hash and the ROS 1 md5sum.

One :class:`MessageSpec` serves the codecs' peers: the TCPROS connection header and ROS 1 bags
(md5sum, ``message_definition``), rmw_zenoh's key expressions and ``~/get_type_description``
(RIHS01, the type description and sources), rosbag2 and MCAP schemas. It is made either from a
message class (:func:`spec_of`, cached per class) or from field definitions as the parser and
rosbags' stores hold them (:func:`spec_from_definitions`: the ROS 1 side, whose types robomodel
decodes into its ROS 2 classes), so every consumer reads one value instead of walking
``__fields__`` itself.

The texts and hashes follow the generators of ROS itself:

- ``.msg`` text and full definitions: genmsg/genpy's ``_full_text`` and rosbag2's
  ``LocalMessageDefinitionSource`` (rosbags' ``generate_msgdef``): the type's constants and
  fields, then each type it uses once, depth first in order of first use, after a line of 80
  ``=`` and ``MSG: pkg/Name``. Comments and default values are not kept by classes, so neither
  text has them. ROS 1 writes ``builtin_interfaces`` Time and Duration as ``time`` and
  ``duration``, which are primitives there and have no section.
- md5sum: genmsg's ``compute_md5_text``: constants, then fields with each message type
  replaced by its own md5sum (an array of messages loses its brackets).
- RIHS01: REP-2016, as ``rosidl_generator_type_description`` (see :mod:`.typehash`).
"""

from __future__ import annotations

import functools
import hashlib
import json
import threading
import weakref
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import Enum
from typing import Any

from robomodel.runtime.msg.schema import Array, Message, MessageTypeError, Seq, Spec

__all__ = [
    "ARRAY",
    "BASE",
    "NAME",
    "PLACEHOLDER",
    "SEQUENCE",
    "Container",
    "FieldDef",
    "FieldSpec",
    "MessageSpec",
    "rihs01_of",
    "short_name",
    "spec_from_definitions",
    "spec_of",
]

# A type's field definition as the parser (:mod:`.definition`) and rosbags' stores give it:
# ``(constants, fields)``, constants as ``(name, type, value)``, fields as ``(name, (node type,
# details))``.
FieldDef = tuple[Sequence[tuple[str, str, Any]], Sequence[tuple[str, Any]]]
# rosbags' Nodetype values (rosbags.typesys.base.Nodetype), kept as ints so that importing
# this module does not import rosbags.
BASE, NAME, ARRAY, SEQUENCE = 1, 2, 3, 4
# rosidl's member of a message without fields; robomodel's classes and specs leave it out (the
# codecs and the hash add it back).
PLACEHOLDER = "structure_needs_at_least_one_member"

TIME = "builtin_interfaces/msg/Time"
DURATION = "builtin_interfaces/msg/Duration"
# ROS 1's primitives time and duration, which ROS 2 (and rosbags' stores) name as messages
ROS1_BUILTINS = {TIME: "time", DURATION: "duration"}
_SEPARATOR = "=" * 80

# type_description_interfaces/msg/FieldType; .msg ``char`` is IDL uint8 and ``byte`` its octet
# (rosidl_adapter's MSG_TYPE_TO_IDL)
_FIELD_TYPE_ID = {
    "int8": 2,
    "uint8": 3,
    "char": 3,
    "int16": 4,
    "uint16": 5,
    "int32": 6,
    "uint32": 7,
    "int64": 8,
    "uint64": 9,
    "float32": 10,
    "float64": 11,
    "bool": 15,
    "byte": 16,
    "octet": 16,
    "string": 17,
}
_NESTED_ID = 1
_BOUNDED_STRING_ID = 21


def short_name(typename: str) -> str:
    """``geometry_msgs/msg/Vector3`` -> ``geometry_msgs/Vector3``, as ``.msg`` files say it.

    The parts of an action or a service (``pkg/action/Name_Feedback``) keep their full name:
    no ``.msg`` file names them, and ``pkg/Name_Feedback`` would be read back as a message of
    another name (and RIHS01 hash)."""
    package, kind, name = typename.split("/")
    return f"{package}/{name}" if kind == "msg" else typename


class Container(Enum):
    """How a field holds its item: once, in a fixed array, or in a (bounded) sequence."""

    SCALAR = "scalar"
    ARRAY = "array"  # T[n]
    BOUNDED_SEQUENCE = "bounded_sequence"  # T[<=n]
    SEQUENCE = "sequence"  # T[]

    @property
    def type_id_offset(self) -> int:
        """What REP-2016's FieldType adds to the item's type id for this container."""
        return _OFFSETS[self]


_OFFSETS = {
    Container.SCALAR: 0,
    Container.ARRAY: 48,
    Container.BOUNDED_SEQUENCE: 96,
    Container.SEQUENCE: 144,
}


@dataclass(frozen=True, slots=True)
class FieldSpec:
    """One field: its name, its item and how the field holds it.

    ``item`` is a primitive as the definition writes it (``float64``, ``string<=8``, ``char``,
    ``byte``) or, when ``nested``, the full name of a message type (``std_msgs/msg/Header``).
    ``size`` is the array's length or the sequence's bound (0 otherwise).
    """

    name: str
    item: str
    nested: bool = False
    container: Container = Container.SCALAR
    size: int = 0

    def item_text(self, *, ros1: bool) -> str:
        """The item as ``.msg`` text names it (``pkg/Name``; ``time`` in ROS 1)."""
        if not self.nested:
            return self.item
        if ros1 and self.item in ROS1_BUILTINS:
            return ROS1_BUILTINS[self.item]
        return short_name(self.item)

    def suffix(self) -> str:
        """``""``, ``[3]``, ``[<=3]`` or ``[]``."""
        return {
            Container.SCALAR: "",
            Container.ARRAY: f"[{self.size}]",
            Container.BOUNDED_SEQUENCE: f"[<={self.size}]",
            Container.SEQUENCE: "[]",
        }[self.container]

    def text(self, *, ros1: bool) -> str:
        """The field's ``.msg`` line: ``float64[3] position``."""
        return f"{self.item_text(ros1=ros1)}{self.suffix()} {self.name}"

    def type_description(self) -> dict[str, Any]:
        """REP-2016's ``Field`` (the name and its ``FieldType``)."""
        if self.nested:
            type_id, string_capacity, nested = _NESTED_ID, 0, self.item
        else:
            base, _, bound = self.item.partition("<=")
            if base == "string" and bound:
                type_id, string_capacity, nested = _BOUNDED_STRING_ID, int(bound), ""
            else:
                type_id, string_capacity, nested = _FIELD_TYPE_ID[base], 0, ""
        capacity = 0 if self.container is Container.SEQUENCE else self.size
        return {
            "name": self.name,
            "type": {
                "type_id": self.container.type_id_offset + type_id,
                "capacity": capacity,
                "string_capacity": string_capacity,
                "nested_type_name": nested,
            },
        }


@dataclass(frozen=True)
class MessageSpec:
    """A message type's definition and what ROS derives from it.

    Attributes:
        name: ``pkg/msg/Name`` (or a service or action part, ``pkg/srv/Name_Request``).
        fields: In declaration (wire) order, rosidl's placeholder of an empty message left out.
        constants: ``(name, type, value)`` in declaration order.
        nested: Every message type the fields use, through any depth, each once: depth first
            in order of first use, the order of a full definition's ``MSG:`` sections.
    """

    name: str
    fields: tuple[FieldSpec, ...]
    constants: tuple[tuple[str, str, Any], ...] = ()
    nested: tuple[MessageSpec, ...] = ()

    # Derived values are computed once on first use (the dataclass is frozen; cached_property
    # writes to the instance's __dict__, as the spec is not changed by it).

    @functools.cached_property
    def msg(self) -> str:
        """The ``.msg`` text in ROS 2's dialect: constants, then fields, one a line."""
        return self._text(ros1=False)

    @functools.cached_property
    def ros1_msg(self) -> str:
        """The ``.msg`` text in ROS 1's dialect (``time``, ``duration``)."""
        return self._text(ros1=True)

    @functools.cached_property
    def definition(self) -> str:
        """The full definition in ROS 2's dialect: rosbag2's ``ros2msg`` schema."""
        sections = [self.msg]
        for dep in self.nested:
            sections.append(f"{_SEPARATOR}\nMSG: {short_name(dep.name)}\n{dep.msg}")
        return "".join(sections)

    @functools.cached_property
    def ros1_definition(self) -> str:
        """The full definition in ROS 1's dialect: TCPROS's and ROS 1 bags'
        ``message_definition`` (genpy's ``_full_text`` layout, without comments)."""
        sections = [self.ros1_msg]
        for dep in self.nested:
            if dep.name not in ROS1_BUILTINS:
                sections.append(f"{_SEPARATOR}\nMSG: {short_name(dep.name)}\n{dep.ros1_msg}")
        return "".join(sections)

    @functools.cached_property
    def md5_text(self) -> str:
        """genmsg's ``compute_md5_text``: what :attr:`md5` hashes (a service hashes its
        request's followed by its response's)."""
        lines = [f"{c_type} {c_name}={value}" for c_name, c_type, value in self.constants]
        for field in self.fields:
            if not field.nested or field.item in ROS1_BUILTINS:
                lines.append(field.text(ros1=True))
            else:
                lines.append(f"{self.dependency(field.item).md5} {field.name}")
        return "\n".join(lines)

    @functools.cached_property
    def md5(self) -> str:
        """The ROS 1 md5sum (genmsg), as the TCPROS header and ROS 1 bags carry it."""
        return hashlib.md5(self.md5_text.encode()).hexdigest()

    def individual_description(self) -> dict[str, Any]:
        """REP-2016's ``IndividualTypeDescription`` of this type alone (default values left
        out, rosidl's placeholder member for a type without fields)."""
        fields = self.fields or (FieldSpec(PLACEHOLDER, "uint8"),)
        return {"type_name": self.name, "fields": [f.type_description() for f in fields]}

    def type_description(self) -> dict[str, Any]:
        """The hashable part of REP-2016's ``TypeDescription``: this type and every type it
        references, sorted by name (a new dict each call)."""
        referenced = sorted((dep for dep in self.nested if dep.name != self.name), key=_name)
        return {
            "type_description": self.individual_description(),
            "referenced_type_descriptions": [dep.individual_description() for dep in referenced],
        }

    @functools.cached_property
    def rihs01(self) -> str:
        """The RIHS01 type hash, ``RIHS01_<64 hex digits>`` (REP-2016)."""
        return rihs01_of(self.type_description())

    def dependency(self, name: str) -> MessageSpec:
        """The spec of nested type ``name``."""
        found = self._by_name.get(name)
        if found is None:
            raise MessageTypeError(f"{self.name} uses no type {name}")
        return found

    @functools.cached_property
    def _by_name(self) -> dict[str, MessageSpec]:
        return {dep.name: dep for dep in self.nested}

    def _text(self, *, ros1: bool) -> str:
        lines = [f"{c_type} {c_name}={value}" for c_name, c_type, value in self.constants]
        lines += [field.text(ros1=ros1) for field in self.fields]
        return "".join(line + "\n" for line in lines)


def _name(spec: MessageSpec) -> str:
    return spec.name


def rihs01_of(description: Mapping[str, Any]) -> str:
    """RIHS01 of a type description (``{"type_description": ..., "referenced_type_descriptions":
    [...]}``): SHA-256 of its compact JSON (REP-2016)."""
    text = json.dumps(description, ensure_ascii=True, allow_nan=False)
    return "RIHS01_" + hashlib.sha256(text.encode("utf-8")).hexdigest()


def _closure(children: list[MessageSpec]) -> tuple[MessageSpec, ...]:
    """Every type of ``children`` and every type they use, each once by name, depth first in
    order of first use (genmsg's, rosbags' ``generate_msgdef``): a child's own ``nested`` is
    already that order of its subtree, and a type seen earlier brought its whole subtree."""
    seen: dict[str, MessageSpec] = {}
    for child in children:
        if child.name in seen:
            continue
        seen[child.name] = child
        for dep in child.nested:
            seen.setdefault(dep.name, dep)
    return tuple(seen.values())


# --- from a message class -------------------------------------------------------------------

_SPECS: weakref.WeakKeyDictionary[type[Message], MessageSpec] = weakref.WeakKeyDictionary()
_SPECS_LOCK = threading.Lock()


def spec_of(cls: type[Message]) -> MessageSpec:
    """The spec of message class ``cls`` (robomodel's own or one built from a definition),
    made once per class from its ``__typename__``, ``__fields__`` and ``__constants__``."""
    found = _SPECS.get(cls)
    if found is None:
        found = _from_class(cls)
        with _SPECS_LOCK:
            found = _SPECS.setdefault(cls, found)
    return found


def _from_class(cls: type[Message]) -> MessageSpec:
    fields: list[FieldSpec] = []
    children: list[MessageSpec] = []
    for name, spec in cls.__fields__:
        field, item = _class_field(name, spec)
        fields.append(field)
        if item is not None:
            children.append(spec_of(item))
    return MessageSpec(
        cls.__typename__, tuple(fields), tuple(cls.__constants__), _closure(children)
    )


def _class_field(name: str, spec: Spec) -> tuple[FieldSpec, type[Message] | None]:
    container, size, item = Container.SCALAR, 0, spec
    if isinstance(spec, Array):
        container, size, item = Container.ARRAY, spec.size, spec.item
    elif isinstance(spec, Seq):
        item = spec.item
        if spec.bound is not None:
            container, size = Container.BOUNDED_SEQUENCE, spec.bound
        else:
            container = Container.SEQUENCE
    if isinstance(item, str):
        return FieldSpec(name, item, False, container, size), None
    if isinstance(item, type) and issubclass(item, Message):
        return FieldSpec(name, item.__typename__, True, container, size), item
    raise MessageTypeError(f"{name}: not a field specification: {spec!r}")


# --- from field definitions -----------------------------------------------------------------


def spec_from_definitions(
    name: str, fielddefs: Mapping[str, FieldDef], *, cache: dict[str, MessageSpec] | None = None
) -> MessageSpec:
    """The spec of type ``name`` from field definitions as :mod:`.definition` parses them and
    rosbags' stores hold them (``{name: (constants, fields)}``), primitives kept as the
    definition writes them (ROS 1's ``byte`` stays ``byte``). ``cache`` keeps the specs made
    (of ``name`` and its nested types) across calls on the same definitions.

    Raises:
        MessageTypeError: ``name``, or a type it uses, is not in ``fielddefs``, or nests itself.
    """
    made = {} if cache is None else cache
    # post-order without recursion: a type is made after every type it uses
    stack: list[tuple[str, bool]] = [(name, False)]
    on_path: list[str] = []
    while stack:
        key, ready = stack.pop()
        if key in made:
            continue
        if key not in fielddefs:
            raise MessageTypeError(f"no definition of the type {key}")
        fields = [(n, _definition_field(n, d)) for n, d in fielddefs[key][1]]
        if not ready:
            if key in on_path:
                raise MessageTypeError(f"{key}: its definition contains itself")
            on_path.append(key)
            stack.append((key, True))
            stack += [(f.item, False) for _, f in reversed(fields) if f.nested]
            continue
        on_path.remove(key)
        if len(fields) == 1 and fields[0][0] == PLACEHOLDER:
            fields = []
        constants = tuple((str(n), str(t), v) for n, t, v in fielddefs[key][0])
        children = [made[f.item] for _, f in fields if f.nested]
        made[key] = MessageSpec(key, tuple(f for _, f in fields), constants, _closure(children))
    return made[name]


def _definition_field(name: str, desc: Any) -> FieldSpec:
    kind, rest = int(desc[0]), desc[1]
    container, size = Container.SCALAR, 0
    if kind not in (BASE, NAME):
        item_desc, count = rest
        size = int(count)
        if kind == ARRAY:
            container = Container.ARRAY
        else:
            container = Container.BOUNDED_SEQUENCE if size else Container.SEQUENCE
        kind, rest = int(item_desc[0]), item_desc[1]
    if kind == NAME:
        return FieldSpec(str(name), str(rest), True, container, size)
    base, bound = rest
    item = f"string<={bound}" if base == "string" and bound else str(base)
    return FieldSpec(str(name), item, False, container, size)
