"""``robomodel node``: the nodes of the graph and what each offers (``ros2 node list|info``),
robomodel's and real ROS 2 ones alike (both read rmw_zenoh's liveliness tokens)."""

from __future__ import annotations

import argparse
from typing import Any

from robomodel._escape import escape_name, escape_names
from robomodel.cli._bus import (
    add_bus_arguments,
    context_from_args,
    hides,
    listing_exit_code,
    settled_graph,
)
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError, close_matches
from robomodel.runtime.transport.base import Graph

__all__ = ["node_info", "register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("node", help=verb_help("node"))
    verbs = parser.add_subparsers(dest="node_verb", metavar="VERB")
    verbs.required = True
    p = verbs.add_parser("list", help="the nodes of the graph")
    p.add_argument(
        "-a",
        "--all",
        action="store_true",
        help="also hidden nodes (a name starting with _), as ros2 node list --all",
    )
    add_bus_arguments(p)
    p.set_defaults(func=_run_list)
    p = verbs.add_parser("info", help="a node's publishers, subscribers, services and clients")
    p.add_argument("node", help="fully qualified name, e.g. /robot_state_publisher")
    add_bus_arguments(p)
    p.set_defaults(func=_run_info)


def _run_list(args: argparse.Namespace) -> int:
    with context_from_args(args) as context:
        graph = settled_graph(context)
        for name in sorted(graph.nodes):
            if not hides(context, name, args.all):
                print(escape_name(name))
    return listing_exit_code(graph)


def node_info(graph: Graph, node: str) -> str:
    """``ros2 node info``'s text for ``node``, names from peers escaped (``escape_name``)."""
    sections: dict[str, list[str]] = {
        "Subscribers": [],
        "Publishers": [],
        "Service Servers": [],
        "Service Clients": [],
    }
    for name, topic in sorted(graph.topics.items()):
        for title, endpoints in (
            ("Subscribers", topic.subscribers),
            ("Publishers", topic.publishers),
        ):
            for endpoint in endpoints:
                if endpoint.node == node:
                    sections[title].append(_entry(name, endpoint.type_name))
    for name, service in sorted(graph.services.items()):
        for title, endpoints in (
            ("Service Servers", service.servers),
            ("Service Clients", service.clients),
        ):
            for endpoint in endpoints:
                if endpoint.node == node:
                    sections[title].append(_entry(name, endpoint.type_name))
    lines = [escape_name(node)]
    for title, entries in sections.items():
        lines.append(f"  {title}:")
        lines.extend(f"    {entry}" for entry in sorted(set(entries)))
    return "\n".join(lines)


def _entry(name: str, type_name: str) -> str:
    return f"{escape_name(name)}: {escape_name(type_name)}"


def _run_info(args: argparse.Namespace) -> int:
    node = "/" + args.node.lstrip("/")
    with context_from_args(args) as context:
        graph = settled_graph(context)
    if node not in graph.nodes:
        hint = close_matches(node, graph.nodes)
        extra = f"; did you mean {escape_names(hint)}?" if hint else ""
        raise RobomodelError(
            f"Unable to find node '{escape_name(node)}'{extra} "
            f"(nodes: {escape_names(sorted(graph.nodes)) or 'none'})"
        )
    print(node_info(graph, node))
    return listing_exit_code(graph)
