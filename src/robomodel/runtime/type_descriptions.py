"""A node's ``~/get_type_description`` (REP-2011), and types learned from a peer's answer.

Serving follows rcl (ros2/rcl ``rcl/src/rcl/node.c``
``rcl_node_type_description_service_handle_request`` and ``node_type_cache.c``): every type
that the node's publishers, subscriptions, services and clients use is in the node's type cache;
a request is looked up by its RIHS01 hash alone (``rosidl_parse_type_hash_string``, the name is
not consulted) and answered with the type's ``TypeDescription`` and, when
``include_type_sources`` is set, its ``TypeSource`` list; otherwise ``successful`` is false with
rcl's reason.

The description is the one the hash is computed from (:func:`typehash.type_description`, the
same fields and field type ids as ``rosidl_generator_type_description``), with empty
``default_value`` strings: robomodel keeps no ``.msg`` default values. The sources follow
rosidl_generator_c's ``full__description.c.em``: the type first, then each referenced type in
the description's order; a service's request, response and event are ``implicit`` without
text; a type read from a ``.msg``/``.srv`` file on the package path has that file's text; other
types (robomodel's own classes, rosbags' stores) have no file here, so their ``.msg`` text is
written from their constants and fields (encoding ``msg``, without comments: the
:class:`~robomodel.runtime.msg.spec.MessageSpec`'s ``msg``).

A peer's answer is read back by :mod:`robomodel.runtime.type_learning`.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg.schema import Message, Service
from robomodel.runtime.msg.spec import MessageSpec, rihs01_of, spec_of
from robomodel.runtime.msg.typehash import type_description, type_hash
from robomodel.runtime.msg.types import type_description_interfaces as tdi

if TYPE_CHECKING:
    from robomodel.runtime.node import Node, ServiceServer

__all__ = [
    "TypeDescriptionService",
    "describe",
    "description_hash",
    "type_sources",
]

log = logging.getLogger("robomodel.runtime")
_HEX = re.compile(r"[0-9a-fA-F]{64}")
Kind = type[Message] | type[Service]


def describe(kind: Kind) -> tdi.TypeDescription:
    """The ``TypeDescription`` message of a message or service type."""

    def individual(data: dict[str, Any]) -> tdi.IndividualTypeDescription:
        fields = [tdi.Field(f["name"], tdi.FieldType(**f["type"])) for f in data["fields"]]
        return tdi.IndividualTypeDescription(data["type_name"], fields)

    data = type_description(kind)
    return tdi.TypeDescription(
        individual(data["type_description"]),
        [individual(d) for d in data["referenced_type_descriptions"]],
    )


def description_hash(description: tdi.TypeDescription) -> str:
    """RIHS01 of a received description, as REP-2011 defines it (default values left out)."""

    def individual(d: tdi.IndividualTypeDescription) -> dict[str, Any]:
        return {
            "type_name": d.type_name,
            "fields": [
                {
                    "name": f.name,
                    "type": {
                        "type_id": f.type.type_id,
                        "capacity": f.type.capacity,
                        "string_capacity": f.type.string_capacity,
                        "nested_type_name": f.type.nested_type_name,
                    },
                }
                for f in d.fields
            ],
        }

    data = {
        "type_description": individual(description.type_description),
        "referenced_type_descriptions": [
            individual(d) for d in description.referenced_type_descriptions
        ],
    }
    return rihs01_of(data)


def _specs(kind: Kind) -> dict[str, MessageSpec]:
    """The spec of every message type ``kind`` uses, by type name."""
    tops = [kind.Request, kind.Response] if issubclass(kind, Service) else [kind]
    found: dict[str, MessageSpec] = {}
    for top in tops:
        spec = spec_of(top)
        for part in (spec, *spec.nested):
            found.setdefault(part.name, part)
    return found


def _source(name: str, kind: Kind, specs: dict[str, MessageSpec]) -> tdi.TypeSource:
    from robomodel.runtime.msg._resolver import package_source

    service = kind.__typename__ if issubclass(kind, Service) else None
    if service is not None and name in (f"{service}_{p}" for p in ("Request", "Response", "Event")):
        return tdi.TypeSource(name, "implicit", "")
    path = package_source(name)
    if path is not None:
        return tdi.TypeSource(name, path.suffix.lstrip("."), path.read_text())
    if name == service:
        halves = (spec_of(kind.Request).msg, spec_of(kind.Response).msg)  # type: ignore[union-attr]
        return tdi.TypeSource(name, "srv", "---\n".join(halves))
    found = specs.get(name)
    return tdi.TypeSource(name, "msg", found.msg if found is not None else "")


def type_sources(kind: Kind, description: tdi.TypeDescription) -> list[tdi.TypeSource]:
    """The ``TypeSource`` of the type and of each type its description references."""
    specs = _specs(kind)
    names = [description.type_description.type_name]
    names += [d.type_name for d in description.referenced_type_descriptions]
    return [_source(name, kind, specs) for name in names]


def _parse_hash(text: str) -> bytes | None:
    """rosidl_parse_type_hash_string: ``RIHS``, version 01 in hex, 32 bytes in hex."""
    if len(text) < 7 or not text.startswith("RIHS") or text[4:6].lower() != "01":
        return None
    if len(text) != 7 + 64 or _HEX.fullmatch(text, 7) is None:
        return None
    return bytes.fromhex(text[7:])


class TypeDescriptionService:
    """One node's type cache and its ``~/get_type_description`` service."""

    def __init__(self, node: Node) -> None:
        # how many of the node's entities use each type (rcl's num_registrations)
        self._kinds: dict[Kind, int] = {tdi.GetTypeDescription: 1}
        self.server: ServiceServer | None = None
        try:
            self.server = node.create_service(
                tdi.GetTypeDescription, "~/get_type_description", self._handle
            )
        except RobomodelError:  # a second node of this name in this process: the first answers
            log.debug("%s: ~/get_type_description is offered by another node of this name",
                      node.fully_qualified_name)  # fmt: skip

    def register(self, kind: Kind) -> Callable[[], None]:
        """A publisher, subscription, service or client of the node uses ``kind``; the call
        returned says it no longer does (``rcl_node_type_cache_unregister_type``)."""
        self._kinds[kind] = self._kinds.get(kind, 0) + 1

        def unregister() -> None:
            left = self._kinds.get(kind, 0) - 1
            if left > 0:
                self._kinds[kind] = left
            else:
                self._kinds.pop(kind, None)

        return unregister

    def _find(self, wanted: bytes) -> Kind | None:
        for kind in tuple(self._kinds):  # a thread may be adding one
            if bytes.fromhex(type_hash(kind)[7:]) == wanted:
                return kind
        return None

    def _handle(self, request: tdi.GetTypeDescription_Request) -> tdi.GetTypeDescription_Response:
        response = tdi.GetTypeDescription_Response()
        wanted = _parse_hash(request.type_hash)
        if wanted is None:
            response.failure_reason = "Failed to parse type hash"
            return response
        kind = self._find(wanted)
        if kind is None:
            response.failure_reason = "Type not currently in use by this node"
            return response
        response.type_description = describe(kind)
        if request.include_type_sources:
            response.type_sources = type_sources(kind, response.type_description)
        response.successful = True
        return response
