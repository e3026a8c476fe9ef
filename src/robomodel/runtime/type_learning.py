"""Learning a topic's type that robomodel lacks, from the peers that publish it.

On ROS 1 a publisher sends its type's full definition in its connection header
(:mod:`robomodel.runtime.transport.ros1.definition_probe`). On ROS 2 every rcl node answers
``~/get_type_description`` (REP-2011) for the types it uses, by the RIHS01 hash that its
publisher's liveliness token carries: robomodel asks the node, checks that the description
hashes to that value (REP-2011's hash of the type and its referenced types, default values left
out), and builds the type from its fields, so ``topic echo`` and ``bag record`` decode a custom
message type of a real ROS 2 package.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING, Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg.schema import MessageTypeError

if TYPE_CHECKING:
    from robomodel.runtime.context import Context
    from robomodel.runtime.msg._from_definition import FieldDef
    from robomodel.runtime.msg.types import type_description_interfaces as tdi
    from robomodel.runtime.transport.base import Endpoint

__all__ = ["fielddefs_of", "learn_topic_type"]

log = logging.getLogger("robomodel.runtime")

# type_description_interfaces/msg/FieldType: a base id plus 48 for T[N], 96 for T[<=N] and
# 144 for T[]; the base ids robomodel has codecs for, as rosbags names the base types.
_BASE_TYPES = {
    2: "int8", 3: "uint8", 4: "int16", 5: "uint16", 6: "int32", 7: "uint32", 8: "int64",
    9: "uint64", 10: "float32", 11: "float64", 15: "bool", 16: "byte", 17: "string",
    21: "string",
}  # fmt: skip
_NESTED = 1
_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4  # rosbags' Nodetype values


def _field_desc(where: str, kind: tdi.FieldType) -> Any:
    """rosbags' ``(node type, details)`` of one described field."""
    offset, base = divmod(int(kind.type_id), 48)
    if base == _NESTED:
        if not kind.nested_type_name:
            raise MessageTypeError(f"{where}: a nested field without a type name")
        item: Any = (_NAME, kind.nested_type_name)
    elif base in _BASE_TYPES and offset <= 3:
        item = (_BASE, (_BASE_TYPES[base], int(kind.string_capacity) if base == 21 else 0))
    else:
        raise MessageTypeError(f"{where}: robomodel has no codec for field type id {kind.type_id}")
    if offset == 0:
        return item
    if offset == 1:
        return (_ARRAY, (item, int(kind.capacity)))
    return (_SEQUENCE, (item, int(kind.capacity) if offset == 2 else 0))


def fielddefs_of(description: tdi.TypeDescription) -> dict[str, FieldDef]:
    """rosbags-style definitions of the described type and of every type it references."""
    found: dict[str, FieldDef] = {}
    for individual in (description.type_description, *description.referenced_type_descriptions):
        name = individual.type_name
        fields = [(f.name, _field_desc(f"{name}.{f.name}", f.type)) for f in individual.fields]
        found[name] = ((), fields)
    return found


def _ask(context: Context, endpoint: Endpoint, timeout_s: float) -> tdi.TypeDescription | None:
    """The description ``endpoint``'s node gives of its type, if it matches the token's hash."""
    from robomodel.runtime.msg.types import type_description_interfaces as tdi
    from robomodel.runtime.type_descriptions import description_hash

    service = f"{endpoint.node.rstrip('/')}/get_type_description"
    request = tdi.GetTypeDescription_Request(endpoint.type_name, endpoint.type_hash, False)
    try:
        answer = context.call_service(service, tdi.GetTypeDescription, request, timeout_s)
    except RobomodelError as exc:
        log.debug("%s: %s", service, exc)
        return None
    description: tdi.TypeDescription = answer.type_description
    if not answer.successful:
        log.warning("%r: %r", service, answer.failure_reason)
        return None
    if description_hash(description) != endpoint.type_hash:
        log.warning("%r described %r with fields that do not hash to %s", service,
                    endpoint.type_name, endpoint.type_hash)  # fmt: skip
        return None
    if description.type_description.type_name != endpoint.type_name:
        return None
    return description


def learn_topic_type(
    context: Context,
    topic: str,
    publishers: list[Endpoint] | None = None,
    *,
    timeout_s: float = 5.0,
) -> bool:
    """Learn ``topic``'s type from its publishers (their definition on ROS 1, their node's type
    description on ROS 2), so that :func:`~robomodel.runtime.msg.get_message_type` finds it;
    False if no publisher tells it."""
    if getattr(context, "bus", "") == "ros1":
        from robomodel.runtime.transport.ros1.definition_probe import learn_topic_type as probe

        return probe(context.transport, topic)
    graph = context.graph(timeout_s=1.0)
    if publishers is None:
        info = graph.topics.get(topic)
        publishers = list(info.publishers) if info is not None else []
    from robomodel.runtime.msg._resolver import learn_fielddefs

    for endpoint in publishers:
        if not endpoint.type_hash.startswith("RIHS01_"):
            continue  # Humble's wire has no hashes, and no node answers for one
        if f"{endpoint.node.rstrip('/')}/get_type_description" not in graph.services:
            continue  # a peer without the service (rcl's can be turned off): no timeout
        description = _ask(context, endpoint, timeout_s)
        if description is not None:
            learn_fielddefs(fielddefs_of(description))
            return True
    return False
