"""ROS 2 type identity on the wire: RIHS01 type hashes and DDS type names.

The hash is REP-2016's RIHS01, as ``rosidl_generator_type_description`` computes it: the
type's description (its name and fields, each field's type id, capacity, string capacity and
nested type name; default values left out) and those of every type it references, sorted by
name, serialised as compact JSON and hashed with SHA-256. A message without fields gets
rosidl's ``uint8 structure_needs_at_least_one_member``. ``.msg`` files' ``char`` is IDL's
``uint8`` and ``byte`` its ``octet`` (rosidl_adapter's MSG_TYPE_TO_IDL).

A service's description (``pkg/srv/Name``) has three nested fields, ``request_message``,
``response_message`` and ``event_message``; the event (``pkg/srv/Name_Event``) is
``service_msgs/ServiceEventInfo info`` and the request and response as bounded sequences of at
most one element (rosidl_generator_type_description's ``add_service_event``).

rmw_zenoh puts the hash and the DDS type name (``std_msgs::msg::dds_::String_``) into every
key expression and liveliness token, so two types with the same name but different fields
never match.
"""

from __future__ import annotations

import hashlib
import json
from typing import Any

from robomodel.runtime.msg.schema import Array, Message, Seq, Service, Spec

__all__ = [
    "dds_type_name",
    "ros_type_name",
    "same_type",
    "type_description",
    "type_hash",
]

# type_description_interfaces/msg/FieldType
_FIELD_TYPE_ID = {
    "int8": 2,
    "uint8": 3,
    "char": 3,  # .msg char is IDL uint8
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
    "string": 17,
}
_NESTED = 1
_BOUNDED_STRING = 21
_ARRAY_OFFSET = 48
_BOUNDED_SEQUENCE_OFFSET = 96
_SEQUENCE_OFFSET = 144

Field = dict[str, Any]
Individual = dict[str, Any]


def _type(
    type_id: int, nested: str = "", capacity: int = 0, string_capacity: int = 0
) -> dict[str, Any]:
    return {
        "type_id": type_id,
        "capacity": capacity,
        "string_capacity": string_capacity,
        "nested_type_name": nested,
    }


def _field_type(spec: Spec) -> tuple[dict[str, Any], type[Message] | None]:
    """The FieldType of ``spec`` and the message class it refers to, if any."""
    offset, capacity, item = 0, 0, spec
    if isinstance(spec, Array):
        offset, capacity, item = _ARRAY_OFFSET, spec.size, spec.item
    elif isinstance(spec, Seq):
        if spec.bound is not None:
            offset, capacity, item = _BOUNDED_SEQUENCE_OFFSET, spec.bound, spec.item
        else:
            offset, item = _SEQUENCE_OFFSET, spec.item
    if isinstance(item, str):
        name, _, bound = item.partition("<=")
        if name == "string" and bound:
            return _type(offset + _BOUNDED_STRING, "", capacity, int(bound)), None
        return _type(offset + _FIELD_TYPE_ID[name], "", capacity), None
    if isinstance(item, type) and issubclass(item, Message):
        return _type(offset + _NESTED, item.__typename__, capacity), item
    raise TypeError(f"not a field specification: {spec!r}")


def _message_individuals(cls: type[Message], out: dict[str, Individual]) -> None:
    """Add the descriptions of ``cls`` and of every type it refers to, to ``out``."""
    if cls.__typename__ in out:
        return
    fields: list[Field] = []
    refs: list[type[Message]] = []
    for name, spec in cls.__fields__ or (("structure_needs_at_least_one_member", "uint8"),):
        kind, ref = _field_type(spec)
        fields.append({"name": name, "type": kind})
        if ref is not None:
            refs.append(ref)
    out[cls.__typename__] = {"type_name": cls.__typename__, "fields": fields}
    for ref in refs:
        _message_individuals(ref, out)


def _service_individuals(srv: type[Service], out: dict[str, Individual]) -> Individual:
    """Add the request, response, event and their types to ``out``; return the service's."""
    from robomodel.runtime.msg.types.service_msgs import ServiceEventInfo

    request, response = srv.Request.__typename__, srv.Response.__typename__
    for cls in (ServiceEventInfo, srv.Request, srv.Response):
        _message_individuals(cls, out)
    event = f"{srv.__typename__}_Event"
    out[event] = {
        "type_name": event,
        "fields": [
            {"name": "info", "type": _type(_NESTED, ServiceEventInfo.__typename__)},
            {"name": "request", "type": _type(_BOUNDED_SEQUENCE_OFFSET + _NESTED, request, 1)},
            {"name": "response", "type": _type(_BOUNDED_SEQUENCE_OFFSET + _NESTED, response, 1)},
        ],
    }
    return {
        "type_name": srv.__typename__,
        "fields": [
            {"name": "request_message", "type": _type(_NESTED, request)},
            {"name": "response_message", "type": _type(_NESTED, response)},
            {"name": "event_message", "type": _type(_NESTED, event)},
        ],
    }


def type_description(kind: type[Message] | type[Service]) -> dict[str, Any]:
    """The hashable part of ``TypeDescription``: the type and every type it references."""
    individuals: dict[str, Individual] = {}
    if isinstance(kind, type) and issubclass(kind, Service):
        top = _service_individuals(kind, individuals)
    else:
        _message_individuals(kind, individuals)
        top = individuals.pop(kind.__typename__)
    referenced = [individuals[name] for name in sorted(individuals) if name != top["type_name"]]
    return {"type_description": top, "referenced_type_descriptions": referenced}


_HASHES: dict[type, str] = {}


def type_hash(kind: type[Message] | type[Service]) -> str:
    """The RIHS01 hash of a message or service type, ``RIHS01_<64 hex digits>``."""
    cached = _HASHES.get(kind)
    if cached is None:
        text = json.dumps(type_description(kind), ensure_ascii=True, allow_nan=False)
        cached = _HASHES[kind] = "RIHS01_" + hashlib.sha256(text.encode("utf-8")).hexdigest()
    return cached


def dds_type_name(ros_name: str) -> str:
    """``std_msgs/msg/String`` -> ``std_msgs::msg::dds_::String_`` (rosidl_typesupport_fastrtps)."""
    package, kind, name = ros_name.split("/")
    return f"{package}::{kind}::dds_::{name}_"


def ros_type_name(dds_name: str) -> str | None:
    """``std_msgs::msg::dds_::String_`` -> ``std_msgs/msg/String``; None if not of that form."""
    parts = dds_name.split("::")
    if len(parts) != 4 or parts[2] != "dds_" or not parts[3].endswith("_") or len(parts[3]) < 2:
        return None
    if not all(parts[:2]):
        return None
    return f"{parts[0]}/{parts[1]}/{parts[3][:-1]}"


def same_type(a: type[Message] | type[Service], b: type[Message] | type[Service]) -> bool:
    """Whether two classes are one ROS type: the same name and RIHS01 hash. Classes built from
    definitions are built again when the type sources change (``--package-path``,
    ``--distro``), so a class held from before is another object for the same type."""
    return a is b or (a.__typename__ == b.__typename__ and type_hash(a) == type_hash(b))
