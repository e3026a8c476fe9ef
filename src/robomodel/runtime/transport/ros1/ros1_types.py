"""robomodel's (ROS 2) message and service types as ROS 1 types: names, md5sums, definitions
and codecs.

The ROS 1 definitions come from rosbags' Noetic type store (std_msgs, geometry_msgs,
sensor_msgs, nav_msgs, trajectory_msgs, rosgraph_msgs, ...) and, for the packages it lacks,
from the ROS 1 files vendored under ``definitions/`` (tf2_msgs, tf, std_srvs, control_msgs,
controller_manager_msgs, gazebo_msgs; see its README). md5sums and message definitions are
those of the definitions' :class:`~robomodel.runtime.msg.spec.MessageSpec` (genmsg's
algorithm); a service's md5sum is genmsg's: the md5 of its request's md5 text followed by its
response's.

A robomodel type ``pkg/msg/Name`` is ROS 1's ``pkg/Name``; a service ``pkg/srv/Name`` ROS 1's
``pkg/Name`` with ``pkg/NameRequest`` and ``pkg/NameResponse``. Fields map by name, with the
differences between the ROS 1 and ROS 2 versions of a type written out in :mod:`.ros1_fields`.
A type with no ROS 1 counterpart (rcl_interfaces, lifecycle_msgs, action types, ...) raises
:class:`Ros1TypeError`: the transport keeps such topics and services inside the process.
"""

from __future__ import annotations

import functools
import hashlib
import re
from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg import Message, _resolver, get_message_type
from robomodel.runtime.msg._actions import ros1_wrapper_text
from robomodel.runtime.msg.definition import split_parts
from robomodel.runtime.msg.schema import Array, MessageTypeError, Seq, Service
from robomodel.runtime.msg.spec import MessageSpec, spec_from_definitions
from robomodel.runtime.msg.typehash import same_type
from robomodel.runtime.transport.ros1.ros1_codec import (
    DURATION,
    PRIMITIVES,
    TIME,
    Decoder,
    Encoder,
    Ros1CodecError,
    make_codec,
)
from robomodel.runtime.transport.ros1.ros1_fields import ALIASES, special_field

__all__ = [
    "Ros1CodecError",
    "Ros1ServiceType",
    "Ros1Type",
    "Ros1TypeError",
    "robomodel_type_for",
    "ros1_service_type",
    "ros1_type",
    "ros1_type_named",
]

DEFINITIONS = Path(__file__).parent / "definitions"


class Ros1TypeError(RobomodelError):
    """A robomodel type with no ROS 1 counterpart, or an unknown ROS 1 type name."""


@dataclass(frozen=True)
class Ros1Type:
    """A message type as ROS 1 knows it, with the codec of its robomodel class."""

    name: str  # "sensor_msgs/JointState"
    md5sum: str
    definition: str
    cls: type[Message]
    _encode: Encoder
    _decode: Decoder
    fixed_size: int | None = None  # bytes of every message on the wire, if they never vary

    def encode(self, msg: Message, seq: int = 0) -> bytes:
        return self._encode(msg, seq)

    def decode(self, data: bytes | memoryview) -> Message:
        return self._decode(bytes(data))


@dataclass(frozen=True)
class Ros1ServiceType:
    name: str  # "std_srvs/Empty"
    md5sum: str
    request: Ros1Type
    response: Ros1Type
    cls: type[Service]


_tables_generation = -1  # the package-path generation the tables below were filled in


def _fresh_tables() -> None:
    """Empty the tables of ROS 1 types when the package folders changed since they were
    filled (``_resolver.configure``: a launch's or a command's ``--package-path``): the types
    entered from the old folders go, with the md5sums, codecs and types built of them. A
    package's ``Reading`` from the folders set now is not the ``Reading`` of other folders."""
    global _tables_generation
    now = _resolver.generation()
    if now != _tables_generation:
        _stored_fielddefs.cache_clear()
        _SPECS.clear()
        _type_named.cache_clear()
        _TYPES.clear()
        _SERVICES.clear()
        _tables_generation = now


def _fielddefs() -> dict[str, Any]:
    """ROS 1's types by name (``pkg/msg/Name``): rosbags' Noetic store's, the vendored files'
    and (:func:`_add`) those of the user's packages and learned definitions."""
    _fresh_tables()
    return _stored_fielddefs()


@functools.cache
def _stored_fielddefs() -> dict[str, Any]:
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    found: dict[str, Any] = dict(get_typestore(Stores.ROS1_NOETIC).fielddefs)
    for path in sorted(DEFINITIONS.glob("*/*/*.*")):
        package, kind, stem = path.parent.parent.name, path.parent.name, path.stem
        text = path.read_text()
        if kind == "msg":
            _add(found, get_types_from_msg(text, f"{package}/msg/{stem}"))
            continue
        if kind == "srv":
            request, response = split_parts(text, "srv", where=str(path))
            _add(found, get_types_from_msg(request, f"{package}/msg/{stem}Request"))
            _add(found, get_types_from_msg(response, f"{package}/msg/{stem}Response"))
            continue
        # an action: genaction's seven messages, its three parts and their four wrappers
        for part, part_text in zip(
            ("Goal", "Result", "Feedback"),
            split_parts(text, "action", where=str(path)),
            strict=True,
        ):
            _add(found, get_types_from_msg(part_text, f"{package}/msg/{stem}{part}"))
        for suffix in ("ActionGoal", "ActionResult", "ActionFeedback", "Action"):
            name = f"{package}/msg/{stem}{suffix}"
            _add(found, get_types_from_msg(ros1_wrapper_text(name, "", suffix), name))
    return found


def _add(fielddefs: dict[str, Any], new: Mapping[str, Any]) -> None:
    """Enter the definitions of ``new`` that ``fielddefs`` lacks: a name keeps its first
    definition, as in rosbags' stores. (Not ``Typestore.register``, which writes a rosbags
    class per type, in time quadratic in a type's fields, that robomodel does not use.)"""
    for name, definition in new.items():
        fielddefs.setdefault(name, definition)


def _ros1_key(name: str) -> str:
    """``sensor_msgs/JointState`` or ``sensor_msgs/msg/JointState`` -> the store's key."""
    parts = name.strip("/").split("/")
    return f"{parts[0]}/msg/{parts[-1]}" if len(parts) in (2, 3) else name


def _robomodel_class(ros1_key: str) -> Any:
    """The robomodel class of ROS 1 type ``pkg/msg/Name`` (None if robomodel has none)."""
    if ros1_key in (TIME, DURATION):
        return get_message_type(ros1_key)
    target = ALIASES.get(ros1_key, ros1_key)
    service = re.fullmatch(r"(\w+)/msg/(\w+?)(Request|Response)", target)
    if service is not None:
        from robomodel.runtime.msg.schema import get_service_type

        try:
            kind = get_service_type(f"{service[1]}/srv/{service[2]}")
        except MessageTypeError:
            pass
        else:
            return kind.Request if service[3] == "Request" else kind.Response
    try:
        return get_message_type(target)
    except MessageTypeError:
        return None


_SPECS: dict[str, MessageSpec] = {}  # of _fielddefs()'s types: one definition per name


def _spec(key: str) -> MessageSpec:
    """The spec of ROS 1 type ``key``: its md5sum and message_definition."""
    return spec_from_definitions(key, _fielddefs(), cache=_SPECS)


def _make_type(key: str, name: str) -> Ros1Type:
    defs = _fielddefs()
    if key not in defs:
        # A type of the user's interface packages, or learned from a peer: ROS 1 gets it too.
        from robomodel.runtime.msg._resolver import definitions_outside

        _add(defs, definitions_outside(key, defs))
    if key not in defs:
        raise Ros1TypeError(f"ROS 1 has no type {name}")
    cls = _robomodel_class(key)
    if cls is None:
        raise Ros1TypeError(f"robomodel has no class for the ROS 1 type {name}")
    spec = _spec(key)
    encode, decode = make_codec(key, defs, _robomodel_class, special_field)
    fixed = _fixed_size(defs, key)
    return Ros1Type(name, spec.md5, spec.ros1_definition, cls, encode, decode, fixed)


def _fixed_size(fielddefs: Any, key: str) -> int | None:
    """The size of every message of ``key`` on ROS 1's wire (std_msgs/Float64: 8), or None when
    a string or a variable-length array makes it vary. A placeholder field is counted though it
    is not sent: the result bounds a frame, and too large a bound is harmless."""
    total = 0
    for _, desc in fielddefs[key][1]:
        size = _fixed_field_size(fielddefs, desc)
        if size is None:
            return None
        total += size
    return total


def _fixed_field_size(fielddefs: Any, desc: Any) -> int | None:
    kind, rest = int(desc[0]), desc[1]
    if kind == 1:  # a primitive
        return None if rest[0] == "string" else int(PRIMITIVES[rest[0]][1])
    if kind == 2:  # a message
        return 8 if rest in (TIME, DURATION) else _fixed_size(fielddefs, rest)
    if kind == 3:  # a fixed-length array
        item = _fixed_field_size(fielddefs, rest[0])
        return None if item is None else item * int(rest[1])
    return None


def ros1_type_named(ros1_name: str) -> Ros1Type:
    """The ROS 1 type ``ros1_name`` (``tf/tfMessage``), decoding into its robomodel class."""
    _fresh_tables()
    return _type_named(ros1_name)


@functools.cache
def _type_named(ros1_name: str) -> Ros1Type:
    key = _ros1_key(ros1_name)
    return _make_type(key, key.replace("/msg/", "/"))


def robomodel_type_for(ros1_name: str) -> type[Message]:
    cls = _robomodel_class(_ros1_key(ros1_name))
    if cls is None:
        raise Ros1TypeError(f"robomodel has no class for the ROS 1 type {ros1_name}")
    return cls  # type: ignore[no-any-return]


def _ros1_name_of(cls: type[Message]) -> str:
    package, kind, name = cls.__typename__.split("/")
    if kind != "msg":
        raise Ros1TypeError(f"{cls.__typename__} has no ROS 1 counterpart")
    for ros1_key, target in ALIASES.items():
        if target == cls.__typename__ and ros1_key.split("/")[0] != "tf":
            return ros1_key
    return f"{package}/msg/{name}"


_TYPES: dict[type[Message], Ros1Type] = {}
_SERVICES: dict[type[Service], Ros1ServiceType] = {}


def ros1_type(cls: type[Message]) -> Ros1Type:
    """The ROS 1 type of robomodel message class ``cls``; Ros1TypeError if ROS 1 has none."""
    _fresh_tables()
    found = _TYPES.get(cls)
    if found is None:
        key = _ros1_name_of(cls)
        found = _make_type(key, key.replace("/msg/", "/"))
        if not same_type(found.cls, cls):
            raise Ros1TypeError(f"{cls.__typename__} has no ROS 1 counterpart")
        _TYPES[cls] = found = _decoding_into(found, cls)
    return found


def _decoding_into(found: Ros1Type, cls: type[Message]) -> Ros1Type:
    """``found`` decoding into ``cls``, a client library's face of its robomodel class (a
    genpy-flavoured class for rospy), with nested types of the same family."""
    if found.cls is cls:
        return found
    family: dict[str, Any] = {}
    _collect(cls, family)

    def classes(ros1_key: str) -> Any:
        ours = _robomodel_class(ros1_key)
        return None if ours is None else family.get(ours.__typename__, ours)

    encode, decode = make_codec(_ros1_key(found.name), _fielddefs(), classes, special_field)
    return replace(found, cls=cls, _encode=encode, _decode=decode)


def _collect(cls: Any, family: dict[str, Any]) -> None:
    """The message classes ``cls`` holds, nested ones too, by type name."""
    if cls.__typename__ in family:
        return
    family[cls.__typename__] = cls
    for _, spec in cls.__fields__:
        while isinstance(spec, (Seq, Array)):
            spec = spec.item
        if isinstance(spec, type):
            _collect(spec, family)


def ros1_service_type(cls: type[Service]) -> Ros1ServiceType:
    """The ROS 1 service of robomodel service class ``cls``; Ros1TypeError if none."""
    _fresh_tables()
    found = _SERVICES.get(cls)
    if found is None:
        found = _SERVICES[cls] = _make_service(cls)
    return found


def _make_service(cls: type[Service]) -> Ros1ServiceType:
    package, kind, name = cls.__typename__.split("/")
    defs = _fielddefs()
    keys = [f"{package}/msg/{name}{part}" for part in ("Request", "Response")]
    if kind == "srv" and any(k not in defs for k in keys):
        # A service of the user's interface packages: ROS 1 gets its halves too.
        from robomodel.runtime.msg._resolver import definitions_outside

        for key in keys:
            _add(defs, definitions_outside(key, defs))
    if kind != "srv" or any(k not in defs for k in keys):
        raise Ros1TypeError(f"{cls.__typename__} has no ROS 1 counterpart")
    request, response = (
        _decoding_into(_make_type(k, k.replace("/msg/", "/")), half)
        for k, half in zip(keys, (cls.Request, cls.Response), strict=True)
    )
    # genmsg: the md5 of the request's md5 text followed by the response's
    text = _spec(keys[0]).md5_text + _spec(keys[1]).md5_text
    md5 = hashlib.md5(text.encode()).hexdigest()
    return Ros1ServiceType(f"{package}/{name}", md5, request, response, cls)
