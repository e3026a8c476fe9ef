"""One robomodel node as a ROS 1 node: its slave API (XML-RPC) and its TCPROS server, each on a
port of its own as a roscpp or rospy process has, and its publications, subscriptions and
services.

The slave API answers the master and other nodes (rospy's masterslave.py): ``requestTopic``,
``publisherUpdate``, ``paramUpdate``, ``getBusInfo``, ``getBusStats``, ``getPid``,
``getMasterUri``, ``getPublications``, ``getSubscriptions`` and ``shutdown`` (logged; a node of a
robomodel process ends with its process). The TCPROS server reads each new connection's header
without blocking on any peer (:mod:`.handshakes`) and hands it to the publication or service it
names.
"""

from __future__ import annotations

import os
import socket
from typing import Any

from robomodel.runtime.transport.ros1.handshakes import HandshakeServer
from robomodel.runtime.transport.ros1.names import advertised_host, http_uri
from robomodel.runtime.transport.ros1.publication import Publication
from robomodel.runtime.transport.ros1.services import ServiceServer
from robomodel.runtime.transport.ros1.subscription import Subscription
from robomodel.runtime.transport.ros1.tcpros import TcprosError, refuse
from robomodel.runtime.transport.ros1.xmlrpc_io import XmlRpcServer, log

__all__ = ["NodeEndpoint"]

Result = list[Any]


class NodeEndpoint:
    """The ROS 1 face of node ``caller_id`` (``/ns/name``)."""

    def __init__(self, caller_id: str, master_uri: str, bind: str) -> None:
        self.caller_id = caller_id
        self.master_uri = master_uri
        self.host = advertised_host()
        self.publications: dict[str, Publication] = {}
        self.subscriptions: dict[str, list[Subscription]] = {}
        self.services: dict[str, ServiceServer] = {}
        self._listener = socket.create_server(
            (bind, 0),
            family=socket.AF_INET6 if ":" in bind else socket.AF_INET,
            backlog=128,
            dualstack_ipv6=bind == "::",
        )
        self.tcpros_port = int(self._listener.getsockname()[1])
        self._handshakes = HandshakeServer(self._listener, self._serve, caller_id)
        self._xmlrpc = XmlRpcServer(bind, 0, self._api())
        self.uri = http_uri(self.host, self._xmlrpc.port)

    # -- TCPROS ---------------------------------------------------------------------------------
    def _serve(self, sock: socket.socket, header: dict[str, str], address: Any) -> None:
        """A connection whose header is in (on a thread of its own)."""
        try:
            if "service" in header:
                self._serve_service(sock, header)
            elif "topic" in header:
                self._serve_topic(sock, header)
            else:
                refuse(sock, "header has neither 'topic' nor 'service'")
        except (OSError, TcprosError) as exc:
            log.warning(
                "%s: dropping a TCPROS connection from %s: %s", self.caller_id, address, exc
            )
            sock.close()

    def _serve_topic(self, sock: socket.socket, header: dict[str, str]) -> None:
        publication = self.publications.get(header["topic"])
        if publication is None:
            refuse(sock, f"{self.caller_id} does not publish {header['topic']}")
            return
        sock.settimeout(None)
        publication.accept(sock, header)

    def _serve_service(self, sock: socket.socket, header: dict[str, str]) -> None:
        server = self.services.get(header["service"])
        if server is None:
            refuse(sock, f"{self.caller_id} does not offer {header['service']}")
        else:
            server.serve(sock, header)

    # -- the slave API --------------------------------------------------------------------------
    def _api(self) -> dict[str, Any]:
        return {
            "getBusStats": lambda caller_id: [1, "", [[], [], []]],
            "getBusInfo": self.get_bus_info,
            "getMasterUri": lambda caller_id: [1, "", self.master_uri],
            "shutdown": self.shutdown_request,
            "getPid": lambda caller_id: [1, "", os.getpid()],
            "getSubscriptions": lambda caller_id: [1, "subscriptions", self._subscribed()],
            "getPublications": lambda caller_id: [1, "publications", self._published()],
            "paramUpdate": lambda caller_id, key, value: [1, "", 0],
            "publisherUpdate": self.publisher_update,
            "requestTopic": self.request_topic,
        }

    def _published(self) -> list[list[str]]:
        return [[t, p.kind.name] for t, p in sorted(self.publications.items())]

    def _subscribed(self) -> list[list[str]]:
        return [[t, subs[0].kind.name] for t, subs in sorted(self.subscriptions.items()) if subs]

    def request_topic(self, caller_id: str, topic: str, protocols: Any) -> Result:
        if topic not in self.publications:
            return [-1, f"Not a publisher of [{topic}]", []]
        offered = (
            [p[0] for p in protocols if isinstance(p, list) and p]
            if isinstance(protocols, list)
            else []
        )
        if "TCPROS" not in offered:
            return [0, "no supported protocol implementations", []]
        return [
            1,
            f"ready on {self.host}:{self.tcpros_port}",
            ["TCPROS", self.host, self.tcpros_port],
        ]

    def publisher_update(self, caller_id: str, topic: str, publishers: Any) -> Result:
        if not isinstance(publishers, list):
            return [-1, "publishers must be a list of URIs", 0]
        for subscription in self.subscriptions.get(topic, []):
            subscription.update_publishers([str(p) for p in publishers])
        return [1, "", 0]

    def get_bus_info(self, caller_id: str) -> Result:
        info: list[list[Any]] = []
        for topic, publication in sorted(self.publications.items()):
            for c in list(publication.connections):
                info.append(
                    [
                        c.id,
                        c.peer,
                        "o",
                        "TCPROS",
                        topic,
                        True,
                        f"TCPROS connection on port {self.tcpros_port} to [{c.peer}]",
                    ]
                )
        for topic, subscriptions in sorted(self.subscriptions.items()):
            for subscription in subscriptions:
                for n, inbound in enumerate(list(subscription.inbound.values())):
                    info.append(
                        [
                            n + 1,
                            inbound.uri,
                            "i",
                            "TCPROS",
                            topic,
                            inbound.connected,
                            f"TCPROS connection to [{inbound.peer}]",
                        ]
                    )
        return [1, "bus info", info]

    def shutdown_request(self, caller_id: str, msg: str = "") -> Result:
        log.warning(
            "%s: %s asked it to shut down (%s); it ends with its process",
            self.caller_id,
            caller_id,
            msg,
        )
        return [1, "shutdown", 0]

    def close(self) -> None:
        self._handshakes.close()
        self._xmlrpc.close()
        self._listener.close()
        for publication in self.publications.values():
            publication.close()
        for subscriptions in self.subscriptions.values():
            for subscription in subscriptions:
                subscription.close()
