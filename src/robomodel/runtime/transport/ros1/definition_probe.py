"""A ROS 1 topic's full message definition, asked of one of its publishers.

Every TCPROS publisher sends its type's ``message_definition`` (the ``.msg`` text followed by
each type it uses after ``===`` / ``MSG: pkg/Name`` lines) in its connection header. A
subscriber that offers ``md5sum: *`` and ``type: *`` is accepted by any publisher (rospy's
and roscpp's wildcard, as ``rostopic echo`` uses it before it knows the type), so robomodel
can learn a type no package or store it knows has, and decode it (see
:func:`robomodel.runtime.msg._resolver.learn_definition`).
"""

from __future__ import annotations

import contextlib
import socket
from dataclasses import dataclass

from robomodel.runtime.transport.ros1.tcpros import read_header, write_header
from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError, call

__all__ = ["PublishedDefinition", "probe_definition"]


@dataclass(frozen=True, slots=True)
class PublishedDefinition:
    """What a publisher says of its topic's type."""

    type_name: str  # "my_msgs/Reading"
    md5sum: str
    definition: str
    publisher: str  # its caller id


def _publisher_uris(master_uri: str, caller_id: str, topic: str) -> list[str]:
    publishers, _, _ = call(master_uri, "getSystemState", caller_id)
    nodes: list[str] = next((n for name, n in publishers if name == topic), [])
    uris = []
    for node in nodes:
        with contextlib.suppress(Ros1WireError):
            uris.append(str(call(master_uri, "lookupNode", caller_id, node)))
    return uris


def probe_definition(
    master_uri: str, caller_id: str, topic: str, *, timeout_s: float = 5.0
) -> PublishedDefinition | None:
    """The definition the first answering publisher of ``topic`` sends; None if none does."""
    for uri in _publisher_uris(master_uri, caller_id, topic):
        try:
            answer = call(uri, "requestTopic", caller_id, topic, [["TCPROS"]], timeout_s=timeout_s)
            host, port = str(answer[1]), int(answer[2])
            with socket.create_connection((host, port), timeout=timeout_s) as sock:
                write_header(
                    sock,
                    {"callerid": caller_id, "md5sum": "*", "topic": topic, "type": "*"},
                )
                header = read_header(sock)
        except (Ros1WireError, OSError, ValueError, IndexError, TypeError):
            continue
        if "message_definition" in header and "type" in header:
            return PublishedDefinition(
                header["type"],
                header.get("md5sum", ""),
                header["message_definition"],
                header.get("callerid", uri),
            )
    return None


def learn_topic_type(transport: object, topic: str) -> bool:
    """On the ROS 1 bus, learn ``topic``'s type from a publisher's definition (so that
    :func:`~robomodel.runtime.msg.get_message_type` finds it); False if not ROS 1 or nobody
    answers."""
    master_uri = getattr(transport, "master_uri", None)
    if not isinstance(master_uri, str):
        return False
    found = probe_definition(master_uri, "/robomodel_type_probe", topic)
    if found is None:
        return False
    from robomodel.runtime.msg._resolver import learn_definition

    learn_definition(found.type_name, found.definition)
    return True
