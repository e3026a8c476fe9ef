"""``rclpy.topic_endpoint_info``: a publisher or subscription as the graph shows it
(``Node.get_publishers_info_by_topic``)."""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.qos import QoSProfile

__all__ = ["TopicEndpointInfo", "TopicEndpointTypeEnum"]


class TopicEndpointTypeEnum(enum.IntEnum):
    INVALID = 0
    PUBLISHER = 1
    SUBSCRIPTION = 2


class TopicEndpointInfo:
    """One endpoint of a topic: its node, type and QoS (the GID is not known: all zeros)."""

    def __init__(
        self,
        *,
        node_name: str = "",
        node_namespace: str = "",
        topic_type: str = "",
        topic_type_hash: str = "",
        endpoint_type: TopicEndpointTypeEnum = TopicEndpointTypeEnum.INVALID,
        endpoint_gid: list[int] | None = None,
        qos_profile: QoSProfile | None = None,
    ) -> None:
        self.node_name = node_name
        self.node_namespace = node_namespace
        self.topic_type = topic_type
        self.topic_type_hash = topic_type_hash
        self.endpoint_type = endpoint_type
        self.endpoint_gid = endpoint_gid or [0] * 16
        self.qos_profile = qos_profile

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, TopicEndpointInfo):
            return NotImplemented
        return vars(self) == vars(other)

    def __str__(self) -> str:
        return "\n".join([
            f"Node name: {self.node_name}",
            f"Node namespace: {self.node_namespace}",
            f"Topic type: {self.topic_type}",
            f"Topic type hash: {self.topic_type_hash}",
            f"Endpoint type: {self.endpoint_type.name}",
            f"QoS profile: {self.qos_profile!r}",
        ])  # fmt: skip
