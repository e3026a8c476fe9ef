"""The ROS graph from rmw_zenoh's liveliness tokens: robomodel's nodes and real ROS 2 ones.

A query of ``@ros2_lv/<domain>/**`` returns every live token of the domain (rmw_zenoh's
context does the same ``liveliness_get`` when it starts, then follows changes). Tokens that
``Entity::make`` would refuse are skipped; at most ``MAX_TOKENS`` are read, so a peer that
declares millions cannot exhaust memory.
"""

from __future__ import annotations

from typing import Any

from robomodel.runtime.msg.typehash import ros_type_name
from robomodel.runtime.qos import QoSProfile
from robomodel.runtime.transport.base import Endpoint, Graph
from robomodel.runtime.transport.rmw_zenoh import (
    ADMIN_SPACE,
    EntityKind,
    EntityToken,
    qos_from_key,
)

__all__ = ["MAX_TOKENS", "read_graph"]

MAX_TOKENS = 100_000
_KINDS = {
    EntityKind.PUBLISHER: "pub",
    EntityKind.SUBSCRIPTION: "sub",
    EntityKind.SERVICE: "srv",
    EntityKind.CLIENT: "cli",
}


def add_token(graph: Graph, token: EntityToken) -> None:
    """Record one entity in ``graph``."""
    if token.kind is EntityKind.NODE:
        graph.nodes.add(token.node)
        return
    type_name = ros_type_name(token.dds_type) or token.dds_type
    qos = qos_from_key(token.qos)
    endpoint = Endpoint(token.node, token.name, type_name, qos or QoSProfile(), token.type_hash)
    graph.add(_KINDS[token.kind], endpoint)


def read_graph(session: Any, domain_id: int, timeout_s: float) -> Graph:
    """The graph of domain ``domain_id`` as the tokens answering within ``timeout_s`` say."""
    graph = Graph()
    replies = session.liveliness().get(f"{ADMIN_SPACE}/{domain_id}/**", timeout=timeout_s)
    for count, reply in enumerate(replies):
        if count >= MAX_TOKENS:
            break
        sample = reply.ok
        if sample is None:
            continue
        token = EntityToken.parse(str(sample.key_expr))
        if token is not None and token.domain_id == domain_id:
            add_token(graph, token)
    return graph
