"""Bus options shared by the verbs that talk to other processes."""

from __future__ import annotations

import argparse
import time

from robomodel.runtime import BUSES, Context

__all__ = ["add_bus_arguments", "context_from_args", "wait_for_peers"]


def add_bus_arguments(parser: argparse.ArgumentParser, *, default: str = "zenoh") -> None:
    group = parser.add_argument_group("bus")
    group.add_argument(
        "--bus", choices=BUSES, default=default, help=f"transport (default: {default})"
    )
    group.add_argument(
        "--domain-id",
        type=int,
        default=None,
        help="keep groups of processes apart (default: ROBOMODEL_DOMAIN_ID or ROS_DOMAIN_ID or 0)",
    )
    group.add_argument(
        "--connect",
        action="append",
        default=[],
        metavar="ENDPOINT",
        help="also connect to a Zenoh endpoint on another machine, e.g. tcp/192.168.1.5:7447",
    )
    group.add_argument(
        "--listen",
        action="append",
        default=[],
        metavar="ENDPOINT",
        help="also accept connections on this Zenoh endpoint, e.g. tcp/0.0.0.0:7447",
    )


def context_from_args(args: argparse.Namespace) -> Context:
    return Context(args.bus, domain_id=args.domain_id, connect=args.connect, listen=args.listen)


def wait_for_peers(context: Context, timeout_s: float = 1.0) -> None:
    """Give a fresh Zenoh session a moment to link up with the others before querying."""
    if context.transport.name != "zenoh":
        return
    session = getattr(context.transport, "session", None)
    deadline = time.monotonic() + timeout_s
    while session is not None and time.monotonic() < deadline:
        if list(session.info.peers_zid()):
            time.sleep(0.1)  # let liveliness tokens propagate over the new link
            return
        time.sleep(0.02)
