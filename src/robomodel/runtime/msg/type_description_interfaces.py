"""type_description_interfaces (Jazzy, REP-2011): type descriptions and GetTypeDescription.

Fields as in ros2/rcl_interfaces ``type_description_interfaces/msg/*.msg`` and
``srv/GetTypeDescription.srv`` (branch jazzy). FieldType's ~90 constants are not repeated: the
ids robomodel writes are in :mod:`robomodel.runtime.msg.typehash`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Message, Seq, Service

__all__ = [
    "Field",
    "FieldType",
    "GetTypeDescription",
    "GetTypeDescription_Request",
    "GetTypeDescription_Response",
    "IndividualTypeDescription",
    "KeyValue",
    "TypeDescription",
    "TypeSource",
]


@dataclass(slots=True)
class FieldType(Message):
    type_id: int = 0
    capacity: int = 0
    string_capacity: int = 0
    nested_type_name: str = ""
    __typename__ = "type_description_interfaces/msg/FieldType"
    __fields__ = (
        ("type_id", "uint8"),
        ("capacity", "uint64"),
        ("string_capacity", "uint64"),
        ("nested_type_name", "string<=255"),
    )


@dataclass(slots=True)
class Field(Message):
    name: str = ""
    type: FieldType = field(default_factory=FieldType)
    default_value: str = ""
    __typename__ = "type_description_interfaces/msg/Field"
    __fields__ = (("name", "string"), ("type", FieldType), ("default_value", "string"))


@dataclass(slots=True)
class IndividualTypeDescription(Message):
    type_name: str = ""
    fields: list[Field] = field(default_factory=list)
    __typename__ = "type_description_interfaces/msg/IndividualTypeDescription"
    __fields__ = (("type_name", "string<=255"), ("fields", Seq(Field)))


@dataclass(slots=True)
class TypeDescription(Message):
    type_description: IndividualTypeDescription = field(default_factory=IndividualTypeDescription)
    referenced_type_descriptions: list[IndividualTypeDescription] = field(default_factory=list)
    __typename__ = "type_description_interfaces/msg/TypeDescription"
    __fields__ = (
        ("type_description", IndividualTypeDescription),
        ("referenced_type_descriptions", Seq(IndividualTypeDescription)),
    )


@dataclass(slots=True)
class TypeSource(Message):
    type_name: str = ""
    encoding: str = ""
    raw_file_contents: str = ""
    __typename__ = "type_description_interfaces/msg/TypeSource"
    __fields__ = (("type_name", "string"), ("encoding", "string"), ("raw_file_contents", "string"))


@dataclass(slots=True)
class KeyValue(Message):
    key: str = ""
    value: str = ""
    __typename__ = "type_description_interfaces/msg/KeyValue"
    __fields__ = (("key", "string"), ("value", "string"))


@dataclass(slots=True)
class GetTypeDescription_Request(Message):
    type_name: str = ""
    type_hash: str = ""
    include_type_sources: bool = True
    __typename__ = "type_description_interfaces/srv/GetTypeDescription_Request"
    __fields__ = (
        ("type_name", "string"),
        ("type_hash", "string"),
        ("include_type_sources", "bool"),
    )


@dataclass(slots=True)
class GetTypeDescription_Response(Message):
    successful: bool = False
    failure_reason: str = ""
    type_description: TypeDescription = field(default_factory=TypeDescription)
    type_sources: list[TypeSource] = field(default_factory=list)
    extra_information: list[KeyValue] = field(default_factory=list)
    __typename__ = "type_description_interfaces/srv/GetTypeDescription_Response"
    __fields__ = (
        ("successful", "bool"),
        ("failure_reason", "string"),
        ("type_description", TypeDescription),
        ("type_sources", Seq(TypeSource)),
        ("extra_information", Seq(KeyValue)),
    )


class GetTypeDescription(Service):
    """``~/get_type_description``, which every rcl node offers (rcl ``node.c``)."""

    __typename__ = "type_description_interfaces/srv/GetTypeDescription"
    Request = GetTypeDescription_Request
    Response = GetTypeDescription_Response
