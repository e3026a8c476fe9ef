"""ROS 2 type identity on the wire: RIHS01 type hashes and DDS type names.

The hash is REP-2016's RIHS01 (a message's is its :class:`~.spec.MessageSpec`'s), as
``rosidl_generator_type_description`` computes it: the type's description (its name and fields, each field's type id, capacity, string capacity and
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

from typing import Any

from robomodel.runtime.msg.schema import Message, Service
from robomodel.runtime.msg.spec import rihs01_of, spec_of

__all__ = [
    "dds_type_name",
    "ros_type_name",
    "same_type",
    "type_description",
    "type_hash",
]

_NESTED = 1
_BOUNDED_SEQUENCE_OFFSET = 96

Individual = dict[str, Any]


def _type(type_id: int, nested: str = "", capacity: int = 0) -> dict[str, Any]:
    return {
        "type_id": type_id,
        "capacity": capacity,
        "string_capacity": 0,
        "nested_type_name": nested,
    }


def _service_description(srv: type[Service]) -> dict[str, Any]:
    """The service's description: request, response and event, and every type they use."""
    from robomodel.runtime.msg.types.service_msgs import ServiceEventInfo

    individuals: dict[str, Individual] = {}
    for cls in (ServiceEventInfo, srv.Request, srv.Response):
        spec = spec_of(cls)
        for part in (spec, *spec.nested):
            individuals.setdefault(part.name, part.individual_description())
    request, response = srv.Request.__typename__, srv.Response.__typename__
    event = f"{srv.__typename__}_Event"
    individuals[event] = {
        "type_name": event,
        "fields": [
            {"name": "info", "type": _type(_NESTED, ServiceEventInfo.__typename__)},
            {"name": "request", "type": _type(_BOUNDED_SEQUENCE_OFFSET + _NESTED, request, 1)},
            {"name": "response", "type": _type(_BOUNDED_SEQUENCE_OFFSET + _NESTED, response, 1)},
        ],
    }
    top = {
        "type_name": srv.__typename__,
        "fields": [
            {"name": "request_message", "type": _type(_NESTED, request)},
            {"name": "response_message", "type": _type(_NESTED, response)},
            {"name": "event_message", "type": _type(_NESTED, event)},
        ],
    }
    referenced = [individuals[name] for name in sorted(individuals)]
    return {"type_description": top, "referenced_type_descriptions": referenced}


def type_description(kind: type[Message] | type[Service]) -> dict[str, Any]:
    """The hashable part of ``TypeDescription``: the type and every type it references (a
    message's is its :class:`~.spec.MessageSpec`'s)."""
    if isinstance(kind, type) and issubclass(kind, Service):
        return _service_description(kind)
    return spec_of(kind).type_description()


_HASHES: dict[type, str] = {}


def type_hash(kind: type[Message] | type[Service]) -> str:
    """The RIHS01 hash of a message or service type, ``RIHS01_<64 hex digits>``."""
    if not (isinstance(kind, type) and issubclass(kind, Service)):
        return spec_of(kind).rihs01
    cached = _HASHES.get(kind)
    if cached is None:
        cached = _HASHES[kind] = rihs01_of(type_description(kind))
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
