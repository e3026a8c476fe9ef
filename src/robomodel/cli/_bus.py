"""Bus options shared by the verbs that talk to other processes."""

from __future__ import annotations

import argparse
import os
import sys
import time

from robomodel.errors import RobomodelError
from robomodel.runtime import BUSES, Context
from robomodel.runtime.clock import Clock
from robomodel.runtime.transport.base import Graph

__all__ = [
    "add_bus_arguments",
    "bus_from_args",
    "context_from_args",
    "domain_id_arg",
    "hides",
    "listing_exit_code",
    "settled_graph",
    "wait_for_peers",
]


def domain_id_arg(text: str) -> int:
    """``--domain-id``, read as rcl reads ``ROS_DOMAIN_ID`` (so ``0x2a`` is 42)."""
    from robomodel.runtime.transport._domain_id import DomainIdError, parse_domain_id

    try:
        value = parse_domain_id(text, variable="--domain-id")
    except DomainIdError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    if value is None:
        raise argparse.ArgumentTypeError("--domain-id needs a number, e.g. 42")
    return value


def add_bus_arguments(parser: argparse.ArgumentParser, *, default: str | None = None) -> None:
    group = parser.add_argument_group("bus")
    said = default or "ros1 when ROS_MASTER_URI is set, else zenoh"
    group.add_argument("--bus", choices=BUSES, default=default, help=f"transport (default: {said})")
    group.add_argument(
        "--master",
        default=None,
        metavar="URI",
        help="the ROS 1 master (--bus ros1; default ROS_MASTER_URI, else http://localhost:11311/)",
    )
    group.add_argument(
        "--domain-id",
        type=domain_id_arg,
        default=None,
        help="keep groups of processes apart (default: ROS_DOMAIN_ID as rcl reads it, else ROBOMODEL_DOMAIN_ID, else 0)",
    )
    group.add_argument(
        "--connect",
        action="append",
        default=[],
        metavar="ENDPOINT",
        help="also connect to a Zenoh router or peer elsewhere, e.g. tcp/192.168.1.5:7447",
    )
    group.add_argument(
        "--listen",
        action="append",
        default=[],
        metavar="ENDPOINT",
        help="also accept connections on this Zenoh endpoint, e.g. tcp/0.0.0.0:7447",
    )


def bus_from_args(args: argparse.Namespace) -> str:
    """The bus asked for; by default ros1 when a ROS 1 master is named (``--master`` or
    ``ROS_MASTER_URI``), as ROS 1 tools find theirs, else zenoh."""
    if args.bus:
        return str(args.bus)
    master = getattr(args, "master", None) or os.environ.get("ROS_MASTER_URI")
    return "ros1" if master else "zenoh"


def context_from_args(
    args: argparse.Namespace, clock: Clock | None = None, *, announce: str | None = None
) -> Context:
    """The context the bus options name. ``announce`` (a long-running verb's name) prints the
    graph it joined on stderr: master, domain and router are shared machine-wide by default,
    and a user on a shared machine must see which one their command is in."""
    bus = bus_from_args(args)
    if bus == "ros1":
        context = Context("ros1", clock=clock, master=getattr(args, "master", None))
    else:
        context = Context(
            bus, clock=clock, domain_id=args.domain_id, connect=args.connect, listen=args.listen
        )
    if announce is not None:
        print(f"{announce}: {context.transport.describe()}", file=sys.stderr, flush=True)
    return context


def wait_for_peers(context: Context, timeout_s: float = 1.0) -> bool:
    """Give a fresh Zenoh session a moment to link up with the others before querying.

    Returns whether another process was found (always True off Zenoh)."""
    if context.transport.name != "zenoh":
        return True
    session = getattr(context.transport, "session", None)
    deadline = time.monotonic() + timeout_s
    while session is not None and time.monotonic() < deadline:
        if list(session.info.peers_zid()) or list(session.info.routers_zid()):
            time.sleep(0.1)  # let liveliness tokens propagate over the new link
            return True
        time.sleep(0.02)
    return False


GRAPH_QUIET_S = 0.5
"""How long the Zenoh graph must have been without a change for a listing to be printed."""


def _shape(graph: Graph) -> tuple[object, ...]:
    topics = tuple(
        (name, tuple(sorted(info.types)), len(info.publishers), len(info.subscribers))
        for name, info in sorted(graph.topics.items())
    )
    return (tuple(sorted(graph.nodes)), topics, tuple(sorted(graph.services)))


def _readable(graph: Graph) -> Graph:
    """``graph``, or the error that it could not be read (a master answering garbage): a
    listing must not print an empty graph and exit 0 (exit 2, as every robomodel error)."""
    if graph.unreadable:
        raise RobomodelError(graph.unreadable)
    return graph


def settled_graph(context: Context, timeout_s: float = 3.0) -> Graph:
    """The bus graph once discovery has settled, as ``ros2 topic list`` spins before answering.

    A fresh session first links up with its peers (``wait_for_peers``), then the graph is
    queried until two answers in a row agree and are not empty, or ``timeout_s`` passes: a
    loaded machine can take a second to deliver every liveliness token, and printing the
    first, partial (or empty) answer made ``topic list`` miss a running simulator. On Zenoh the
    graph must also have been still for ``GRAPH_QUIET_S``: a peer with many tokens sends them
    some 0.1-0.3 s after the others (measured with 2,000), and two equal answers in between
    left all of them out.
    """
    if not wait_for_peers(context, timeout_s):
        return _readable(context.graph(timeout_s=0.5))  # nobody else on this domain
    deadline = time.monotonic() + timeout_s
    previous: tuple[object, ...] | None = None
    quiet_s = getattr(context.transport, "graph_quiet_s", None)
    while True:
        graph = _readable(context.graph(timeout_s=0.5))
        shape = _shape(graph)
        settled = quiet_s is None or quiet_s() >= min(GRAPH_QUIET_S, timeout_s / 2)
        if shape == previous and (graph.topics or graph.nodes) and settled:
            return graph
        if time.monotonic() >= deadline:
            return graph
        previous = shape
        time.sleep(0.15)


def listing_exit_code(graph: Graph) -> int:
    """0, or 1 with a line on stderr when ``graph`` is known to lack entities (a bound left
    some out, or the graph could not be read): such a listing must not look complete."""
    if graph.complete:
        return 0
    print(
        "warning: the graph could not be read completely; this listing lacks entries "
        "(see the warning above)",
        file=sys.stderr,
    )
    return 1


def hides(context: Context, name: str, include_hidden: bool) -> bool:
    """Whether a listing leaves ``name`` out: on ROS 2 buses a hidden name (a part starting
    with ``_``, e.g. ``/fib/_action/feedback``) unless asked for, as ``ros2 topic list`` and
    ``ros2 service list`` (rclpy's ``include_hidden_topics``); ROS 1's listings hide nothing."""
    if include_hidden or context.transport.name == "ros1":
        return False
    return any(part.startswith("_") for part in name.split("/"))
