"""``robomodel router``: a Zenoh router for the ROS 2 graph, as ``ros2 run rmw_zenoh_cpp rmw_zenohd``.

On one machine no router command is needed: when a robomodel process finds no router, it starts
a detached ``robomodel router --idle-exit 60`` on ``tcp/localhost:7447`` (like ``ros2 daemon``),
which serves every later process and ends a minute after the last session left. Across
machines, run one router that the others reach::

    robomodel router --listen tcp/[::]:7447          # on the robot (rmw_zenohd's endpoint)
    robomodel view ... --connect tcp/robot:7447 --listen tcp/MY_ADDRESS:0   # elsewhere

By default it listens on ``tcp/localhost:7447`` only; ``ZENOH_ROUTER_CONFIG_URI`` and
``ZENOH_CONFIG_OVERRIDE`` apply as they do to ``rmw_zenohd``. It runs until Ctrl-C or SIGTERM
(or ``--idle-exit``); ``robomodel router --stop`` ends the one robomodel runs on the endpoint
(to give way to ``rmw_zenohd``).
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import time
from typing import Any

from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError

__all__ = ["register"]

_DEFAULT = "tcp/localhost:7447"
TRIM_PERIOD_S = 5.0
"""How often the router returns freed memory to the system (see ``release_freed_memory``)."""


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("router", help=verb_help("router"))
    parser.add_argument(
        "--listen",
        action="append",
        default=[],
        metavar="ENDPOINT",
        help="listen here instead of tcp/localhost:7447 (repeatable), e.g. tcp/[::]:7447",
    )
    parser.add_argument("--duration", type=float, default=None, help="stop after S seconds")
    parser.add_argument(
        "--idle-exit",
        type=float,
        default=None,
        metavar="S",
        help="stop once no Zenoh session has been linked to it for S seconds",
    )
    parser.add_argument(
        "--stop",
        action="store_true",
        help="end the router robomodel runs on the (first) --listen endpoint, and exit",
    )
    parser.set_defaults(func=run)


def _stop(endpoint: str) -> int:
    from robomodel.runtime.transport._zenoh_router import stop_router

    record = stop_router(endpoint)
    if record is None:
        print(f"no robomodel router is running on {endpoint}", file=sys.stderr)
    else:
        print(f"stopped the Zenoh router {record.zid} (pid {record.pid})", file=sys.stderr)
    return 0


def _linked(session: Any) -> bool:
    info = session.info
    return bool(list(info.peers_zid()) or list(info.routers_zid()))


def run(args: argparse.Namespace) -> int:
    if args.stop:
        return _stop(args.listen[0] if args.listen else _DEFAULT)
    from robomodel.runtime.transport._zenoh_common import import_zenoh, release_freed_memory
    from robomodel.runtime.transport._zenoh_router import RouterRecord
    from robomodel.runtime.transport._zenoh_session import router_config

    zenoh = import_zenoh()
    conf = router_config(args.listen)
    try:
        session = zenoh.open(conf)
    except Exception as exc:
        raise RobomodelError(
            f"cannot start the router: {exc} (is another router, rmw_zenohd or robomodel's, "
            "already listening there? `robomodel router --stop` ends robomodel's)"
        ) from None
    endpoints = tuple(args.listen) or (_DEFAULT,)
    record = RouterRecord(os.getpid(), str(session.zid()), endpoints)
    record.write()
    stopped: list[bool] = []  # a flag, not an Event: a second SIGTERM must not wait on a lock
    previous = signal.signal(signal.SIGTERM, lambda *_: stopped.append(True))
    print(
        f"Started Zenoh router with id {session.zid()}; listening on "
        f"{', '.join(endpoints)}; Ctrl-C stops",
        file=sys.stderr,
        flush=True,
    )
    end = None if args.duration is None else time.monotonic() + args.duration
    last_used = time.monotonic()
    next_trim = time.monotonic() + TRIM_PERIOD_S
    try:
        while not stopped and (end is None or time.monotonic() < end):
            time.sleep(0.1)
            if time.monotonic() >= next_trim:  # what peers' tokens took goes back when they go
                release_freed_memory()
                next_trim = time.monotonic() + TRIM_PERIOD_S
            if args.idle_exit is None:
                continue
            if _linked(session):
                last_used = time.monotonic()
            elif time.monotonic() - last_used > args.idle_exit:
                print(f"no session for {args.idle_exit:g} s; stopping", file=sys.stderr)
                break
    except KeyboardInterrupt:
        pass
    finally:
        signal.signal(signal.SIGTERM, previous)
        record.remove()
        session.close()
    return 0
